//! How a glossy surface reads as its lobe narrows: a box whose floor is rough metal, the
//! floor's image region against the path tracer at roughness 0.1 to 0.5. A measurement
//! (ignored): it prints, for each roughness, the floor's relative error and its standard error
//! over seeds, for shadow-rays mode with the cube estimator (one shot) and for the progressive
//! mode. Below [`NEAR_SPECULAR_ROUGHNESS`] the camera path samples through the surface (a BSDF
//! bounce, then photons at the next vertex); above it the photons are read there (`Σ Φ f`). To
//! see both reads at one roughness, change that constant: the numbers in its documentation
//! came from builds with 0.1 and 0.35.
//!
//! `cargo test --release --test glossy_roughness_sweep -- --ignored --nocapture`

#[path = "support/replicates.rs"]
mod replicates;
use replicates::mean_and_error;

use photon_maps::render::core::NEAR_SPECULAR_ROUGHNESS;
use photon_maps::render::progressive::{ProgressiveRenderer, ProgressiveSettings};
use photon_maps::render::{EstimatorKind, Image, Mode, RenderSettings, Renderer};
use photon_maps::trace::bsdf::MetallicRoughness;
use photon_maps::trace::glam::Vec3;
use photon_maps::trace::{Camera, CreaseAngle, Partitioned, Partitioner, Scene, Surface};

const SIZE: u32 = 32;

/// A 1 m box open at z = 0, lit by a ceiling panel; its floor rough metal of `roughness`.
fn metal_floor_box(roughness: f32) -> Partitioned {
    let c = |x: f32, y: f32, z: f32| Vec3::new(x, y, z);
    let corners = [
        c(0.0, 0.0, 0.0),
        c(1.0, 0.0, 0.0),
        c(1.0, 0.0, 1.0),
        c(0.0, 0.0, 1.0),
        c(0.0, 1.0, 0.0),
        c(1.0, 1.0, 0.0),
        c(1.0, 1.0, 1.0),
        c(0.0, 1.0, 1.0),
    ];
    // Inward-facing: floor, ceiling, left, right, back.
    let faces: [[u32; 4]; 5] = [
        [0, 3, 2, 1],
        [4, 5, 6, 7],
        [0, 4, 7, 3],
        [1, 2, 6, 5],
        [3, 7, 6, 2],
    ];
    let metal = MetallicRoughness::new(Vec3::new(0.9, 0.7, 0.5), 1.0, roughness).unwrap();
    let surfaces = [
        Surface::metallic_roughness(metal),
        Surface::diffuse(Vec3::splat(0.7)),
        Surface::diffuse(Vec3::new(0.7, 0.1, 0.1)),
        Surface::diffuse(Vec3::new(0.1, 0.6, 0.1)),
        Surface::diffuse(Vec3::splat(0.7)),
    ];
    let scene = Scene::builder()
        .mesh_per_face(&corners, &faces, &surfaces)
        .area_light_quad(
            c(0.4, 0.999, 0.4),
            c(0.2, 0.0, 0.0),
            c(0.0, 0.0, 0.2),
            Vec3::splat(20.0),
        )
        .camera(Camera::new(
            c(0.5, 0.8, -0.6),
            c(0.5, 0.1, 0.6),
            Vec3::Y,
            50f32.to_radians(),
        ))
        .build()
        .unwrap();
    CreaseAngle::default().partition(scene).unwrap()
}

fn settings(mode: Mode, spp: u32, seed: u64) -> RenderSettings {
    RenderSettings {
        width: SIZE,
        height: SIZE,
        photons: 100_000,
        samples_per_pixel: spp,
        mode,
        seed,
        threads: 2,
        ..RenderSettings::default()
    }
}

/// The mean of the image's lower half (the floor), channels summed.
fn floor_mean(image: &Image) -> f64 {
    let m = image.mean_in_rect(0, SIZE / 2, SIZE, SIZE / 2).unwrap();
    f64::from(m.x + m.y + m.z)
}

#[test]
#[ignore = "measurement: prints the floor's error against the path tracer per roughness"]
fn photon_read_of_a_metal_floor_against_the_path_tracer() {
    let seeds: Vec<u64> = (0..4).map(|s| 5 + 7919 * s).collect();
    eprintln!("near-specular threshold: roughness {NEAR_SPECULAR_ROUGHNESS}");
    for roughness in [0.1, 0.15, 0.2, 0.3, 0.5] {
        let scene = metal_floor_box(roughness);
        let over = |render: &dyn Fn(u64) -> Image| {
            mean_and_error(&seeds.iter().map(|&s| floor_mean(&render(s))).collect::<Vec<_>>())
        };
        let reference = over(&|s| {
            Renderer::new(EstimatorKind::Disc, settings(Mode::PathTrace, 1024, s))
                .render(&scene, &())
                .unwrap()
                .image
        });
        let shadow = over(&|s| {
            Renderer::new(EstimatorKind::GeometryCube, settings(Mode::ShadowRays, 4, s))
                .render(&scene, &())
                .unwrap()
                .image
        });
        let progressive = over(&|s| {
            ProgressiveRenderer::new(
                EstimatorKind::GeometryCube,
                ProgressiveSettings::new(settings(Mode::ShadowRays, 4, s), 16),
            )
            .render(&scene, &())
            .unwrap()
            .accumulation
            .mean()
        });
        let line = |(m, e): (f64, f64)| {
            let (r, re) = reference;
            let t = (m - r) / (e * e + re * re).sqrt();
            format!(
                "{:+.4} ± {:.4} (t {t:+.1})",
                (m - r) / r,
                (e * e + re * re).sqrt() / r
            )
        };
        eprintln!(
            "roughness {roughness}: path tracer {:.4} ± {:.4}; shadow-rays cube {}; progressive 16 passes {}",
            reference.0,
            reference.1,
            line(shadow),
            line(progressive)
        );
    }
}
