//! The gather-volume trait: a region that can report the area of a polygon inside it.
//! The cube ([`Aabb`]) and the [`Ball`] implement it; new volumes plug in the same way.

use crate::{Aabb, Ball, ClipScratch};
use glam::Vec3;

/// A closed region of space over which the geometry estimator spreads photon power.
pub trait GatherVolume {
    /// A box holding the volume, for finding candidate polygons.
    fn bounds(&self) -> Aabb;
    /// Area of the convex planar `polygon` inside the volume. `normal` is the polygon's unit
    /// normal (callers usually have it precomputed).
    fn polygon_area_inside(&self, polygon: &[Vec3], normal: Vec3, scratch: &mut ClipScratch) -> f32;
}

impl GatherVolume for Aabb {
    fn bounds(&self) -> Aabb {
        *self
    }
    fn polygon_area_inside(&self, polygon: &[Vec3], normal: Vec3, scratch: &mut ClipScratch) -> f32 {
        let _ = (polygon, normal, scratch);
        todo!("pm-geom issue")
    }
}

impl GatherVolume for Ball {
    fn bounds(&self) -> Aabb {
        Aabb::cube(self.center, self.radius)
    }
    fn polygon_area_inside(&self, polygon: &[Vec3], normal: Vec3, scratch: &mut ClipScratch) -> f32 {
        let _ = (polygon, normal, scratch);
        todo!("pm-geom issue")
    }
}
