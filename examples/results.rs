//! Reproduces the report's results (its section 8): the 16 timed cases (four scenes ×
//! basic / multiple maps / geometry area / both) plus the ball estimator, each measured against
//! a path-traced reference, written to `results.md` with 2×2 image grids under `results/` in
//! `--out-dir` (default `target/results`; `--out-dir docs` regenerates the repository's own).
//!
//! `cargo run --release --example results -- --out-dir docs` (add `--quick` for a small trial
//! run).

use clap::Parser;
use glam::Vec3;
use photon_maps::kdtree::{Euclidean, KindMask, Neighbours};
use photon_maps::render::{EstimatorKind, Image, Mode, RenderSettings, RenderStats, Renderer};
use photon_maps::trace::{CreaseAngle, Hit, Material, Partitioner, Ray, RayKind, Scene, SingleMap, scenes};
use std::fmt::Write as _;
use std::fs;
use std::path::{Path, PathBuf};
use std::process::ExitCode;
use std::time::Instant;

#[path = "results/markdown.rs"]
mod markdown;
#[path = "results/metrics.rs"]
mod metrics;
#[path = "results/reference.rs"]
mod reference;

use markdown::*;
use metrics::*;
use reference::*;

/// Reproduce the report's table and figures against path-traced references.
#[derive(Parser, Debug)]
#[command(about)]
struct Args {
    /// A small, fast trial run (128×128, few reference samples, one repeat); writes to
    /// target/results-quick unless --out-dir is given.
    #[arg(long)]
    quick: bool,
    /// Worker threads (0 = rayon's global pool: a thread per core unless RAYON_NUM_THREADS says otherwise).
    #[arg(long, default_value_t = 0)]
    threads: usize,
    /// Where results.md and the results/ PNG folder go [default: target/results, quick:
    /// target/results-quick; `--out-dir docs` regenerates the repository's own].
    #[arg(long)]
    out_dir: Option<PathBuf>,
    /// Where path-traced references are cached.
    #[arg(long, default_value = "target/pm-references")]
    cache_dir: PathBuf,
    /// Timed runs per case; the fastest total is reported.
    #[arg(long)]
    repeats: Option<u32>,
    /// Multiplies every scene's reference samples per pixel.
    #[arg(long, default_value_t = 1.0)]
    ref_spp_scale: f32,
}

/// A scene of the report: its Table 1 row and how we render its reference and previews.
struct SceneSpec {
    name: &'static str,
    title: &'static str,
    /// Table 1 of the report: basic, multiple maps, geometry area, both (seconds, 8 threads).
    paper_seconds: [f64; 4],
    /// Path-traced reference samples per pixel at 500×500.
    reference_spp: u32,
    /// PNG exposure in stops.
    exposure: f32,
}

const SCENES: [SceneSpec; 4] = [
    SceneSpec {
        name: "cornell-box",
        title: "Cornell box",
        paper_seconds: [622.1, 555.0, 549.5, 473.6],
        reference_spp: 256,
        exposure: 0.0,
    },
    SceneSpec {
        name: "accordion",
        title: "accordion",
        paper_seconds: [53.4, 34.7, 46.9, 29.2],
        reference_spp: 512,
        exposure: -2.5,
    },
    SceneSpec {
        name: "lit-unlit-rooms",
        title: "lit and unlit rooms",
        paper_seconds: [1412.8, 137.3, 1343.5, 119.7],
        reference_spp: 1024,
        exposure: -4.5,
    },
    SceneSpec {
        name: "colored-rooms",
        title: "coloured rooms",
        paper_seconds: [384.3, 256.1, 325.9, 218.7],
        reference_spp: 1024,
        exposure: -3.0,
    },
];

/// One estimator configuration: the report's four variants and the ball as a fifth.
struct Case {
    label: &'static str,
    maps: &'static str,
    estimator: EstimatorKind,
}

const CASES: [Case; 5] = [
    Case {
        label: "basic",
        maps: "single",
        estimator: EstimatorKind::Disc,
    },
    Case {
        label: "multiple maps",
        maps: "crease",
        estimator: EstimatorKind::Disc,
    },
    Case {
        label: "geometry area",
        maps: "single",
        estimator: EstimatorKind::GeometryCube,
    },
    Case {
        label: "both",
        maps: "crease",
        estimator: EstimatorKind::GeometryCube,
    },
    Case {
        label: "ball",
        maps: "crease",
        estimator: EstimatorKind::GeometryBall,
    },
];

