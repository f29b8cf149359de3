//! Reproduces the report's results (its section 8): the 16 timed cases (four scenes ×
//! basic / multiple maps / geometry area / both) plus the ball estimator, each measured against
//! a path-traced reference, written to `docs/results.md` with 2×2 image grids under
//! `docs/results/`.
//!
//! `cargo run --release --example results` (add `--quick` for a small trial run).

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

/// Reproduce the report's table and figures against path-traced references.
#[derive(Parser, Debug)]
#[command(about)]
struct Args {
    /// A small, fast trial run (128×128, few reference samples, one repeat); writes to
    /// target/results-quick unless --out-dir is given.
    #[arg(long)]
    quick: bool,
    /// Worker threads (0 = all cores).
    #[arg(long, default_value_t = 0)]
    threads: usize,
    /// Where results.md and the results/ PNG folder go (default: docs).
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
                "docs"
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
        let partition = partitioner(case.maps);
        let renderer = Renderer::new(case.estimator, settings(config, Mode::Visualize, 1, 0));
        let mut best: Option<(RenderStats, Image)> = None;
        for _ in 0..config.repeats {
            let out = renderer
                .render(&scene, &*partition, &())
                .map_err(|e| e.to_string())?;
            if best.as_ref().is_none_or(|(s, _)| out.stats.total() < s.total()) {
                best = Some((out.stats, out.image));
            }
        }
        let (stats, image) = best.ok_or("no render")?;
        // The same pixel samples over photon maps of another seed: the photons' own noise.
        let other_maps = Renderer::new(case.estimator, settings(config, Mode::Visualize, 1, 1))
            .build_maps(
                &scene,
                &partition.partition(&scene),
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

/// Part of every cached reference's file name: bump it when a built-in scene or the path
/// tracer changes, so that no result is measured against a stale reference (v2: independent,
/// hashed random streams).
const REFERENCE_VERSION: &str = "v2";

/// Loads the cached reference, or renders it as two half-sample images with independent seeds
/// (their difference gives the reference's own noise) and caches both.
fn reference(spec: &SceneSpec, scene: &Scene, config: &Config) -> Result<Reference, String> {
    let spp = ((spec.reference_spp as f32 * config.ref_spp_scale).round() as u32 / 2).max(1) * 2;
    let stem = format!(
        "{}-{}x{}-{spp}-{REFERENCE_VERSION}",
        spec.name, config.width, config.height
    );
    let full_path = config.cache_dir.join(format!("{stem}.exr"));
    let half_path = config.cache_dir.join(format!("{stem}-half.exr"));
    if let (Ok(full), Ok(half)) = (Image::read_exr(&full_path), Image::read_exr(&half_path)) {
        println!(
            "{}: reference {} (cached; delete it, or bump REFERENCE_VERSION, after changing a scene or the path tracer)",
            spec.name,
            full_path.display()
        );
        return Ok(Reference {
            image: full,
            half,
            spp,
            sigma: f32::NAN,
            seconds: None,
        });
    }
    let start = Instant::now();
    let render_half = |seed| {
        Renderer::new(
            EstimatorKind::Disc,
            settings(config, Mode::PathTrace, spp / 2, seed),
        )
        .render(scene, &SingleMap, &())
        .map(|out| out.image)
        .map_err(|e| e.to_string())
    };
    let a = render_half(1001)?;
    let b = render_half(2002)?;
    let full = Image::from_fn(a.width(), a.height(), |x, y| {
        0.5 * (a.get(x, y).unwrap_or_default() + b.get(x, y).unwrap_or_default())
    })
    .map_err(|e| e.to_string())?;
    let seconds = start.elapsed().as_secs_f64();
    full.write_exr(&full_path).map_err(|e| e.to_string())?;
    a.write_exr(&half_path).map_err(|e| e.to_string())?;
    println!(
        "{}: reference {} ({spp} spp, {seconds:.0} s)",
        spec.name,
        full_path.display()
    );
    Ok(Reference {
        image: full,
        half: a,
        spp,
        sigma: f32::NAN,
        seconds: Some(seconds),
    })
}

/// True when the eye path of `ray` (first hit `hit`), followed through mirrors, meets an
/// emitter or glass.
fn sees_emitter(scene: &Scene, mut ray: Ray, mut hit: Hit) -> bool {
    for _ in 0..8 {
        if scene.emission(&hit) != Vec3::ZERO {
            return true;
        }
        match scene.material(&hit) {
            Material::Mirror { .. } => {
                let d = ray.direction;
                ray = scene.spawn_ray(&hit, d - 2.0 * d.dot(hit.normal) * hit.normal);
                match scene.intersect(&ray, f32::INFINITY, RayKind::Camera) {
                    Some(next) => hit = next,
                    None => return false,
                }
            }
            Material::Glass { .. } => return true,
            _ => return false,
        }
    }
    false
}

/// Pixels that count in the fidelity figures: all but those that see an emitter through their
/// centre or next to it. At one sample per pixel a pixel on a light's outline is either the
/// light or its surround (two pixels of margin), while the reference averages both: a large error that says
/// nothing about the estimators, which never see emitters.
fn fidelity_mask(scene: &Scene, config: &Config) -> Vec<bool> {
    let hits = first_hits(scene, config);
    let (w, h) = (config.width as i64, config.height as i64);
    let emits = |x: i64, y: i64| {
        x >= 0 && y >= 0 && x < w && y < h && hits[(y * w + x) as usize].is_some_and(|(_, e)| e)
    };
    let mut mask = Vec::with_capacity(hits.len());
    for y in 0..h {
        for x in 0..w {
            let near = (-2..=2).any(|dy| (-2..=2).any(|dx| emits(x + dx, y + dy)));
            mask.push(!near);
        }
    }
    mask
}

/// RMS over the masked pixels and their channels of `a − b`.
fn masked_rmse(a: &Image, b: &Image, mask: &[bool]) -> f32 {
    let (sum, n) = a
        .pixels()
        .iter()
        .zip(b.pixels())
        .zip(mask)
        .filter(|(_, m)| **m)
        .fold((0.0f64, 0usize), |(s, n), ((p, q), _)| {
            (s + (p.as_dvec3() - q.as_dvec3()).length_squared(), n + 1)
        });
    (sum / (3 * n.max(1)) as f64).sqrt() as f32
}

/// Mean over the masked pixels and channels.
fn masked_mean(a: &Image, mask: &[bool]) -> f32 {
    let (sum, n) = a
        .pixels()
        .iter()
        .zip(mask)
        .filter(|(_, m)| **m)
        .fold((0.0f64, 0usize), |(s, n), (p, _)| {
            (s + p.as_dvec3().element_sum(), n + 1)
        });
    (sum / (3 * n.max(1)) as f64) as f32
}

fn luminance(c: Vec3) -> f64 {
    (0.2126 * c.x + 0.7152 * c.y + 0.0722 * c.z) as f64
}

/// The first surface seen through each pixel centre, row by row (`None` for a miss), and
/// whether the eye path, followed through mirrors, reaches an emitter or glass.
fn first_hits(scene: &Scene, config: &Config) -> Vec<Option<(Vec3, bool)>> {
    let camera = scene.camera();
    let aspect = config.width as f32 / config.height as f32;
    let mut out = Vec::with_capacity((config.width * config.height) as usize);
    for y in 0..config.height {
        for x in 0..config.width {
            let u = (x as f32 + 0.5) / config.width as f32;
            let v = (y as f32 + 0.5) / config.height as f32;
            let ray = camera.ray(u, v, aspect);
            out.push(
                scene
                    .intersect(&ray, f32::INFINITY, RayKind::Camera)
                    .map(|h| (h.position, sees_emitter(scene, ray, h))),
            );
        }
    }
    out
}

/// Which room of `lit-unlit-rooms` a pixel shows.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Room {
    Lit,
    Dark,
    Neither,
}

/// The lit room spans x ∈ [0, 1], the dark one x ∈ [1.02, 2.02] (pm-trace's rooms scene); a
/// pixel belongs to the room its camera ray's first hit lies in.
fn room_classes(scene: &Scene, config: &Config) -> Vec<Room> {
    first_hits(scene, config)
        .into_iter()
        .map(|hit| match hit.map(|(p, _)| p) {
            Some(p) if p.x < 1.0 - 1e-4 => Room::Lit,
            Some(p) if p.x > 1.02 + 1e-4 => Room::Dark,
            _ => Room::Neither,
        })
        .collect()
}

/// Mean luminance over the dark room's pixels divided by the lit room's (the truth is 0).
fn leak_ratio(image: &Image, classes: &[Room]) -> f64 {
    let mean = |room: Room| {
        let (sum, count) = image
            .pixels()
            .iter()
            .zip(classes)
            .filter(|(_, c)| **c == room)
            .fold((0.0, 0usize), |(s, n), (p, _)| (s + luminance(*p), n + 1));
        sum / count.max(1) as f64
    };
    mean(Room::Dark) / mean(Room::Lit)
}

/// Where a pixel of the accordion lies relative to the creases.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Facet {
    /// Within one search radius of an interior crease.
    Crease,
    /// Farther than one search radius from every crease and from the strip's border.
    Interior,
    /// Near the border only, or off the strip.
    Other,
}

