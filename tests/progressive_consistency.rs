//! Consistency of the progressive renderer against a closed form: a diffuse square of albedo
//! ρ under a point light of intensity I at height h has irradiance `E = I h / d³` (d the
//! distance to the light) and radiance `ρ/π · E`; nothing else is in the scene, so that is
//! all the light there is. The progressive mean must come within 0.5 % of the truth for the
//! disc, the cube and the ball, and its RMSE must fall as a power of the pass count (the
//! theory for α = 2/3 is MSE ∝ N^(−2/3), RMSE ∝ N^(−1/3)).

use glam::Vec3;
use photon_maps::render::progressive::{ProgressiveRenderer, ProgressiveSettings, Shard};
use photon_maps::render::{EstimatorKind, Image, Mode, RenderSettings};
use photon_maps::trace::Partitioner;
use photon_maps::trace::{Camera, CreaseAngle, PointLight, Scene, Surface};
use std::f32::consts::PI;

const ALBEDO: f32 = 0.5;
const HEIGHT: f32 = 1.0;
const POWER: f32 = 4.0 * PI * 10.0;
const W: u32 = 24;

fn scene() -> Scene {
    let positions = [
        Vec3::new(-1.0, 0.0, -1.0),
        Vec3::new(-1.0, 0.0, 1.0),
        Vec3::new(1.0, 0.0, 1.0),
        Vec3::new(1.0, 0.0, -1.0),
    ];
    Scene::builder()
        .mesh(
            &positions,
            &[[0u32, 1, 2, 3]],
            Surface::diffuse(Vec3::splat(ALBEDO)),
        )
        .light(PointLight::new(Vec3::new(0.0, HEIGHT, 0.0), Vec3::splat(POWER)))
        .camera(Camera::new(
            Vec3::new(0.0, 2.0, 0.0),
            Vec3::ZERO,
            Vec3::NEG_Z,
            0.6,
        ))
        .build()
        .expect("valid scene")
}

/// The exact image: the radiance averaged over each pixel by 8×8 stratified rays.
fn reference(scene: &Scene) -> Image {
    let camera = scene.camera();
    let intensity = POWER / (4.0 * PI);
    Image::from_fn(W, W, |x, y| {
        let mut sum = 0.0f64;
        for i in 0..8 {
            for j in 0..8 {
                let u = (x as f32 + (i as f32 + 0.5) / 8.0) / W as f32;
                let v = (y as f32 + (j as f32 + 0.5) / 8.0) / W as f32;
                let ray = camera.ray(u, v, 1.0);
                let t = -ray.origin.y / ray.direction.y;
                let p = ray.origin + ray.direction * t;
                let d = (Vec3::new(0.0, HEIGHT, 0.0) - p).length();
                sum += f64::from(ALBEDO / PI * intensity * HEIGHT / (d * d * d));
            }
        }
        Vec3::splat((sum / 64.0) as f32)
    })
    .unwrap()
}

fn settings(first_pass: u64, passes: u64) -> ProgressiveSettings {
    ProgressiveSettings {
        first_pass,
        ..ProgressiveSettings::new(
            RenderSettings {
                width: W,
                height: W,
                photons: 4_000,
                k: 30,
                mode: Mode::PhotonMap,
                seed: 11,
                ..RenderSettings::default()
            },
            passes,
        )
    }
}

/// Least-squares slope of log y against log x.
fn log_slope(points: &[(f64, f64)]) -> f64 {
    let n = points.len() as f64;
    let (lx, ly): (Vec<f64>, Vec<f64>) = points.iter().map(|&(x, y)| (x.ln(), y.ln())).unzip();
    let (mx, my) = (lx.iter().sum::<f64>() / n, ly.iter().sum::<f64>() / n);
    let cov: f64 = lx.iter().zip(&ly).map(|(x, y)| (x - mx) * (y - my)).sum();
    let var: f64 = lx.iter().map(|x| (x - mx).powi(2)).sum();
    cov / var
}

#[test]
fn progressive_mean_converges_to_the_point_lit_plane() {
    let scene = scene();
    let truth = reference(&scene);
    let truth_mean = truth.mean().x as f64;
    for kind in EstimatorKind::ALL {
        // Shards of doubling length: after shard j the merged passes are 2^(j+2).
        let mut shards = Vec::new();
        let mut points = Vec::new();
        let mut last_error = f64::NAN;
        let mut first = 0u64;
        for j in 0..7u32 {
            let count = if j == 0 { 4 } else { first };
            let out = ProgressiveRenderer::new(kind, settings(first, count))
                .render(&CreaseAngle::default().partition(scene.clone()).unwrap(), &())
                .unwrap();
            let a = &out.accumulation;
            shards.push(Shard::new(a.mean(), first, a.passes(), "plane", "s").unwrap());
            first += count;
            let merged = Shard::merge(&shards).unwrap();
            let rmse = merged.mean().relative_rmse(&truth).unwrap() as f64;
            last_error = (merged.mean().mean().x as f64 - truth_mean).abs() / truth_mean;
            println!("{kind}: {first} passes, relative RMSE {rmse:.5}, mean error {last_error:.5}");
            points.push((first as f64, rmse));
        }
        let slope = log_slope(&points);
        println!("{kind}: RMSE slope {slope:.3} (theory −1/3)");
        assert!(last_error < 0.005, "{kind}: mean error {last_error}");
        assert!((-0.7..-0.2).contains(&slope), "{kind}: slope {slope}");
    }
}