fn partitioner(maps: &str) -> Box<dyn Partitioner> {
    match maps {
        "single" => Box::new(SingleMap),
        _ => Box::new(CreaseAngle::default()),
    }
}

/// Run-wide choices derived from the arguments.
struct Config {
    width: u32,
    height: u32,
    photons: u32,
    k: usize,
    threads: usize,
    repeats: u32,
    ref_spp_scale: f32,
    quick: bool,
    out_dir: PathBuf,
    cache_dir: PathBuf,
}

/// The path-traced reference of a scene and its own noise.
struct Reference {
    image: Image,
    spp: u32,
    /// The first of the two half-sample renders whose mean is `image`.
    half: Image,
    /// Standard error of the reference per pixel and channel, RMS over the fidelity mask:
    /// RMS(A − B) / 2 for the two independent half-sample renders A and B.
    sigma: f32,
    seconds: Option<f64>,
}

/// The figures of one case.
struct CaseResult {
    stats: RenderStats,
    image: Image,
    rmse: f32,
    relative_rmse: f32,
    /// The estimate's own noise (RMS over pixels and channels), from a second photon seed.
    noise: f32,
    leak_ratio: Option<f64>,
    edge: Option<EdgeError>,
}

/// Accordion edge error: mean |estimate − reference| luminance near creases and inside facets.
#[derive(Clone, Copy, Debug)]
struct EdgeError {
    edge_abs: f64,
    interior_abs: f64,
    /// Mean signed (estimate − reference) / mean reference over the edge pixels.
    edge_bias: f64,
    interior_bias: f64,
}

/// Everything measured on one scene.
struct SceneResult {
    spec: &'static SceneSpec,
    reference: Reference,
    reference_leak: Option<f64>,
    cases: Vec<CaseResult>,
    pixel_classes: String,
    /// Mean of the reference over the fidelity mask and the channels.
    reference_mean: f32,
    /// Pixels in the fidelity mask.
    masked_pixels: usize,
}

fn main() -> ExitCode {
    let args = Args::parse();
    match run(&args) {
        Ok(()) => ExitCode::SUCCESS,
        Err(message) => {
            eprintln!("results: {message}");
            ExitCode::FAILURE
        }
    }
}

fn run(args: &Args) -> Result<(), String> {
    let size = if args.quick { 128 } else { 500 };
    let config = Config {
        width: size,
        height: size,
        photons: 100_000,
        k: 100,
        threads: args.threads,
        repeats: args.repeats.unwrap_or(if args.quick { 1 } else { 2 }).max(1),
        ref_spp_scale: if args.quick {
            args.ref_spp_scale / 16.0
        } else {
            args.ref_spp_scale
        },
        quick: args.quick,
        out_dir: args.out_dir.clone().unwrap_or_else(|| {
            PathBuf::from(if args.quick {
                "target/results-quick"
            } else {
                "target/results"
            })
        }),
        cache_dir: args.cache_dir.clone(),
    };
    let images_dir = config.out_dir.join("results");
    fs::create_dir_all(&images_dir).map_err(|e| format!("{}: {e}", images_dir.display()))?;
    fs::create_dir_all(&config.cache_dir).map_err(|e| format!("{}: {e}", config.cache_dir.display()))?;

    let start = Instant::now();
    let mut results = Vec::new();
    for spec in &SCENES {
        let result = run_scene(spec, &config)?;
        write_images(&result, &images_dir)?;
        results.push(result);
    }
    let wall = start.elapsed().as_secs_f64();
    let md_path = config.out_dir.join("results.md");
    let kept = fs::read_to_string(&md_path)
        .ok()
        .and_then(|text| text.split_once(READING_MARKER).map(|(_, tail)| tail.to_owned()))
        .unwrap_or_else(|| "\n## Reading\n\n(write the reading of the figures here)\n".to_owned());
    let text = report(&results, &config, args, wall) + READING_MARKER + &kept;
    fs::write(&md_path, text).map_err(|e| format!("{}: {e}", md_path.display()))?;
    println!("wrote {} in {wall:.0} s", md_path.display());
    Ok(())
}

/// Text after this line in results.md is hand-written and survives regeneration.
const READING_MARKER: &str =
    "<!-- Everything below this line is hand-written and kept when the file is regenerated. -->\n";

fn settings(config: &Config, mode: Mode, spp: u32, seed: u64) -> RenderSettings {
    RenderSettings {
        width: config.width,
        height: config.height,
        samples_per_pixel: spp,
        photons: config.photons,
        k: config.k,
        mode,
        seed,
        threads: config.threads,
        ..RenderSettings::default()
    }
}