/// The accordion's facets are 0.25 m wide at ±45°: its folds lie at x = i·STEP, along z
/// (pm-trace's accordion scene; checked against the scene bounds).
const ACCORDION_STEP: f32 = 0.25 * std::f32::consts::FRAC_1_SQRT_2;
const ACCORDION_FACETS: usize = 8;

/// Classifies each pixel by the distance of its first hit to the nearest crease, measured
/// against that point's own search radius: the distance to its k-th nearest photon in the
/// single map (the disc estimator's radius).
fn accordion_classes(scene: &Scene, config: &Config) -> Result<Vec<Facet>, String> {
    let width = scene.bounds().max.x - scene.bounds().min.x;
    let expected = ACCORDION_FACETS as f32 * ACCORDION_STEP;
    if (width - expected).abs() > 0.05 * expected {
        return Err(format!(
            "accordion is {width} m wide, expected {expected} m: update ACCORDION_STEP"
        ));
    }
    let s = settings(config, Mode::Visualize, 1, 0);
    let renderer = Renderer::new(EstimatorKind::Disc, s);
    let assignment = SingleMap.partition(scene);
    let maps = renderer
        .build_maps(scene, &assignment, &(), &mut RenderStats::default())
        .map_err(|e| e.to_string())?;
    let tree = maps.map(0).tree();
    let max_distance = s.estimator_options(&scene.bounds()).max_distance;
    let fold = |i: usize| {
        let y = if i.is_multiple_of(2) { 0.0 } else { ACCORDION_STEP };
        glam::Vec2::new(i as f32 * ACCORDION_STEP, y)
    };
    let mut neighbours = Neighbours::new();
    Ok(first_hits(scene, config)
        .into_iter()
        .map(|hit| {
            let Some((p, _)) = hit else { return Facet::Other };
            tree.nearest_k::<Euclidean>(p, config.k, max_distance, KindMask::ALL, &mut neighbours);
            let r = neighbours.extent();
            let xy = glam::Vec2::new(p.x, p.y);
            let crease = (1..ACCORDION_FACETS)
                .map(|i| xy.distance(fold(i)))
                .fold(f32::INFINITY, f32::min);
            let border = xy
                .distance(fold(0))
                .min(xy.distance(fold(ACCORDION_FACETS)))
                .min(p.z)
                .min(1.0 - p.z);
            if crease < r {
                Facet::Crease
            } else if border >= r {
                Facet::Interior
            } else {
                Facet::Other
            }
        })
        .collect())
}

