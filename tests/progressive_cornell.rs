//! The progressive renderer on the Cornell box against a path-traced reference: its RMSE
//! falls with the pass count and its mean converges to the reference's. The full acceptance
//! run (128², 50k photons per pass, 4 → 32 passes) is `#[ignore]`d for CI time; a smaller
//! version runs always.

use photon_maps::render::progressive::{ProgressiveRenderer, ProgressiveSettings, Shard};
use photon_maps::render::{EstimatorKind, Image, Mode, RenderSettings, Renderer};
use photon_maps::trace::Partitioner;
use photon_maps::trace::{CreaseAngle, scenes};

struct Case {
    size: u32,
    photons: u32,
    reference_spp: u32,
    /// Passes of the first shard; the second brings the total to `many`.
    few: u64,
    many: u64,
    /// Photons for all light, or shadow rays for direct light (the pass trees then hold no
    /// direct photons).
    mode: Mode,
}

/// Relative RMSE after `few` and after `many` passes, and the relative error of the mean
/// after `many`.
fn run(case: &Case) -> (f32, f32, f32) {
    let scene = scenes::build("cornell-box").unwrap();
    let base = RenderSettings {
        width: case.size,
        height: case.size,
        photons: case.photons,
        seed: 1,
        mode: case.mode,
        ..RenderSettings::default()
    };
    let reference = Renderer::new(
        EstimatorKind::Disc,
        RenderSettings {
            mode: Mode::PathTrace,
            samples_per_pixel: case.reference_spp,
            seed: 99,
            ..base
        },
    )
    .render(&CreaseAngle::default().partition(scene.clone()).unwrap(), &())
    .unwrap()
    .image;
    let shard = |first, passes| {
        let settings = ProgressiveSettings {
            first_pass: first,
            ..ProgressiveSettings::new(base, passes)
        };
        let out = ProgressiveRenderer::new(EstimatorKind::GeometryCube, settings)
            .render(&CreaseAngle::default().partition(scene.clone()).unwrap(), &())
            .unwrap();
        Shard::new(out.accumulation.mean(), first, passes, "cornell-box", "").unwrap()
    };
    let few = shard(0, case.few);
    let many = Shard::merge(&[few.clone(), shard(case.few, case.many - case.few)]).unwrap();
    let mean = |im: &Image| {
        let m = im.mean();
        (m.x + m.y + m.z) / 3.0
    };
    let rmse_few = few.mean().relative_rmse(&reference).unwrap();
    let rmse_many = many.mean().relative_rmse(&reference).unwrap();
    let mean_error = (mean(&many.mean()) - mean(&reference)).abs() / mean(&reference);
    println!(
        "{0}x{0}, {1} photons/pass: relative RMSE {2:.4} at {3} passes, {4:.4} at {5} ({6:.2}x), mean error {7:.4}",
        case.size,
        case.photons,
        rmse_few,
        case.few,
        rmse_many,
        case.many,
        rmse_few / rmse_many,
        mean_error
    );
    (rmse_few, rmse_many, mean_error)
}

#[test]
fn cornell_box_rmse_falls_with_passes() {
    let (few, many, mean_error) = run(&Case {
        size: 32,
        photons: 10_000,
        reference_spp: 1024,
        few: 2,
        many: 16,
        mode: Mode::PhotonMap,
    });
    assert!(few / many >= 1.4, "RMSE {few} -> {many}");
    assert!(mean_error < 0.03, "mean error {mean_error}");
}

#[test]
fn cornell_box_with_shadow_rays_for_direct_light_converges_too() {
    let (few, many, mean_error) = run(&Case {
        size: 32,
        photons: 10_000,
        reference_spp: 1024,
        few: 2,
        many: 16,
        mode: Mode::ShadowRays,
    });
    assert!(few / many >= 1.4, "RMSE {few} -> {many}");
    assert!(mean_error < 0.03, "mean error {mean_error}");
}

/// The acceptance run: 128², 50k photons per pass, cube + crease. Takes minutes.
#[test]
#[ignore]
fn cornell_box_128_rmse_falls_from_4_to_32_passes() {
    let (few, many, mean_error) = run(&Case {
        size: 128,
        photons: 50_000,
        reference_spp: 4096,
        few: 4,
        many: 32,
        mode: Mode::PhotonMap,
    });
    assert!(few / many >= 1.6, "RMSE {few} -> {many}");
    assert!(mean_error < 0.02, "mean error {mean_error}");
}
