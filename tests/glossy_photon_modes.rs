//! Every photon mode against the path tracer on `glossy-cornell-box` (rough metal blocks at
//! roughness 0.2 and 0.5 on a glossy dielectric floor), region by region: the image is cut into
//! 4 × 4 blocks and each block's mean (all three channels summed) is compared with the path
//! tracer's, in units of the combined standard error of the two (from independent seeds).

use photon_maps::render::progressive::{
    ProgressiveRenderer, ProgressiveSettings, SppmRenderer, SppmSettings,
};
use photon_maps::render::{EstimatorKind, FinalGatherOptions, Image, Mode, RenderSettings, Renderer};
use photon_maps::trace::{CreaseAngle, Partitioned, Partitioner, Scene, scenes};

const SIZE: u32 = 24;

/// A mode's name and how it renders the scene for a seed.
type Case<'a> = (&'static str, Box<dyn Fn(u64) -> Image + 'a>);
const BLOCKS: u32 = 4;

fn settings(mode: Mode, seed: u64) -> RenderSettings {
    RenderSettings {
        width: SIZE,
        height: SIZE,
        photons: 60_000,
        samples_per_pixel: 4,
        mode,
        seed,
        threads: 2,
        final_gather: FinalGatherOptions {
            gather_rays: 4,
            ..FinalGatherOptions::default()
        },
        ..RenderSettings::default()
    }
}

/// The mean of each of the 4 × 4 blocks, channels summed.
fn block_means(image: &Image) -> Vec<f64> {
    let side = SIZE / BLOCKS;
    let mut means = Vec::new();
    for by in 0..BLOCKS {
        for bx in 0..BLOCKS {
            let m = image.mean_in_rect(bx * side, by * side, side, side).unwrap();
            means.push(f64::from(m.x + m.y + m.z));
        }
    }
    means
}

/// Per block: the mean over seeds and its standard error.
fn over_seeds(render: impl Fn(u64) -> Image, seeds: u64) -> Vec<(f64, f64)> {
    let runs: Vec<Vec<f64>> = (0..seeds).map(|s| block_means(&render(11 + 7919 * s))).collect();
    (0..runs[0].len())
        .map(|b| {
            let values: Vec<f64> = runs.iter().map(|r| r[b]).collect();
            let n = values.len() as f64;
            let mean = values.iter().sum::<f64>() / n;
            let var = values.iter().map(|v| (v - mean).powi(2)).sum::<f64>() / (n - 1.0);
            (mean, (var / n).sqrt())
        })
        .collect()
}

fn one_shot(partitioned: &Partitioned, kind: EstimatorKind, mode: Mode, seed: u64) -> Image {
    Renderer::new(kind, settings(mode, seed))
        .render(partitioned, &())
        .unwrap()
        .image
}

fn progressive(partitioned: &Partitioned, kind: EstimatorKind, mode: Mode, seed: u64) -> Image {
    ProgressiveRenderer::new(kind, ProgressiveSettings::new(settings(mode, seed), 4))
        .render(partitioned, &())
        .unwrap()
        .accumulation
        .mean()
}

fn sppm(scene: &Scene, seed: u64) -> Image {
    SppmRenderer::new(SppmSettings::new(settings(Mode::PhotonMap, seed), 8))
        .render(scene, &())
        .unwrap()
        .image
}

/// Largest |t| over the blocks and the mean relative difference, against `reference`.
fn compare(name: &str, modes: &[(f64, f64)], reference: &[(f64, f64)]) -> (f64, f64) {
    let mut worst: f64 = 0.0;
    let mut rel = 0.0;
    for (&(m, s), &(r, sr)) in modes.iter().zip(reference) {
        let t = (m - r) / (s * s + sr * sr).sqrt().max(1e-9);
        worst = worst.max(t.abs());
        rel += ((m - r) / r).abs();
    }
    rel /= modes.len() as f64;
    let line: Vec<String> = modes
        .iter()
        .zip(reference)
        .map(|(&(m, s), &(r, _))| format!("{:+.3}±{:.3}", (m - r) / r, s / r))
        .collect();
    eprintln!(
        "{name}: max |t| {worst:.2}, mean |rel| {rel:.3}\n  {}",
        line.join(" ")
    );
    (worst, rel)
}

