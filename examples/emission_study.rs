//! Camera-driven against uniform photon emission at equal wall time: the relative RMSE of the
//! progressive renderer (shadow rays for direct light), the progressive final gather and SPPM
//! against a path-traced reference, each run with both emissions on several seeds, read after
//! every pass (off nothing: the wall time counts the guide's camera pass and pilot, the
//! progressive pilot and the error's own reading, a few microseconds a pass).
//!
//! The reference is the mean of `--reference-replicates` path-traced images of independent
//! seeds; its per-pixel variance (from the replicates) is removed from every error, and its
//! noise is printed beside the errors it judges (kept in `--out-dir` and reused by later
//! runs of the same scene, size and samples). Writes `emission-study-<scene>.md` into
//! `--out-dir` (default `target/emission-study`); nothing into the repository unless its
//! folder is named.
//!
//! `cargo run --release --example emission_study -- --scene doorway-rooms-8`
//! `cargo run --release --example emission_study -- --scene cornell-box`

#[path = "../tests/support/replicates.rs"]
mod replicates;
use replicates::mean_and_error;

use clap::Parser;
use photon_maps::render::emission::PhotonEmission;
use photon_maps::render::progressive::{
    ProgressiveRenderer, ProgressiveSettings, SppmRenderer, SppmSettings,
};
use photon_maps::render::{FinalGatherOptions, GeometryCube, Image, Mode, RenderSettings, Renderer};
use photon_maps::trace::{CreaseAngle, GuideOptions, Partitioned, Partitioner, scenes};
use std::fmt::Write as _;
use std::ops::ControlFlow;
use std::path::PathBuf;
use std::process::ExitCode;
use std::time::Duration;

#[derive(Parser, Debug)]
#[command(about = "Camera-driven against uniform photon emission at equal wall time")]
struct Args {
    /// A built-in scene.
    #[arg(long, default_value = "doorway-rooms-8")]
    scene: String,
    /// Image size, WIDTHxHEIGHT.
    #[arg(long, default_value = "96x72")]
    size: String,
    /// Wall-time budgets in seconds, comma-separated.
    #[arg(long, default_value = "1,3,9")]
    budgets: String,
    /// Seeds per method and emission.
    #[arg(long, default_value_t = 3)]
    seeds: u64,
    /// Photons per pass.
    #[arg(long, default_value_t = 50_000)]
    photons: u32,
    /// Path-traced reference: samples per pixel of each replicate.
    #[arg(long, default_value_t = 1024)]
    reference_spp: u32,
    /// Path-traced reference: independent replicates (at least 2, for its variance).
    #[arg(long, default_value_t = 4)]
    reference_replicates: u64,
    /// Where the table goes, and the references (kept and reused:
    /// `reference-<scene>-<size>-<spp>x<replicates>.bin`).
    #[arg(long, default_value = "target/emission-study")]
    out_dir: PathBuf,
}

/// The path-traced reference: per-pixel mean of the replicates and the variance of that mean.
struct Reference {
    mean: Vec<f64>,
    variance_of_mean: Vec<f64>,
    image_mean: f64,
}

impl Reference {
    /// The reference kept in `path`, or made and kept there.
    fn kept(
        path: &std::path::Path,
        partitioned: &Partitioned,
        base: RenderSettings,
        spp: u32,
        replicates: u64,
    ) -> Result<Self, String> {
        let pixels = base.width as usize * base.height as usize;
        if let Ok(bytes) = std::fs::read(path) {
            if bytes.len() == 16 * pixels {
                let values: Vec<f64> = bytes
                    .chunks_exact(8)
                    .map(|b| f64::from_le_bytes(b.try_into().expect("8 bytes")))
                    .collect();
                let (mean, variance_of_mean) = values.split_at(pixels);
                eprintln!("reference: read {}", path.display());
                return Ok(Reference {
                    image_mean: mean.iter().sum::<f64>() / pixels as f64,
                    mean: mean.to_vec(),
                    variance_of_mean: variance_of_mean.to_vec(),
                });
            }
            eprintln!(
                "reference: {} has the wrong size; making it again",
                path.display()
            );
        }
        eprintln!("reference: {replicates} × {spp} spp path traced");
        let reference = Self::new(partitioned, base, spp, replicates)?;
        let bytes: Vec<u8> = reference
            .mean
            .iter()
            .chain(&reference.variance_of_mean)
            .flat_map(|v| v.to_le_bytes())
            .collect();
        std::fs::write(path, bytes).map_err(|e| format!("{}: {e}", path.display()))?;
        Ok(reference)
    }