fn edge_error(image: &Image, reference: &Image, classes: &[Facet]) -> EdgeError {
    let stats = |class: Facet| {
        let (mut abs, mut signed, mut truth, mut n) = (0.0, 0.0, 0.0, 0usize);
        for ((p, r), c) in image.pixels().iter().zip(reference.pixels()).zip(classes) {
            if *c == class {
                let (e, t) = (luminance(*p), luminance(*r));
                abs += (e - t).abs();
                signed += e - t;
                truth += t;
                n += 1;
            }
        }
        let n = n.max(1) as f64;
        (abs / n, signed / truth.max(f64::MIN_POSITIVE))
    };
    let (edge_abs, edge_bias) = stats(Facet::Crease);
    let (interior_abs, interior_bias) = stats(Facet::Interior);
    EdgeError {
        edge_abs,
        interior_abs,
        edge_bias,
        interior_bias,
    }
}

fn write_images(result: &SceneResult, dir: &Path) -> Result<(), String> {
    let name = result.spec.name;
    let exposure = result.spec.exposure;
    let c = &result.cases;
    let grid =
        Image::grid_2x2([&c[0].image, &c[1].image, &c[2].image, &c[3].image]).map_err(|e| e.to_string())?;
    let write = |image: &Image, suffix: &str| {
        image
            .write_png(dir.join(format!("{name}-{suffix}.png")), exposure)
            .map_err(|e| e.to_string())
    };
    write(&grid, "grid")?;
    write(&result.reference.image, "reference")?;
    write(&c[4].image, "ball")
}

