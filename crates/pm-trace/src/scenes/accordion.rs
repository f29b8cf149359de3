//! The accordion: a zig-zag strip of 8 facets (0.25 m × 1 m, ±45°, right-angle folds) under a
//! directional light 30° from vertical across the folds.

use crate::camera::Camera;
use crate::error::SceneError;
use crate::light::directional::DirectionalLight;
use crate::material::Surface;
use crate::scene::Scene;
use glam::Vec3;

/// Travel direction of the accordion's light: 30° from straight down, towards +x (across the
/// folds). The facets facing it get `cos 15°`, the others `cos 75°` of its irradiance.
pub const ACCORDION_LIGHT_DIRECTION: Vec3 = Vec3::new(0.5, -0.866_025_4, 0.0);

pub(super) fn accordion() -> Result<Scene, SceneError> {
    let facets = 8;
    let step = 0.25 * std::f32::consts::FRAC_1_SQRT_2;
    let mut positions = Vec::new();
    for i in 0..=facets {
        let y = if i % 2 == 0 { 0.0 } else { step };
        positions.push(Vec3::new(i as f32 * step, y, 0.0));
        positions.push(Vec3::new(i as f32 * step, y, 1.0));
    }
    // Normals up: (−1, 1, 0)/√2 on rising facets, (1, 1, 0)/√2 on falling ones.
    let faces: Vec<[u32; 4]> = (0..facets)
        .map(|i| [2 * i, 2 * i + 1, 2 * i + 3, 2 * i + 2])
        .collect();
    let center = Vec3::new(facets as f32 * step * 0.5, step * 0.5, 0.5);
    Scene::builder()
        .mesh(&positions, &faces, Surface::diffuse(Vec3::splat(0.8)))
        .light(DirectionalLight::new(
            ACCORDION_LIGHT_DIRECTION,
            Vec3::splat(10.0),
        ))
        .camera(Camera::new(
            center + Vec3::new(0.0, 1.0, -1.3),
            center,
            Vec3::Y,
            50f32.to_radians(),
        ))
        .build()
}
