//! Polygon helpers over `&[Vec3]` (vertices in order, planar): Newell's normal and area.

use glam::Vec3;

/// Newell's vector area: normal direction (right-handed, counter-clockwise vertices) with
/// length equal to the polygon's area. Robust for slightly non-planar polygons.
pub fn polygon_vector_area(polygon: &[Vec3]) -> Vec3 {
    let _ = polygon;
    todo!("pm-geom issue")
}

/// The polygon's area (0 for fewer than 3 vertices).
pub fn polygon_area(polygon: &[Vec3]) -> f32 {
    polygon_vector_area(polygon).length()
}

/// The unit normal (counter-clockwise vertices seen from its tip), `None` when degenerate.
pub fn polygon_normal(polygon: &[Vec3]) -> Option<Vec3> {
    polygon_vector_area(polygon).try_normalize()
}
