//! Every photon mode against the path tracer on `glossy-cornell-box` (rough metal blocks at
//! roughness 0.2 and 0.5 on a glossy dielectric floor), region by region: the image is cut into
//! 4 × 4 blocks and each block's mean (all three channels summed) is compared with the path
//! tracer's, in units of the combined standard error of the two (from independent seeds).

use photon_maps::render::progressive::{ProgressiveRenderer, ProgressiveSettings};
use photon_maps::render::{EstimatorKind, Image, Mode, RenderSettings, Renderer};
use photon_maps::trace::{CreaseAngle, Partitioner, scenes};

#[path = "support/photon_modes.rs"]
mod photon_modes;
use photon_modes::{Sppm, every_mode, small_settings};

const SIZE: u32 = 24;

const BLOCKS: u32 = 4;

fn settings(mode: Mode, seed: u64) -> RenderSettings {
    small_settings((SIZE, SIZE), 60_000, 4, mode, seed)
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

#[test]
#[ignore = "measurement: prints each mode's block errors against the path tracer"]
fn measure_every_photon_mode_against_the_path_tracer() {
    let scene = scenes::build("glossy-cornell-box").unwrap();
    let crease = CreaseAngle::default().partition(scene).unwrap();
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
    let cases = every_mode(&crease, &settings, Sppm::Included);
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
    let crease = CreaseAngle::default().partition(scene).unwrap();
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
    let cases = every_mode(&crease, &settings, Sppm::Included);
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

/// The path tracer's blocks over `seeds` seeds at `spp` samples per pixel.
fn path_traced(spp: u32, seeds: u64) -> Vec<(f64, f64)> {
    let crease = CreaseAngle::default()
        .partition(scenes::build("glossy-cornell-box").unwrap())
        .unwrap();
    over_seeds(
        |s| {
            let mut settings = settings(Mode::PathTrace, s);
            settings.samples_per_pixel = spp;
            Renderer::new(EstimatorKind::Disc, settings)
                .render(&crease, &())
                .unwrap()
                .image
        },
        seeds,
    )
}

/// The progressive modes at `passes` passes of 15,000 photons, one sample per pixel per pass,
/// with Knaus & Zwicker's `alpha`: their blocks over `seeds` seeds.
fn progressive_blocks(
    kind: EstimatorKind,
    mode: Mode,
    passes: u64,
    alpha: f32,
    seeds: u64,
) -> Vec<(f64, f64)> {
    let crease = CreaseAngle::default()
        .partition(scenes::build("glossy-cornell-box").unwrap())
        .unwrap();
    let settings_for = |s| RenderSettings {
        photons: 15_000,
        samples_per_pixel: 1,
        ..settings(mode, s)
    };
    over_seeds(
        |s| {
            let mut progressive = ProgressiveSettings::new(settings_for(s), passes);
            progressive.alpha = alpha;
            ProgressiveRenderer::new(kind, progressive)
                .render(&crease, &())
                .unwrap()
                .accumulation
                .mean()
        },
        seeds,
    )
}

/// The progressive modes the pass tests follow.
const PROGRESSIVE: [(&str, EstimatorKind, Mode); 3] = [
    ("progressive cube", EstimatorKind::GeometryCube, Mode::PhotonMap),
    (
        "progressive shadow-rays disc",
        EstimatorKind::Disc,
        Mode::ShadowRays,
    ),
    (
        "progressive final-gather cube",
        EstimatorKind::GeometryCube,
        Mode::FinalGather,
    ),
];

/// The progressive modes at 2, 8 and 32 passes of 15,000 photons against the path tracer,
/// block by block: the progressive mode's bias (from the shrinking volumes) must fall with
/// passes at region level, not only over the image.
#[test]
#[ignore = "measurement: prints the progressive modes' block errors as passes grow"]
fn measure_the_progressive_bias_as_passes_grow() {
    let seeds = 4;
    let reference = path_traced(1024, seeds);
    for (name, kind, mode) in PROGRESSIVE {
        for passes in [2, 8, 32] {
            let t = std::time::Instant::now();
            let blocks = progressive_blocks(kind, mode, passes, ProgressiveSettings::DEFAULT_ALPHA, seeds);
            compare(&format!("{name}, {passes} passes"), &blocks, &reference);
            eprintln!("  ({:.1} s)", t.elapsed().as_secs_f64());
        }
    }
}

/// Measured (4 seeds, the measurement above): the mean |relative error| over the 16 blocks
/// fell from 2 to 32 passes 0.065 → 0.030 (cube), 0.083 → 0.041 (shadow-rays disc) and
/// 0.043 → 0.020 (final gather), a ratio of 0.46 to 0.49 (3 seeds: 0.36 to 0.43).
const MEAN_RATIO: f64 = 0.6;

/// The disc darkens the top right corner's block (t ≈ −60 against the path tracer): a bias,
/// not noise, which shrinks with the volumes. After 32 passes from the same first pass, the
/// corner's error with the default α = 2/3 is below this fraction of its error with α = 0.999
/// (volumes that barely shrink). Measured (3 seeds): 0.089 against 0.140 (0.64); before pixel
/// samples were stratified, 0.127 against 0.173 (0.73). (Comparing the corner's error at 2
/// and 32 passes of one α instead leaned on the noise of 2 passes, which stratified pixel
/// samples cut: 0.110 → 0.089 at α = 2/3, and 0.120 → 0.140 at α = 0.999.)
const CORNER_RATIO: f64 = 0.8;
const DISC_CORNER: usize = 3;

#[test]
fn the_progressive_modes_bias_falls_with_passes_region_by_region() {
    let seeds = 3;
    let reference = path_traced(512, seeds);
    let rel = |blocks: &[(f64, f64)]| -> Vec<f64> {
        blocks
            .iter()
            .zip(&reference)
            .map(|(&(m, _), &(r, _))| ((m - r) / r).abs())
            .collect()
    };
    let mean = |v: &[f64]| v.iter().sum::<f64>() / v.len() as f64;
    let alpha = ProgressiveSettings::DEFAULT_ALPHA;
    for (name, kind, mode) in PROGRESSIVE {
        let early = mean(&rel(&progressive_blocks(kind, mode, 2, alpha, seeds)));
        let late = mean(&rel(&progressive_blocks(kind, mode, 32, alpha, seeds)));
        eprintln!("{name}: mean |rel| {early:.3} at 2 passes, {late:.3} at 32");
        assert!(
            late < MEAN_RATIO * early,
            "{name}: the block error fell only from {early:.3} to {late:.3} from 2 to 32 passes"
        );
    }
    let (_, kind, mode) = PROGRESSIVE[1];
    let corner =
        |alpha: f32, passes: u64| rel(&progressive_blocks(kind, mode, passes, alpha, seeds))[DISC_CORNER];
    let (shrinking, kept) = (corner(alpha, 32), corner(0.999, 32));
    eprintln!("the disc's corner after 32 passes: {shrinking:.3} (alpha {alpha}), {kept:.3} (alpha 0.999)");
    assert!(
        shrinking < CORNER_RATIO * kept,
        "the disc's corner bias does not shrink with the volumes: {shrinking:.3} against {kept:.3}"
    );
}
