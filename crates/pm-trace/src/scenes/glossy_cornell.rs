//! The Cornell box with glossy materials: its two blocks rough metal at two roughnesses and a
//! glossy dielectric floor, for photon maps read through a BSDF's glossy lobe.

use super::box_mesh::{Facing, box_mesh};
use crate::bsdf::metallic_roughness::MetallicRoughness;
use crate::camera::Camera;
use crate::error::SceneError;
use crate::material::Surface;
use crate::scene::Scene;
use glam::Vec3;

/// The roughness of the short block's metal (`glossy-cornell-box`).
pub const SHORT_BLOCK_ROUGHNESS: f32 = 0.2;
/// The roughness of the tall block's metal.
pub const TALL_BLOCK_ROUGHNESS: f32 = 0.5;
/// The roughness of the floor's dielectric (metallic 0).
pub const FLOOR_ROUGHNESS: f32 = 0.3;

/// `glossy-cornell-box`: the measured Cornell box (as `cornell-box`, its light and camera),
/// holding two axis-aligned blocks of gold-coloured metal, the short one at roughness
/// [`SHORT_BLOCK_ROUGHNESS`], the tall one at [`TALL_BLOCK_ROUGHNESS`], on a white glossy
/// dielectric floor (metallic 0, roughness [`FLOOR_ROUGHNESS`]).
pub(super) fn glossy_cornell_box() -> Result<Scene, SceneError> {
    let size = Vec3::new(0.556, 0.5488, 0.5592);
    // The parameters are constants in range: `new` cannot refuse them.
    let glossy = |base: Vec3, metallic: f32, roughness: f32| {
        let material = MetallicRoughness::new(base, metallic, roughness).expect("constants in range");
        Surface::metallic_roughness(material)
    };
    let white = Surface::diffuse(Vec3::new(0.725, 0.71, 0.68));
    let red = Surface::diffuse(Vec3::new(0.63, 0.065, 0.05));
    let green = Surface::diffuse(Vec3::new(0.14, 0.45, 0.091));
    let floor = glossy(Vec3::new(0.725, 0.71, 0.68), 0.0, FLOOR_ROUGHNESS);
    let gold = Vec3::new(0.95, 0.76, 0.33);
    let short = glossy(gold, 1.0, SHORT_BLOCK_ROUGHNESS);
    let tall = glossy(gold, 1.0, TALL_BLOCK_ROUGHNESS);
    let (corners, faces) = box_mesh(Vec3::ZERO, size, Facing::Inward);
    // Open at z = 0: floor, ceiling, green x = 0 wall, red x = 0.556 wall, back; no front.
    let walls = &faces[..5];
    let surfaces = [floor, white, green, red, white];
    let light_y = size.y - 0.0005;
    let (short_corners, short_faces) = box_mesh(
        Vec3::new(0.13, 0.0, 0.065),
        Vec3::new(0.29, 0.165, 0.225),
        Facing::Outward,
    );
    let (tall_corners, tall_faces) = box_mesh(
        Vec3::new(0.3, 0.0, 0.295),
        Vec3::new(0.46, 0.33, 0.455),
        Facing::Outward,
    );
    Scene::builder()
        .mesh_per_face(&corners, walls, &surfaces)
        .mesh(&short_corners, &short_faces, short)
        .mesh(&tall_corners, &tall_faces, tall)
        .area_light_quad(
            Vec3::new(0.213, light_y, 0.227),
            Vec3::new(0.13, 0.0, 0.0),
            Vec3::new(0.0, 0.0, 0.105),
            Vec3::new(17.0, 12.0, 4.0),
        )
        .camera(Camera::new(
            Vec3::new(0.278, 0.273, -0.800),
            Vec3::new(0.278, 0.273, 0.0),
            Vec3::Y,
            39.3f32.to_radians(),
        ))
        .build()
}
