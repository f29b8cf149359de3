//! The first hits of camera rays through the centres of a square grid of pixels, row by row:
//! the query points of the estimator benches.

use photon_maps::trace::{Hit, Ray, RayKind, Scene};

/// Each first hit of a camera ray through the centre of a pixel of a `grid` × `grid` image,
/// with its ray, in row order.
pub fn camera_hits(scene: &Scene, grid: u32) -> Vec<(Hit, Ray)> {
    let mut out = Vec::new();
    for y in 0..grid {
        for x in 0..grid {
            let (u, v) = ((x as f32 + 0.5) / grid as f32, (y as f32 + 0.5) / grid as f32);
            let ray = scene.camera().ray(u, v, 1.0);
            if let Some(hit) = scene.intersect(&ray, f32::INFINITY, RayKind::Camera) {
                out.push((hit, ray));
            }
        }
    }
    out
}