fn machine() -> (String, usize) {
    let cpu = fs::read_to_string("/proc/cpuinfo")
        .ok()
        .and_then(|text| {
            text.lines()
                .find(|l| l.starts_with("model name"))
                .and_then(|l| l.split_once(':'))
                .map(|(_, v)| v.trim().to_owned())
        })
        .unwrap_or_else(|| "unknown CPU".to_owned());
    let cores = std::thread::available_parallelism().map_or(1, |n| n.get());
    (cpu, cores)
}

fn today() -> String {
    std::process::Command::new("date")
        .args(["-u", "+%Y-%m-%d %H:%M UTC"])
        .output()
        .ok()
        .and_then(|o| String::from_utf8(o.stdout).ok())
        .map(|s| s.trim().to_owned())
        .unwrap_or_else(|| "unknown date".to_owned())
}

fn command_line(args: &Args) -> String {
    let mut cmd = String::from("cargo run --release --example results");
    let mut extra = Vec::new();
    if args.quick {
        extra.push("--quick".to_owned());
    }
    if args.threads != 0 {
        extra.push(format!("--threads {}", args.threads));
    }
    if let Some(r) = args.repeats {
        extra.push(format!("--repeats {r}"));
    }
    if args.ref_spp_scale != 1.0 {
        extra.push(format!("--ref-spp-scale {}", args.ref_spp_scale));
    }
    if !extra.is_empty() {
        cmd += " -- ";
        cmd += &extra.join(" ");
    }
    cmd
}