fn run_scene(spec: &'static SceneSpec, config: &Config) -> Result<SceneResult, String> {
    let scene = scenes::build(spec.name).map_err(|e| e.to_string())?;
    let mut reference = reference(spec, &scene, config)?;
    let mask = fidelity_mask(&scene, config);
    let reference_mean = masked_mean(&reference.image, &mask);
    // The other half is 2·full − half.
    let other_half = Image::from_fn(config.width, config.height, |x, y| {
        2.0 * reference.image.get(x, y).unwrap_or_default() - reference.half.get(x, y).unwrap_or_default()
    })
    .map_err(|e| e.to_string())?;
    reference.sigma = masked_rmse(&reference.half, &other_half, &mask) / 2.0;
    println!(
        "{}: reference sigma {:.4}, mean {reference_mean:.4}",
        spec.name, reference.sigma
    );
    let classes = match spec.name {
        "lit-unlit-rooms" => Some(room_classes(&scene, config)),
        _ => None,
    };
    let crease_radius = match spec.name {
        "accordion" => Some(accordion_classes(&scene, config)?),
        _ => None,
    };
    let mut cases = Vec::new();
    for case in &CASES {
        let partitioned = partitioner(case.maps)
            .partition(scene.clone())
            .map_err(|e| e.to_string())?;
        let renderer = Renderer::new(case.estimator, settings(config, Mode::PhotonMap, 1, 0));
        let mut best: Option<(RenderStats, Image)> = None;
        for _ in 0..config.repeats {
            let out = renderer.render(&partitioned, &()).map_err(|e| e.to_string())?;
            if best.as_ref().is_none_or(|(s, _)| out.stats.total() < s.total()) {
                best = Some((out.stats, out.image));
            }
        }
        let (stats, image) = best.ok_or("no render")?;
        // The same pixel samples over photon maps of another seed: the photons' own noise.
        let other_maps = Renderer::new(case.estimator, settings(config, Mode::PhotonMap, 1, 1))
            .build_maps(
                partitioned.scene(),
                partitioned.assignment(),
                &(),
                &mut RenderStats::default(),
            )
            .map_err(|e| e.to_string())?;
        let second = renderer
            .render_image(&scene, Some(&other_maps), &())
            .map_err(|e| e.to_string())?;
        let noise = masked_rmse(&image, &second, &mask) / std::f32::consts::SQRT_2;
        let rmse = masked_rmse(&image, &reference.image, &mask);
        let relative_rmse = rmse / reference_mean;
        let leak_ratio = classes.as_ref().map(|c| leak_ratio(&image, c));
        let edge = crease_radius
            .as_ref()
            .map(|c| edge_error(&image, &reference.image, c));
        println!(
            "{} [{}]: trace {:.3} s, build {:.3} s, render {:.3} s, total {:.3} s; RMSE {:.4} ({:.1} %), noise {:.4}{}{}",
            spec.name,
            case.label,
            stats.trace.as_secs_f64(),
            stats.build.as_secs_f64(),
            stats.render.as_secs_f64(),
            stats.total().as_secs_f64(),
            rmse,
            100.0 * relative_rmse,
            noise,
            leak_ratio.map(|l| format!(", leak {l:.4}")).unwrap_or_default(),
            edge.map(|e| format!(", edge {:.4} / interior {:.4}", e.edge_abs, e.interior_abs))
                .unwrap_or_default(),
        );
        cases.push(CaseResult {
            stats,
            image,
            rmse,
            relative_rmse,
            noise,
            leak_ratio,
            edge,
        });
    }
    let reference_leak = classes.as_ref().map(|c| leak_ratio(&reference.image, c));
    let pixel_classes = match (&classes, &crease_radius) {
        (Some(c), _) => format!(
            "{} lit-room and {} dark-room pixels",
            c.iter().filter(|&&r| r == Room::Lit).count(),
            c.iter().filter(|&&r| r == Room::Dark).count()
        ),
        (_, Some(c)) => format!(
            "{} crease pixels and {} interior pixels",
            c.iter().filter(|&&r| r == Facet::Crease).count(),
            c.iter().filter(|&&r| r == Facet::Interior).count()
        ),
        _ => String::new(),
    };
    Ok(SceneResult {
        spec,
        reference,
        reference_leak,
        cases,
        pixel_classes,
        reference_mean,
        masked_pixels: mask.iter().filter(|m| **m).count(),
    })
}