    fn new(
        partitioned: &Partitioned,
        base: RenderSettings,
        spp: u32,
        replicates: u64,
    ) -> Result<Self, String> {
        let mut images = Vec::new();
        for r in 0..replicates.max(2) {
            let settings = RenderSettings {
                mode: Mode::PathTrace,
                samples_per_pixel: spp,
                seed: 1_000_000 + r,
                ..base
            };
            let image = Renderer::new(GeometryCube, settings)
                .render(partitioned, &())
                .map_err(|e| e.to_string())?
                .image;
            images.push(grey(&image));
        }
        let n = images.len() as f64;
        let pixels = images[0].len();
        let mean: Vec<f64> = (0..pixels)
            .map(|i| images.iter().map(|im| im[i]).sum::<f64>() / n)
            .collect();
        let variance_of_mean = (0..pixels)
            .map(|i| images.iter().map(|im| (im[i] - mean[i]).powi(2)).sum::<f64>() / (n - 1.0) / n)
            .collect();
        let image_mean = mean.iter().sum::<f64>() / pixels as f64;
        Ok(Reference {
            mean,
            variance_of_mean,
            image_mean,
        })
    }

    /// Relative RMSE of `image` with the reference's own variance removed.
    fn error(&self, image: &Image) -> f64 {
        let g = grey(image);
        let n = g.len() as f64;
        let squared = g
            .iter()
            .zip(&self.mean)
            .map(|(o, r)| (o - r).powi(2))
            .sum::<f64>()
            / n;
        let noise = self.variance_of_mean.iter().sum::<f64>() / n;
        (squared - noise).max(0.0).sqrt() / self.image_mean
    }

    /// The relative difference of `image`'s mean from the reference's.
    fn mean_difference(&self, image: &Image) -> f64 {
        let g = grey(image);
        g.iter().sum::<f64>() / g.len() as f64 / self.image_mean - 1.0
    }

    /// The reference's own relative error of the image mean.
    fn mean_noise(&self) -> f64 {
        let n = self.mean.len() as f64;
        (self.variance_of_mean.iter().sum::<f64>()).sqrt() / n / self.image_mean
    }

    /// The reference's own relative RMS noise.
    fn noise(&self) -> f64 {
        (self.variance_of_mean.iter().sum::<f64>() / self.mean.len() as f64).sqrt() / self.image_mean
    }
}

fn grey(image: &Image) -> Vec<f64> {
    image
        .pixels()
        .iter()
        .map(|p| f64::from(p.element_sum()) / 3.0)
        .collect()
}

#[derive(Clone, Copy, Debug, PartialEq)]
enum Method {
    Progressive,
    ProgressiveGather,
    Sppm,
}

impl Method {
    fn name(self) -> &'static str {
        match self {
            Method::Progressive => "progressive (shadow rays)",
            Method::ProgressiveGather => "progressive final gather (4 rays, 4 spp)",
            Method::Sppm => "SPPM",
        }
    }
}