/// The generated part of results.md.
fn report(results: &[SceneResult], config: &Config, args: &Args, wall: f64) -> String {
    let (cpu, cores) = machine();
    let threads = results
        .first()
        .and_then(|r| r.cases.first())
        .map_or(0, |c| c.stats.threads);
    let mut o = String::new();
    let w = &mut o;
    let _ = writeln!(w, "# Reproduced results\n");
    let _ = writeln!(
        w,
        "Generated by `{}` on {} ({wall:.0} s wall clock, references included{}).\n",
        command_line(args),
        today(),
        if results.iter().all(|r| r.reference.seconds.is_none()) {
            ", all from the cache"
        } else {
            ""
        }
    );
    let _ = writeln!(
        w,
        "Machine: {cpu}, {cores} logical cores (`nproc`), {threads} rendering threads. Every case: {}×{}, {} photons emitted, k = {}, one sample per pixel, `Visualize` mode, seed 0; times are the fastest of {} runs of the whole case (trace + build + render). The machine is shared, so times vary by ±20 %.{}\n",
        config.width,
        config.height,
        config.photons,
        config.k,
        config.repeats,
        if config.quick {
            " **Quick run: not the real figures.**"
        } else {
            ""
        },
    );

    let _ = writeln!(w, "## Table 1: seconds per case, the report's beside ours\n");
    let _ = writeln!(
        w,
        "The report: Intel i7-4770k, 8 threads. Speed-up = report / ours.\n"
    );
    let _ = writeln!(
        w,
        "| scene | basic | multiple maps | geometry area | both |\n|---|---|---|---|---|"
    );
    for r in results {
        let cells: Vec<String> = (0..4)
            .map(|i| {
                let ours = r.cases[i].stats.total().as_secs_f64();
                format!(
                    "{:.1} / **{ours:.2}** ({:.0}×)",
                    r.spec.paper_seconds[i],
                    r.spec.paper_seconds[i] / ours
                )
            })
            .collect();
        let _ = writeln!(w, "| {} | {} |", r.spec.title, cells.join(" | "));
    }
    let over: Vec<String> = results
        .iter()
        .flat_map(|r| {
            r.cases[..4]
                .iter()
                .zip(CASES.iter())
                .filter(|(c, _)| c.stats.total().as_secs_f64() > 1.0)
                .map(move |(c, case)| {
                    format!(
                        "{} / {} ({:.2} s)",
                        r.spec.title,
                        case.label,
                        c.stats.total().as_secs_f64()
                    )
                })
        })
        .collect();
    let _ = writeln!(
        w,
        "\nGoal ≤ 1.0 s per case: {} of 16 met{}.\n",
        16 - over.len(),
        if over.is_empty() {
            String::new()
        } else {
            format!("; over: {}", over.join(", "))
        }
    );

    let _ = writeln!(w, "## Phase split (seconds: trace + build + render = total)\n");
    let _ = writeln!(
        w,
        "| scene | case | maps | estimator | photons stored | trace | build | render | total |\n|---|---|---|---|---|---|---|---|---|"
    );
    for r in results {
        for (c, case) in r.cases.iter().zip(CASES.iter()) {
            let s = &c.stats;
            let _ = writeln!(
                w,
                "| {} | {} | {} ({}) | {} | {} | {:.3} | {:.3} | {:.3} | {:.3} |",
                r.spec.title,
                case.label,
                case.maps,
                s.map_count,
                case.estimator.name(),
                s.photons_stored,
                s.trace.as_secs_f64(),
                s.build.as_secs_f64(),
                s.render.as_secs_f64(),
                s.total().as_secs_f64()
            );
        }
    }

    let _ = writeln!(w, "\n## Fidelity against the path-traced reference\n");
    let _ = writeln!(
        w,
        "RMSE is over the RGB channels of the linear radiance image, over every pixel except those within two pixels of one whose centre ray sees a light, directly or through the mirror (at one sample per pixel a light's outline is all light or all surround while the reference averages both; that error says nothing about the estimators, which never look at emitters). Relative RMSE divides it by the reference's mean over the same pixels. *Noise* is the case's own per-pixel standard deviation, RMS(I₀ − I₁)/√2 for two images rendered from the same pixel samples over photon maps traced with seeds 0 and 1. σ_ref is the reference's standard error, RMS(A − B)/2 for its two half-sample renders A and B. Since RMSE² ≈ bias² + noise² + σ_ref², *bias* = √(RMSE² − noise² − σ_ref²) is the systematic part (0 when the subtraction goes negative).\n"
    );
    let _ = writeln!(
        w,
        "| scene | reference spp | σ_ref (RMS) | reference mean | pixels counted |\n|---|---|---|---|---|"
    );
    for r in results {
        let _ = writeln!(
            w,
            "| {} | {} | {:.4} | {:.4} | {} |",
            r.spec.title, r.reference.spp, r.reference.sigma, r.reference_mean, r.masked_pixels
        );
    }
    let _ = writeln!(
        w,
        "\n| scene | case | RMSE | relative RMSE | noise | bias |\n|---|---|---|---|---|---|"
    );
    for r in results {
        for (c, case) in r.cases.iter().zip(CASES.iter()) {
            let bias2 =
                (c.rmse as f64).powi(2) - (c.noise as f64).powi(2) - (r.reference.sigma as f64).powi(2);
            let _ = writeln!(
                w,
                "| {} | {} | {:.4} | {:.1} % | {:.4} | {:.4} |",
                r.spec.title,
                case.label,
                c.rmse,
                100.0 * c.relative_rmse,
                c.noise,
                bias2.max(0.0).sqrt()
            );
        }
    }

    let _ = writeln!(w, "\n## Ball against cube (crease maps)\n");
    let _ = writeln!(
        w,
        "| scene | cube noise | ball noise | ball / cube | cube RMSE | ball RMSE | cube s | ball s |\n|---|---|---|---|---|---|---|---|"
    );
    for r in results {
        let (cube, ball) = (&r.cases[3], &r.cases[4]);
        let _ = writeln!(
            w,
            "| {} | {:.4} | {:.4} | {:.2} | {:.4} | {:.4} | {:.2} | {:.2} |",
            r.spec.title,
            cube.noise,
            ball.noise,
            ball.noise / cube.noise,
            cube.rmse,
            ball.rmse,
            cube.stats.total().as_secs_f64(),
            ball.stats.total().as_secs_f64()
        );
    }

    for r in results {
        if let Some(reference_leak) = r.reference_leak {
            let _ = writeln!(w, "\n## Leak ratio, {}\n", r.spec.title);
            let _ = writeln!(
                w,
                "Mean luminance over the dark room's pixels divided by the lit room's; the truth is 0. A pixel belongs to the room its camera ray (through the pixel centre) first hits ({}). Reference: {reference_leak:.2e}.\n",
                r.pixel_classes
            );
            let _ = writeln!(w, "| case | leak ratio |\n|---|---|");
            for (c, case) in r.cases.iter().zip(CASES.iter()) {
                let _ = writeln!(w, "| {} | {:.2e} |", case.label, c.leak_ratio.unwrap_or(f64::NAN));
            }
        }
        if r.cases.iter().any(|c| c.edge.is_some()) {
            let _ = writeln!(w, "\n## Edge error, {}\n", r.spec.title);
            let _ = writeln!(
                w,
                "Mean |estimate − reference| of luminance over pixels whose first hit lies within one search radius of a crease (the distance to the point's k-th nearest photon in the single map), against pixels farther than that from every crease and from the strip's border ({}). Bias is the signed mean error divided by the reference's mean over the same pixels. The truth is the path-traced reference rather than E₀cos θ: the folds face each other at 90° with albedo 0.8, so interreflection adds a large, position-dependent share that the direct term leaves out.\n",
                r.pixel_classes
            );
            let _ = writeln!(
                w,
                "| case | crease \\|error\\| | interior \\|error\\| | crease bias | interior bias |\n|---|---|---|---|---|"
            );
            for (c, case) in r.cases.iter().zip(CASES.iter()) {
                if let Some(e) = c.edge {
                    let _ = writeln!(
                        w,
                        "| {} | {:.4} | {:.4} | {:+.1} % | {:+.1} % |",
                        case.label,
                        e.edge_abs,
                        e.interior_abs,
                        100.0 * e.edge_bias,
                        100.0 * e.interior_bias
                    );
                }
            }
        }
    }

    let _ = writeln!(w, "\n## Images\n");
    let _ = writeln!(
        w,
        "Each grid is the report's arrangement: basic top left, multiple maps top right, geometry area bottom left, both bottom right. Previews are 8-bit sRGB at the stated exposure; the numbers above come from the linear images.\n"
    );
    for r in results {
        let n = r.spec.name;
        let _ = writeln!(
            w,
            "### {} (exposure {:+} stops)\n\n![{n} grid](results/{n}-grid.png)\n\nPath-traced reference ({} spp) and the ball estimator with crease maps:\n\n<img src=\"results/{n}-reference.png\" width=\"49%\"> <img src=\"results/{n}-ball.png\" width=\"49%\">\n",
            r.spec.title, r.spec.exposure, r.reference.spp
        );
    }
    o
}
