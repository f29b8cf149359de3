//! The Cornell box in its measured dimensions (metres), with a mirror sphere and a diffuse
//! ring on the floor instead of the two blocks.

use super::box_mesh::{Facing, box_mesh};
use crate::camera::Camera;
use crate::error::SceneError;
use crate::material::Surface;
use crate::scene::Scene;
use glam::Vec3;

pub(super) fn cornell_box() -> Result<Scene, SceneError> {
    let size = Vec3::new(0.556, 0.5488, 0.5592);
    let white = Surface::diffuse(Vec3::new(0.725, 0.71, 0.68));
    let red = Surface::diffuse(Vec3::new(0.63, 0.065, 0.05));
    let green = Surface::diffuse(Vec3::new(0.14, 0.45, 0.091));
    let (corners, faces) = box_mesh(Vec3::ZERO, size, Facing::Inward);
    // Open at z = 0: floor, ceiling, green x = 0 wall, red x = 0.556 wall, back; no front.
    let walls = &faces[..5];
    let surfaces = [white, white, green, red, white];
    let light_y = size.y - 0.0005;
    Scene::builder()
        .mesh_per_face(&corners, walls, &surfaces)
        .area_light_quad(
            Vec3::new(0.213, light_y, 0.227),
            Vec3::new(0.13, 0.0, 0.0),
            Vec3::new(0.0, 0.0, 0.105),
            Vec3::new(17.0, 12.0, 4.0),
        )
        .sphere(
            Vec3::new(0.38, 0.1, 0.36),
            0.1,
            Surface::mirror(Vec3::splat(0.95)),
        )
        .ring(Vec3::new(0.16, 0.0005, 0.2), Vec3::Y, 0.045, 0.09, 0.03, white)
        .camera(Camera::new(
            Vec3::new(0.278, 0.273, -0.800),
            Vec3::new(0.278, 0.273, 0.0),
            Vec3::Y,
            39.3f32.to_radians(),
        ))
        .build()
}