/// (wall seconds, error, image mean's relative difference) after each pass of one run.
fn run(
    method: Method,
    partitioned: &Partitioned,
    reference: &Reference,
    base: RenderSettings,
    budget: Duration,
) -> Result<Vec<(f64, f64, f64)>, String> {
    let mut out = Vec::new();
    match method {
        Method::Progressive | Method::ProgressiveGather => {
            let render = match method {
                Method::Progressive => RenderSettings {
                    mode: Mode::ShadowRays,
                    ..base
                },
                _ => RenderSettings {
                    mode: Mode::FinalGather,
                    samples_per_pixel: 4,
                    final_gather: FinalGatherOptions {
                        gather_rays: 4,
                        ..FinalGatherOptions::default()
                    },
                    ..base
                },
            };
            let settings = ProgressiveSettings {
                passes: None,
                time_budget: Some(budget),
                ..ProgressiveSettings::new(render, 1)
            };
            ProgressiveRenderer::new(GeometryCube, settings)
                .render_observed(partitioned, &(), &mut |acc, stats| {
                    let mean = acc.mean();
                    out.push((
                        stats.wall.as_secs_f64(),
                        reference.error(&mean),
                        reference.mean_difference(&mean),
                    ));
                    ControlFlow::Continue(())
                })
                .map_err(|e| e.to_string())?;
        }
        Method::Sppm => {
            let settings = SppmSettings {
                passes: None,
                time_budget: Some(budget),
                ..SppmSettings::new(base, 1)
            };
            SppmRenderer::new(settings)
                .render_observed(partitioned.scene(), &(), &mut |snapshot| {
                    if let Ok(image) = snapshot.image() {
                        out.push((
                            snapshot.stats().wall.as_secs_f64(),
                            reference.error(&image),
                            reference.mean_difference(&image),
                        ));
                    }
                    ControlFlow::Continue(())
                })
                .map_err(|e| e.to_string())?;
        }
    }
    Ok(out)
}

/// The error of the last pass that ended within `budget` seconds (`None`: no pass did).
fn at_budget(trace: &[(f64, f64, f64)], budget: f64) -> Option<f64> {
    trace
        .iter()
        .rev()
        .find(|(t, _, _)| *t <= budget)
        .map(|&(_, e, _)| e)
}

