//! pbrt's closed-sphere furnace, shared by the cache tests: a point light of power 4π²
//! (intensity π) at the centre of a closed diffuse sphere of radius 1 and albedo 1/2. Direct
//! irradiance is π everywhere, and with the even interreflection E = π/(1 − 1/2) = 2π, so the
//! outgoing radiance ρ/π · E is exactly 1.

use pm_render::glam::Vec3;
use pm_trace::{
    Camera, CreaseAngle, Partitioner, PhotonMaps, PointLight, Scene, Surface, TraceOptions, trace_photons,
};
use std::f32::consts::PI;

/// The furnace scene.
pub fn furnace() -> Scene {
    Scene::builder()
        .sphere(Vec3::ZERO, 1.0, Surface::diffuse(Vec3::splat(0.5)))
        .light(PointLight::new(Vec3::ZERO, Vec3::splat(4.0 * PI * PI)))
        .camera(Camera::new(Vec3::new(0.0, 0.0, 0.5), Vec3::NEG_Z, Vec3::Y, 1.2))
        .build()
        .unwrap()
}

/// The furnace's photon maps (crease maps) from `photons` photon paths of seed `seed`.
pub fn furnace_maps(scene: &Scene, photons: u32, seed: u64) -> PhotonMaps {
    let assignment = CreaseAngle::default()
        .partition(scene.clone())
        .unwrap()
        .assignment()
        .clone();
    let options = TraceOptions {
        photons,
        seed,
        ..TraceOptions::default()
    };
    PhotonMaps::build(
        scene,
        &assignment,
        trace_photons(scene, &assignment, &options).unwrap(),
    )
    .unwrap()
}
