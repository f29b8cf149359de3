//! Analytic shape parts (spheres, ring sides) as ray-query primitives, searched apart from
//! the triangles.

use crate::part::PartSurface;
use crate::shape::ring::{Ring, RingSide};
use crate::shape::sphere::Sphere;
use glam::Vec3;

/// An analytic shape part (a sphere, or one side of a ring) as a ray-query primitive.
#[derive(Clone, Copy, Debug)]
pub(crate) enum ShapePrimitive {
    Sphere {
        sphere: Sphere,
        part: PartSurface,
    },
    RingSide {
        ring: Ring,
        side: RingSide,
        part: PartSurface,
    },
}

impl ShapePrimitive {
    pub(super) fn part(&self) -> PartSurface {
        match *self {
            ShapePrimitive::Sphere { part, .. } | ShapePrimitive::RingSide { part, .. } => part,
        }
    }

    pub(super) fn bounds(&self) -> pm_geom::Aabb {
        match self {
            ShapePrimitive::Sphere { sphere, .. } => sphere.bounds(),
            ShapePrimitive::RingSide { ring, side, .. } => ring.side_bounds(*side),
        }
    }

    /// Distance along the ray in `(t_min, t_max)`, or infinity.
    #[inline]
    pub(super) fn intersect(&self, origin: Vec3, direction: Vec3, t_min: f32, t_max: f32) -> f32 {
        match self {
            ShapePrimitive::Sphere { sphere, .. } => sphere.intersect(origin, direction, t_min, t_max),
            ShapePrimitive::RingSide { ring, side, .. } => {
                ring.intersect_side(*side, origin, direction, t_min, t_max)
            }
        }
    }

    pub(super) fn normal_at(&self, p: Vec3) -> Vec3 {
        match self {
            ShapePrimitive::Sphere { sphere, .. } => sphere.normal_at(p),
            ShapePrimitive::RingSide { ring, side, .. } => ring.side_normal(*side, p),
        }
    }
}