fn study(args: &Args) -> Result<String, String> {
    let (width, height) = args
        .size
        .split_once('x')
        .and_then(|(w, h)| Some((w.parse().ok()?, h.parse().ok()?)))
        .ok_or_else(|| format!("--size {}: give WIDTHxHEIGHT", args.size))?;
    let budgets: Vec<f64> = args
        .budgets
        .split(',')
        .map(|b| b.trim().parse::<f64>().map_err(|e| format!("--budgets {b}: {e}")))
        .collect::<Result<_, _>>()?;
    let largest = budgets.iter().copied().fold(0.0, f64::max);
    if !(largest > 0.0 && largest.is_finite()) || args.seeds < 2 {
        return Err("give positive budgets and at least 2 seeds".into());
    }
    let scene = scenes::build(&args.scene).map_err(|e| e.to_string())?;
    let partitioned = CreaseAngle::default()
        .partition(scene)
        .map_err(|e| e.to_string())?;
    let base = RenderSettings {
        width,
        height,
        photons: args.photons,
        ..RenderSettings::default()
    };
    base.validate().map_err(|e| e.to_string())?;
    std::fs::create_dir_all(&args.out_dir).map_err(|e| format!("{}: {e}", args.out_dir.display()))?;
    let kept = args.out_dir.join(format!(
        "reference-{}-{width}x{height}-{}x{}.bin",
        args.scene, args.reference_spp, args.reference_replicates
    ));
    let reference = Reference::kept(
        &kept,
        &partitioned,
        base,
        args.reference_spp,
        args.reference_replicates,
    )?;
    let mut md = String::new();
    let _ = writeln!(
        md,
        "## {} ({width}×{height}, {} photons per pass, crease maps, cube estimator)\n\nReference: path tracer, {} replicates × {} spp; its own relative RMS noise per pixel {:.4} (removed from every error below). Errors: relative RMSE per pixel, mean ± standard error over {} seeds (a budget's error is that of the last pass ended within it, wall time from the renderer's start, the guide's learning and the pilot included); z = (camera − uniform) / combined se.\n",
        args.scene,
        args.photons,
        args.reference_replicates,
        args.reference_spp,
        reference.noise(),
        args.seeds
    );
    let _ = writeln!(
        md,
        "| method | budget (s) | uniform | camera-driven | camera / uniform | z |\n|---|---|---|---|---|---|"
    );
    let mut bias = String::new();
    for method in [Method::Progressive, Method::ProgressiveGather, Method::Sppm] {
        let mut traces = [Vec::new(), Vec::new()];
        for (e, emission) in [
            PhotonEmission::Uniform,
            PhotonEmission::CameraDriven(GuideOptions::default()),
        ]
        .into_iter()
        .enumerate()
        {
            for seed in 0..args.seeds {
                let settings = RenderSettings {
                    seed,
                    emission,
                    ..base
                };
                let trace = run(
                    method,
                    &partitioned,
                    &reference,
                    settings,
                    Duration::from_secs_f64(largest),
                )?;
                eprintln!(
                    "{} {} seed {seed}: {} passes, error {:.4} at {:.2} s",
                    method.name(),
                    emission.name(),
                    trace.len(),
                    trace.last().map_or(f64::NAN, |t| t.1),
                    trace.last().map_or(f64::NAN, |t| t.0)
                );
                traces[e].push(trace);
            }
        }
        let last = |runs: &Vec<Vec<(f64, f64, f64)>>| -> Vec<f64> {
            runs.iter().filter_map(|t| t.last().map(|l| l.2)).collect()
        };
        let ((um, us), (cm, cs)) = (
            mean_and_error(&last(&traces[0])),
            mean_and_error(&last(&traces[1])),
        );
        let _ = writeln!(
            bias,
            "| {} | {:+.2} % ± {:.2} % | {:+.2} % ± {:.2} % |",
            method.name(),
            100.0 * um,
            100.0 * us,
            100.0 * cm,
            100.0 * cs
        );
        for &budget in &budgets {
            let read = |runs: &Vec<Vec<(f64, f64, f64)>>| -> Option<Vec<f64>> {
                runs.iter().map(|t| at_budget(t, budget)).collect()
            };
            let (Some(u), Some(c)) = (read(&traces[0]), read(&traces[1])) else {
                let _ = writeln!(
                    md,
                    "| {} | {budget} | no pass ended in time | | | |",
                    method.name()
                );
                continue;
            };
            let ((um, us), (cm, cs)) = (mean_and_error(&u), mean_and_error(&c));
            let z = (cm - um) / (us * us + cs * cs).sqrt().max(f64::MIN_POSITIVE);
            let _ = writeln!(
                md,
                "| {} | {budget} | {um:.4} ± {us:.4} | {cm:.4} ± {cs:.4} | {:.2} | {z:+.1} |",
                method.name(),
                cm / um
            );
        }
    }
    let _ = writeln!(
        md,
        "\nImage mean against the reference's (its own error {:.2} %), after the last pass of the {largest} s runs, mean ± standard error over the seeds:\n\n| method | uniform | camera-driven |\n|---|---|---|\n{bias}",
        100.0 * reference.mean_noise()
    );
    Ok(md)
}

fn main() -> ExitCode {
    let args = Args::parse();
    match study(&args) {
        Ok(md) => {
            print!("{md}");
            let path = args.out_dir.join(format!("emission-study-{}.md", args.scene));
            if let Err(e) = std::fs::create_dir_all(&args.out_dir).and_then(|()| std::fs::write(&path, &md)) {
                eprintln!("emission_study: {}: {e}", path.display());
                return ExitCode::FAILURE;
            }
            eprintln!("wrote {}", path.display());
            ExitCode::SUCCESS
        }
        Err(e) => {
            eprintln!("emission_study: {e}");
            ExitCode::FAILURE
        }
    }
}