/// Every photon mode the tests compare, with the estimators they read through: one-shot
/// photon-map, shadow-rays and final gather, progressive, and SPPM.
fn every_mode<'a>(crease: &'a Partitioned, scene: &'a Scene) -> Vec<Case<'a>> {
    use EstimatorKind::{Disc, GeometryBall, GeometryCube};
    let one = |name, kind, mode| -> Case<'a> { (name, Box::new(move |s| one_shot(crease, kind, mode, s))) };
    let passes =
        |name, kind, mode| -> Case<'a> { (name, Box::new(move |s| progressive(crease, kind, mode, s))) };
    vec![
        one("photon-map disc", Disc, Mode::PhotonMap),
        one("photon-map cube", GeometryCube, Mode::PhotonMap),
        one("shadow-rays cube", GeometryCube, Mode::ShadowRays),
        one("shadow-rays ball", GeometryBall, Mode::ShadowRays),
        one("final-gather cube", GeometryCube, Mode::FinalGather),
        one("final-gather disc", Disc, Mode::FinalGather),
        passes("progressive cube", GeometryCube, Mode::PhotonMap),
        passes("progressive shadow-rays disc", Disc, Mode::ShadowRays),
        passes("progressive final-gather cube", GeometryCube, Mode::FinalGather),
        ("sppm", Box::new(move |s| sppm(scene, s))),
    ]
}

#[test]
#[ignore = "measurement: prints each mode's block errors against the path tracer"]
fn measure_every_photon_mode_against_the_path_tracer() {
    let scene = scenes::build("glossy-cornell-box").unwrap();
    let crease = CreaseAngle::default().partition(scene.clone()).unwrap();
    let seeds = 4;
    let reference = over_seeds(
        |s| {
            let mut settings = settings(Mode::PathTrace, s);
            settings.samples_per_pixel = 256;
            Renderer::new(EstimatorKind::Disc, settings)
                .render(&crease, &())
                .unwrap()
                .image
        },
        seeds,
    );
    let r: Vec<String> = reference.iter().map(|(m, s)| format!("{m:.4}±{s:.4}")).collect();
    eprintln!("path tracer: {}", r.join(" "));
    let cases = every_mode(&crease, &scene);
    for (name, render) in cases {
        let t = std::time::Instant::now();
        let blocks = over_seeds(render, seeds);
        compare(name, &blocks, &reference);
        eprintln!("  ({:.1} s)", t.elapsed().as_secs_f64());
    }
}

/// The tolerances, from the measurement above (4 seeds, 24², 60k photons): the modes' mean
/// |relative error| over the 16 blocks was 0.018 to 0.055 (the disc's own darkening at edges
/// the largest), against 0.10 to 0.13 with the glossy lobe read as `ρ_d/π · E`; the short
/// metal block's block (row 2, column 1) was within 0.09 of the path tracer in every mode,
/// against 0.65 to 0.68 too dark before. Since the short block (roughness 0.2) is sampled
/// through by camera paths (the near-specular threshold 0.25), this test's 3 seeds read it
/// within 0.13 (mean |relative error| 0.024 to 0.049 over the 10 modes).
const MEAN_REL: f64 = 0.075;
const SHORT_BLOCK_REL: f64 = 0.15;
const SHORT_BLOCK: usize = 9;

#[test]
fn every_photon_mode_reads_the_glossy_lobes_as_the_path_tracer_does() {
    let scene = scenes::build("glossy-cornell-box").unwrap();
    let crease = CreaseAngle::default().partition(scene.clone()).unwrap();
    let seeds = 3;
    let reference = over_seeds(
        |s| {
            let mut settings = settings(Mode::PathTrace, s);
            settings.samples_per_pixel = 128;
            Renderer::new(EstimatorKind::Disc, settings)
                .render(&crease, &())
                .unwrap()
                .image
        },
        seeds,
    );
    let cases = every_mode(&crease, &scene);
    for (name, render) in cases {
        let blocks = over_seeds(render, seeds);
        let (_, rel) = compare(name, &blocks, &reference);
        let short = (blocks[SHORT_BLOCK].0 - reference[SHORT_BLOCK].0) / reference[SHORT_BLOCK].0;
        assert!(
            rel < MEAN_REL,
            "{name}: mean |relative error| {rel:.3} over the blocks"
        );
        assert!(
            short.abs() < SHORT_BLOCK_REL,
            "{name}: the short metal block is off by {short:+.3}"
        );
    }
}
