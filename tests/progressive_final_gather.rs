//! The consistent final gather (`--mode progressive --gather-rays N`): each pass a final
//! gather with the pass's photons, cache and shrinking fixed volumes. Its error against the
//! path tracer falls with passes; the same image on any thread count; shards merge into the
//! single run bit for bit; in the furnace it averages to the exact radiance.

use photon_maps::render::glam::Vec3;
use photon_maps::render::progressive::{ProgressiveRenderer, ProgressiveSettings, Shard};
use photon_maps::render::{EstimatorKind, FinalGatherOptions, Image, Mode, RenderSettings, Renderer};
use photon_maps::trace::{CreaseAngle, Material, RayKind, Scene, scenes};

#[path = "support/furnace_sphere.rs"]
mod furnace_sphere;
use furnace_sphere::furnace_sphere;
use photon_maps::trace::Partitioner;

const SIZE: u32 = 32;

fn settings(mode: Mode, spp: u32, photons: u32, threads: usize) -> RenderSettings {
    RenderSettings {
        width: SIZE,
        height: SIZE,
        samples_per_pixel: spp,
        photons,
        mode,
        seed: 5,
        threads,
        final_gather: FinalGatherOptions {
            gather_rays: 8,
            ..FinalGatherOptions::default()
        },
        ..RenderSettings::default()
    }
}

fn progressive(scene: &Scene, first: u64, passes: u64, threads: usize) -> Shard {
    let s = ProgressiveSettings {
        first_pass: first,
        ..ProgressiveSettings::new(settings(Mode::FinalGather, 1, 5_000, threads), passes)
    };
    let out = ProgressiveRenderer::new(EstimatorKind::GeometryCube, s)
        .render(&CreaseAngle::default().partition(scene.clone()).unwrap(), &())
        .unwrap();
    assert!(out.stats.precompute > std::time::Duration::ZERO);
    Shard::from_accumulation(&out.accumulation, "cornell-box", &s.identity()).unwrap()
}

/// Pixels whose centre and corners all see diffuse, non-emitting surfaces.
fn diffuse_pixels(scene: &Scene) -> Vec<bool> {
    let camera = scene.camera();
    let diffuse = |u: f32, v: f32| {
        let ray = camera.ray(u / SIZE as f32, v / SIZE as f32, 1.0);
        scene
            .intersect(&ray, f32::INFINITY, RayKind::Camera)
            .is_some_and(|hit| {
                scene.emission(&hit) == Vec3::ZERO
                    && matches!(scene.material(&hit), Material::Lambertian { .. })
            })
    };
    (0..SIZE * SIZE)
        .map(|i| {
            let (x, y) = ((i % SIZE) as f32, (i / SIZE) as f32);
            [(0.5, 0.5), (0.0, 0.0), (1.0, 0.0), (0.0, 1.0), (1.0, 1.0)]
                .iter()
                .all(|&(dx, dy)| diffuse(x + dx, y + dy))
        })
        .collect()
}

fn bits(image: &Image) -> Vec<u32> {
    image
        .pixels()
        .iter()
        .flat_map(|p| p.to_array().map(f32::to_bits))
        .collect()
}

#[test]
fn threads_and_shards_do_not_change_the_image() {
    let scene = scenes::build("cornell-box").unwrap();
    let single = progressive(&scene, 0, 4, 1);
    assert_eq!(
        bits(&single.mean()),
        bits(&progressive(&scene, 0, 4, 3).mean()),
        "1 and 3 threads differ"
    );
    let merged = Shard::merge(&[progressive(&scene, 2, 2, 2), progressive(&scene, 0, 2, 2)]).unwrap();
    assert_eq!(
        bits(&merged.mean()),
        bits(&single.mean()),
        "merged shards differ from the single run"
    );
    // Another gather-ray count is another image, and its shards do not merge with these.
    let s = ProgressiveSettings::new(settings(Mode::FinalGather, 1, 5_000, 0), 2);
    let mut other = s;
    other.render.final_gather.gather_rays = 9;
    assert_ne!(s.identity(), other.identity());
}

