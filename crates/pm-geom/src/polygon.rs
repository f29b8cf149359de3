//! Polygon helpers over `&[Vec3]` (vertices in order, planar): Newell's normal and area.

use glam::Vec3;

/// Newell's vector area: normal direction (right-handed, counter-clockwise vertices) with
/// length equal to the polygon's area. Robust for slightly non-planar polygons.
///
/// Computed as the fan sum `½ Σ (vᵢ − v₀) × (vᵢ₊₁ − v₀)`, which equals Newell's sum exactly
/// (the vector area of a closed loop does not depend on the origin) but subtracts `v₀`
/// first, so polygons far from the origin keep their precision. Fewer than 3 vertices give
/// [`Vec3::ZERO`].
pub fn polygon_vector_area(polygon: &[Vec3]) -> Vec3 {
    let [first, rest @ ..] = polygon else {
        return Vec3::ZERO;
    };
    if rest.len() < 2 {
        return Vec3::ZERO;
    }
    let mut sum = Vec3::ZERO;
    let mut prev = rest[0] - *first;
    for &v in &rest[1..] {
        let cur = v - *first;
        sum += prev.cross(cur);
        prev = cur;
    }
    sum * 0.5
}

/// The polygon's area (0 for fewer than 3 vertices).
pub fn polygon_area(polygon: &[Vec3]) -> f32 {
    polygon_vector_area(polygon).length()
}

/// The unit normal (counter-clockwise vertices seen from its tip), `None` when degenerate.
pub fn polygon_normal(polygon: &[Vec3]) -> Option<Vec3> {
    polygon_vector_area(polygon).try_normalize()
}
