//! pbrt's analytic furnace, shared by the tests that need an exact answer: a closed diffuse
//! sphere (radius 1, albedo 0.5) around a point light at its centre, seen from inside.

use photon_maps::render::glam::Vec3;
use photon_maps::trace::{Camera, PointLight, Scene, Surface};

/// The furnace with a light of `power` watts per channel: radiance is `power / (4π²)` per
/// channel everywhere inside (direct irradiance `power / 4π`, doubled by the bounces).
pub fn furnace_sphere(power: Vec3) -> Scene {
    Scene::builder()
        .sphere(Vec3::ZERO, 1.0, Surface::diffuse(Vec3::splat(0.5)))
        .light(PointLight::new(Vec3::ZERO, power))
        .camera(Camera::new(
            Vec3::new(0.1, 0.2, 0.6),
            Vec3::new(-0.3, -0.1, -1.0),
            Vec3::Y,
            1.4,
        ))
        .build()
        .expect("valid scene")
}
