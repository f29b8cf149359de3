//! Analytic shapes (sphere, ring) that rays intersect exactly, split into parts that each get
//! a photon map, with a fine polygonal proxy per part for the geometry-based estimators.

pub(crate) mod ring;
pub(crate) mod sphere;

pub use ring::{Ring, RingSide};
pub use sphere::Sphere;

use pm_geom::Aabb;

/// An analytic shape in a scene.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Shape {
    /// A sphere (one part).
    Sphere(Sphere),
    /// A thick washer (four parts: top, bottom, inner and outer side).
    Ring(Ring),
}

impl Shape {
    /// Number of parts (photon-map units) of the shape.
    pub fn part_count(&self) -> u32 {
        match self {
            Shape::Sphere(_) => 1,
            Shape::Ring(_) => 4,
        }
    }

    /// Bounds of the whole shape.
    pub fn bounds(&self) -> Aabb {
        match self {
            Shape::Sphere(s) => s.bounds(),
            Shape::Ring(r) => RingSide::ALL
                .iter()
                .fold(Aabb::EMPTY, |b, &side| b.union(r.side_bounds(side))),
        }
    }
}
