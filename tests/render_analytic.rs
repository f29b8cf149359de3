//! pbrt's analytic scene: inside a closed diffuse sphere of albedo 0.5 with a point light of
//! intensity π (power 4π² W) at its centre, radiance is exactly 1 everywhere
//! (direct irradiance π, total π / (1 − 0.5) = 2π, radiance 0.5/π · 2π). Every estimator in
//! PhotonMap mode and the path tracer must give an image mean within 3 % of 1.

use glam::Vec3;
use photon_maps::render::{EstimatorKind, Mode, RenderSettings, Renderer};
use photon_maps::trace::{CreaseAngle, Scene};
use std::f32::consts::PI;

#[path = "support/furnace_sphere.rs"]
mod furnace_sphere;
use furnace_sphere::furnace_sphere;
use photon_maps::trace::Partitioner;

fn furnace() -> Scene {
    furnace_sphere(Vec3::splat(4.0 * PI * PI))
}

fn settings(mode: Mode) -> RenderSettings {
    RenderSettings {
        width: 48,
        height: 48,
        photons: 60_000,
        mode,
        seed: 7,
        ..RenderSettings::default()
    }
}

fn assert_mean_is_one(label: &str, mean: Vec3) {
    for c in mean.to_array() {
        assert!(
            (c - 1.0).abs() < 0.03,
            "{label}: image mean {mean}, want 1 within 3 %"
        );
    }
}

#[test]
fn every_estimator_sees_radiance_one_inside_the_sphere() {
    let scene = furnace();
    for kind in EstimatorKind::ALL {
        let out = Renderer::new(kind, settings(Mode::PhotonMap))
            .render(&CreaseAngle::default().partition(scene.clone()).unwrap(), &())
            .unwrap();
        assert_mean_is_one(kind.name(), out.image.mean());
    }
}

#[test]
fn path_tracer_sees_radiance_one_inside_the_sphere() {
    let scene = furnace();
    let s = RenderSettings {
        samples_per_pixel: 8,
        ..settings(Mode::PathTrace)
    };
    let out = Renderer::new(EstimatorKind::Disc, s)
        .render(&CreaseAngle::default().partition(scene.clone()).unwrap(), &())
        .unwrap();
    assert_mean_is_one("path tracer", out.image.mean());
}

#[test]
fn shadow_rays_see_radiance_one_inside_the_sphere() {
    let scene = furnace();
    let out = Renderer::new(EstimatorKind::GeometryBall, settings(Mode::ShadowRays))
        .render(&CreaseAngle::default().partition(scene.clone()).unwrap(), &())
        .unwrap();
    assert_mean_is_one("shadow rays", out.image.mean());
}