#[test]
fn the_error_against_the_path_tracer_falls_with_passes() {
    let scene = scenes::build("cornell-box").unwrap();
    // Two independent path-traced halves: their mean is the reference, their difference its
    // own noise (which the errors below have removed, in quadrature).
    let half = |seed| {
        let s = RenderSettings {
            seed,
            ..settings(Mode::PathTrace, 1024, 1, 0)
        };
        Renderer::new(EstimatorKind::GeometryCube, s)
            .render(&CreaseAngle::default().partition(scene.clone()).unwrap(), &())
            .unwrap()
            .image
    };
    let halves = [half(100), half(101)];
    let reference = Image::from_pixels(
        SIZE,
        SIZE,
        halves[0]
            .pixels()
            .iter()
            .zip(halves[1].pixels())
            .map(|(a, b)| (*a + *b) / 2.0)
            .collect(),
    )
    .unwrap();
    let mean = |im: &Image| im.mean().element_sum() / 3.0;
    // Pixels that see only diffuse surfaces (a light's edge pixels, or its reflection in the
    // mirror ball, would be all the error at one sample per pixel and pass).
    let mask = diffuse_pixels(&scene);
    let rmse_against = |im: &Image, reference: &Image| {
        let pairs: Vec<(Vec3, Vec3)> = im
            .pixels()
            .iter()
            .zip(reference.pixels())
            .zip(&mask)
            .filter(|(_, m)| **m)
            .map(|((a, b), _)| (*a, *b))
            .collect();
        let se: f32 = pairs.iter().map(|(a, b)| (*a - *b).length_squared() / 3.0).sum();
        (se / pairs.len() as f32).sqrt() / mean(reference)
    };
    // The variance of the mean of two halves is a quarter of their difference's.
    let reference_noise = rmse_against(&halves[0], &halves[1]) / 2.0;
    let rmse = |im: &Image| {
        (rmse_against(im, &reference).powi(2) - reference_noise.powi(2))
            .max(0.0)
            .sqrt()
    };
    let few = progressive(&scene, 0, 4, 0);
    let more = Shard::merge(&[few.clone(), progressive(&scene, 4, 28, 0)]).unwrap();
    let (e4, e32) = (rmse(&few.mean()), rmse(&more.mean()));
    let bias = (mean(&more.mean()) - mean(&reference)) / mean(&reference);
    eprintln!(
        "relative RMSE {e4:.4} at 4 passes, {e32:.4} at 32 (the reference's own {reference_noise:.4} removed); image mean {bias:+.4} at 32"
    );
    // Noise alone would fall by √8 (to 0.35); the bias falls too.
    assert!(e32 < 0.5 * e4, "{e4} → {e32}");
    assert!(bias.abs() < 0.02, "image mean off by {bias}");
}

/// Inside a closed diffuse sphere of albedo 0.5 with a point light of intensity π at its
/// centre, radiance is exactly 1 everywhere. The consistent final gather with Jensen's disc
/// (on a sphere the disc's πr² is exactly the area within r, so no smoothing bias either) must
/// average to 1 within its noise, over independent runs: a cache that sets aside a share of
/// photons other than the one it scales by is off by that share in every pass (the same tree
/// slots in every pass read 0.9970 ± 0.0004).
#[test]
fn the_consistent_gather_sees_radiance_one_in_the_furnace() {
    use std::f32::consts::PI;
    let scene = furnace_sphere(Vec3::splat(4.0 * PI * PI));
    let runs: Vec<f64> = (0..12u64)
        .map(|seed| {
            let s = RenderSettings {
                width: 16,
                height: 16,
                photons: 2_500,
                seed,
                mode: Mode::FinalGather,
                final_gather: FinalGatherOptions {
                    gather_rays: 4,
                    ..FinalGatherOptions::default()
                },
                ..RenderSettings::default()
            };
            let out = ProgressiveRenderer::new(EstimatorKind::Disc, ProgressiveSettings::new(s, 32))
                .render(&CreaseAngle::default().partition(scene.clone()).unwrap(), &())
                .unwrap();
            f64::from(out.accumulation.mean().mean().element_sum()) / 3.0
        })
        .collect();
    let n = runs.len() as f64;
    let mean = runs.iter().sum::<f64>() / n;
    let se = (runs.iter().map(|r| (r - mean).powi(2)).sum::<f64>() / (n - 1.0) / n).sqrt();
    eprintln!("consistent final gather in the furnace: {mean:.5} ± {se:.5} (exact 1)");
    assert!(se < 0.001, "too noisy to tell ({se})");
    assert!((mean - 1.0).abs() < 4.0 * se.max(2e-4), "{mean} ± {se}, exact 1");
}
