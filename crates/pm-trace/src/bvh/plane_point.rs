//! A triangle hit moved onto the triangle's plane, with the magnitudes its rounding scales
//! with, and the rest of what a hit reads from the primitive it met.

use glam::Vec3;

use crate::part::PartSurface;

/// What a hit reads from the primitive it met ([`super::SceneBvh::hit_surface`]).
#[derive(Clone, Copy, Debug)]
pub(crate) struct HitSurface {
    /// The primitive's part and surface.
    pub part: PartSurface,
    /// The unit geometric normal (triangles: counter-clockwise winding).
    pub normal: Vec3,
    /// On a triangle, the hit moved onto its plane; `None` for shapes, and for triangles whose
    /// squared normal leaves f32's range.
    pub on_plane: Option<PlanePoint>,
}

/// The ray's point `o + t·d` written in a triangle's own coordinates, `v₀ + b₁ e₁ + b₂ e₂`
/// (its weights by projection along the face normal). However thin the triangle, this point
/// lies on its plane within a few units in the last place of [`PlanePoint::magnitude`] (where
/// it lies within the plane matters little), while `o + t·d` carries t's error, which a sliver
/// magnifies by up to [`PlanePoint::condition`].
#[derive(Clone, Copy, Debug)]
pub(crate) struct PlanePoint {
    /// The point.
    pub point: Vec3,
    /// The largest coordinate of `|v₀| + |b₁ e₁| + |b₂ e₂|`, which its rounding scales with.
    pub magnitude: f32,
    /// The triangle's condition, longest edge squared over twice the area: how much the
    /// watertight test's distance, and so `o + t·d`, may be off for a thin triangle.
    pub condition: f32,
}

impl PlanePoint {
    /// `on_ray` moved onto the plane of the triangle with corner `v0`, edges `e1`, `e2` and
    /// unnormalised normal `n = e1 × e2` (`length_squared = |n|²`).
    #[inline(always)]
    pub(crate) fn of(on_ray: Vec3, v0: Vec3, e1: Vec3, e2: Vec3, n: Vec3, length_squared: f32) -> Option<PlanePoint> {
        let inverse = 1.0 / length_squared;
        // |n|² overflows for edges past about 4·10⁹ m and underflows below about 10⁻¹⁰ m: the
        // ray's own point then (a zero inverse would put every hit on the first corner).
        if !(inverse.is_finite() && inverse > 0.0) {
            return None;
        }
        let q = on_ray - v0;
        let (b1, b2) = (q.cross(e2).dot(n) * inverse, e1.cross(q).dot(n) * inverse);
        let (p1, p2) = (e1 * b1, e2 * b2);
        let point = v0 + p1 + p2;
        let magnitude = (v0.abs() + p1.abs() + p2.abs()).max_element();
        let longest = e1
            .length_squared()
            .max(e2.length_squared())
            .max((e2 - e1).length_squared());
        let condition = longest * inverse.sqrt();
        (point.is_finite() && magnitude.is_finite() && condition.is_finite()).then_some(PlanePoint {
            point,
            magnitude,
            condition,
        })
    }
}
