//! The gather-volume trait: a region that can report the area of a polygon inside it.
//! The cube ([`Aabb`]) and the [`Ball`] implement it; new volumes plug in the same way.

use crate::aabb::Aabb;
use crate::ball::{Ball, polygon_area_in_ball};
use crate::clip::ClipScratch;
use crate::clip::clip_into_scratch;
use crate::polygon::polygon_vector_area;
use glam::Vec3;

/// A closed region of space over which the geometry estimator spreads photon power.
///
/// Implement it for a new shape (an ellipsoid, a disc flattened along the normal) and the
/// estimators accept it unchanged: they find candidate polygons by [`GatherVolume::bounds`]
/// and weigh them by [`GatherVolume::polygon_area_inside`].
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

    /// Sutherland–Hodgman against the six faces, with two fast paths: a polygon whose bounds
    /// lie inside the box keeps its whole area, and one whose bounds or plane miss the box
    /// gets 0. Never NaN: a result that is not finite is reported as 0.
    fn polygon_area_inside(&self, polygon: &[Vec3], normal: Vec3, scratch: &mut ClipScratch) -> f32 {
        if polygon.len() < 3 {
            return 0.0;
        }
        let bounds = Aabb::from_points(polygon);
        if !bounds.overlaps(self) {
            return 0.0;
        }
        let area = if self.contains_point(bounds.min) && self.contains_point(bounds.max) {
            polygon_vector_area(polygon).length()
        } else {
            if plane_misses_box(polygon[0], normal, self) {
                return 0.0;
            }
            polygon_vector_area(clip_into_scratch(polygon, &bounds, self, scratch)).length()
        };
        if area.is_finite() { area } else { 0.0 }
    }
}

/// True when the plane through `point` with `normal` has every box corner strictly on one
/// side (a zero or non-finite normal never claims a miss).
fn plane_misses_box(point: Vec3, normal: Vec3, aabb: &Aabb) -> bool {
    let center_distance = normal.dot(aabb.center() - point);
    let reach = normal.abs().dot(aabb.size() * 0.5);
    // The margin covers the rounding of the dot products (conservative: near-misses clip).
    let scale = normal.abs().dot(aabb.center().abs() + point.abs()) + reach;
    center_distance.abs() > reach + 1e-5 * scale
}

impl GatherVolume for Ball {
    fn bounds(&self) -> Aabb {
        Aabb::cube(self.center, self.radius)
    }

    /// Exact polygon ∩ disc area, see [`polygon_area_in_ball`].
    fn polygon_area_inside(&self, polygon: &[Vec3], normal: Vec3, scratch: &mut ClipScratch) -> f32 {
        polygon_area_in_ball(polygon, normal, self, scratch)
    }
}
