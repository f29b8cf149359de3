//! The convergence study: relative RMSE against a path-traced reference versus rendering
//! seconds for path tracing, SPPM, the progressive renderer (disc, cube and ball with crease
//! maps), the final gather and the progressive final gather on the report's four scenes; the
//! light leaked into the unlit room and the accordion's crease bias per pass count. Writes
//! `convergence.md` and `images/convergence-<scene>.png` into `--out-dir` (default
//! `target/convergence`; `--out-dir docs` regenerates the repository's own).
//!
//! Each (scene, method) is run once, to the largest budget, and the accumulated image's error
//! is read after every pass (off the clock): the error at a budget is that of the last pass
//! that ended within it. So the study takes about scenes × methods × the largest budget (about
//! 30 minutes on 2 cores), plus the references. Those are kept in `--reference-dir` and
//! reused; without it, the repository's `docs/convergence-references` (125×125, made by this
//! example) are read, and a reference they lack is made in `target/convergence-references`:
//! nothing is written into the repository unless its folder is named. `--extend-references S`
//! path traces S more seconds into each (it needs `--reference-dir`), `--references-only` stops
//! after them. Without one, a `results` reference of a whole multiple of the size is
//! box-filtered down, or else one is path traced for `--reference-seconds`.
//!
//! `--save-run DIR` keeps what the study measured and, per scene and method, the image each
//! budget's error is read from; `--rescore DIR` measures those images again against the
//! references as they are now and rewrites the Markdown and charts in seconds, so extending
//! a reference does not need the study run again.
//!
//! The full study: `cargo run --release --example convergence -- --clock cpu --out-dir docs`
//! A smoke test in seconds (writes under `target/convergence`):
//! `cargo run --release --example convergence -- --quick`

#[path = "convergence/chart.rs"]
mod chart;
#[path = "convergence/clock.rs"]
mod clock;
#[path = "../tests/support/dark_room.rs"]
mod dark_room;
#[path = "convergence/mask.rs"]
mod mask;
#[path = "convergence/memory.rs"]
mod memory;
#[path = "convergence/methods.rs"]
mod methods;
#[path = "convergence/per_pass.rs"]
mod per_pass;
#[path = "convergence/reference.rs"]
mod reference;
#[path = "convergence/report.rs"]
mod report;
#[path = "convergence/saved.rs"]
mod saved;
#[path = "convergence/study_scene.rs"]
mod study_scene;
// Counts heap bytes for the memory table (an atomic add per allocation; the render loops do
// not allocate once warm).
#[path = "../tests/support/tracking_allocator.rs"]
mod tracking_allocator;

use clap::{Parser, ValueEnum};
use methods::{Method, Progressive, Run};
use photon_maps::render::{FinalGatherOptions, Mode, RenderSettings};
use photon_maps::trace::scenes;
use report::{SceneResult, Study};
use std::path::PathBuf;
use std::process::ExitCode;

/// How the progressive renderer lights the first diffuse hit.
#[derive(Clone, Copy, Debug, PartialEq, Eq, ValueEnum)]
enum Direct {
    /// Shadow rays for direct light, photons for the rest (as SPPM has it).
    ShadowRays,
    /// Photons for all light.
    Photons,
}

/// Convergence of progressive photon mapping against SPPM and path tracing.
#[derive(Parser, Debug)]
struct Args {
    /// A small, fast run for smoke tests: 24×24 pixels, 4,000 photons per pass, budgets up to
    /// 0.2 s, 1 s references, pass counts 1, 2, 4 (explicit options still win).
    #[arg(long)]
    quick: bool,
    /// Image side in pixels (square images) [default: 125, a quarter of the `results` references' 500; quick: 24].
    #[arg(long)]
    size: Option<u32>,
    /// Photon paths per pass, for SPPM and the progressive renderer [default: 50000; quick: 4000].
    #[arg(long)]
    photons: Option<u32>,
    /// Wall-time budgets in seconds, comma-separated [default: 0.5,1,2,4,8,15,30,60].
    #[arg(long)]
    budgets: Option<String>,
    /// Pass counts of the leak and crease tables, comma-separated [default: 1,4,16,64].
    #[arg(long)]
    pass_counts: Option<String>,
    /// Seconds of path tracing per reference [default: 600; quick: 1].
    #[arg(long)]
    reference_seconds: Option<f64>,
    /// Seconds of path tracing to add to each cached reference this example path traced
    /// (new batches into the same two halves; 0: use them as they are).
    #[arg(long, default_value_t = 0.0)]
    extend_references: f64,
    /// Render (or extend) the references, report their noise, and stop.
    #[arg(long)]
    references_only: bool,
    /// Where references are kept (one EXR, its first half and a note per scene and size; delete
    /// to re-render) [default: read from docs/convergence-references, the study's own in the
    /// repository, and made in target/convergence-references where that has none; quick:
    /// target/convergence-quick-references].
    #[arg(long)]
    reference_dir: Option<PathBuf>,
    /// Where the `results` example caches its (larger) references: one whose size is a whole
    /// multiple of `--size` (500 for 125) is box-filtered down instead of path tracing anew.
    #[arg(long, default_value = "target/pm-references")]
    results_references: PathBuf,
    /// Scenes, comma-separated: built-in names or glTF files (filed under their stems).
    #[arg(long, default_value = "cornell-box,lit-unlit-rooms,colored-rooms,accordion")]
    scenes: String,
    /// Worker threads for every renderer.
    #[arg(long, default_value_t = 2)]
    threads: usize,
    /// The progressive renderer's direct light.
    #[arg(long, value_enum, default_value_t = Direct::ShadowRays)]
    direct: Direct,
    /// Methods, comma-separated, of path-trace, sppm, disc, cube, ball, final-gather and
    /// progressive-gather (the per-pass tables always show the progressive ones and SPPM).
    #[arg(
        long,
        default_value = "path-trace,sppm,disc,cube,ball,final-gather,progressive-gather"
    )]
    methods: String,
    /// Gather rays per camera sample of the final-gather methods (4 and 16 samples per pass
    /// had the lowest error at 8 s of four settings tried on the Cornell box and the lit/unlit
    /// rooms).
    #[arg(long, default_value_t = 4)]
    gather_rays: u32,
    /// Camera samples per pixel per pass of the final-gather methods (a pass traces its
    /// photons and precomputes its cache once for all of them).
    #[arg(long, default_value_t = 16)]
    gather_samples: u32,
    /// Jensen's extra bounce of the final-gather methods: a gather ray whose diffuse hit lies
    /// closer than this (metres) to its origin takes one more bounce instead of reading the
    /// cache (0: never) [default: the renderer's, 5 % of each scene's bounding-box diagonal].
    #[arg(long)]
    corner_distance: Option<f32>,
    /// k of the progressive renderer's pilot extents (SPPM's initial radius keeps k = 100).
    #[arg(long, default_value_t = 100)]
    progressive_k: usize,
    /// The progressive renderer's α (Knaus & Zwicker).
    #[arg(long, default_value_t = 2.0 / 3.0)]
    alpha: f32,
    /// What the budgets count: wall time, or CPU time over the thread count (steadier on a
    /// shared machine).
    #[arg(long, value_enum, default_value_t = clock::ClockKind::Wall)]
    clock: clock::ClockKind,
    /// Measure the errors over every pixel, light sources and their outlines included.
    #[arg(long)]
    all_pixels: bool,
    /// Skip the leak and crease tables (for quick experiments with the convergence tables).
    #[arg(long)]
    no_per_pass: bool,
    /// Output folder: writes convergence.md there and the charts in its images/ folder
    /// (`--out-dir docs` regenerates the repository's own).
    #[arg(long, default_value = "target/convergence")]
    out_dir: PathBuf,
    /// Keep what the study measured in this folder (`study.json`, and per scene and method
    /// the image each budget's error is read from) so that `--rescore` can measure it again.
    #[arg(long, conflicts_with = "references_only")]
    save_run: Option<PathBuf>,
    /// Measure a run kept by `--save-run` in this folder again, against the references in
    /// `--reference-dir` as they are now (after `--extend-references`, say), and write the
    /// Markdown and charts to `--out-dir`, rendering nothing.
    #[arg(long, conflicts_with_all = [
        "quick", "size", "photons", "budgets", "pass_counts", "reference_seconds",
        "extend_references", "references_only", "results_references", "scenes", "threads",
        "direct", "methods", "gather_rays", "gather_samples", "corner_distance",
        "progressive_k", "alpha", "clock", "all_pixels", "no_per_pass", "save_run",
    ])]
    rescore: Option<PathBuf>,
    /// TrueType font for the charts' labels.
    #[arg(long, default_value = "/usr/share/fonts/truetype/dejavu/DejaVuSans.ttf")]
    font: PathBuf,
}

fn main() -> ExitCode {
    match run(&Args::parse()) {
        Ok(()) => ExitCode::SUCCESS,
        Err(e) => {
            eprintln!("convergence: {e}");
            ExitCode::FAILURE
        }
    }
}

/// The repository's references, read (never written) when `--reference-dir` is not given.
const REPOSITORY_REFERENCES: &str = "docs/convergence-references";

/// Where the reference of scene `name` at `size`² is kept: the folder named, or else the
/// repository's own where it has this one, or a scratch folder under `target/` (so that a run
/// naming no folder writes nothing into the repository).
fn reference_dir(args: &Args, name: &str, size: u32) -> PathBuf {
    if let Some(dir) = &args.reference_dir {
        return dir.clone();
    }
    if args.quick {
        return PathBuf::from("target/convergence-quick-references");
    }
    let repository = PathBuf::from(REPOSITORY_REFERENCES);
    if repository.join(format!("{name}-{size}x{size}.exr")).is_file() {
        repository
    } else {
        PathBuf::from("target/convergence-references")
    }
}

fn list<T: std::str::FromStr>(text: &str, what: &str) -> Result<Vec<T>, String> {
    text.split(',')
        .map(|t| t.trim().parse().map_err(|_| format!("{what}: cannot read {t:?}")))
        .collect()
}

fn run(args: &Args) -> Result<(), String> {
    if let Some(record) = &args.rescore {
        let charts = chart::register_font(&args.font);
        if let Err(e) = &charts {
            eprintln!("convergence: {e}; charts are not drawn");
        }
        saved::rescore(&saved::Rescore {
            record,
            references: args
                .reference_dir
                .as_deref()
                .unwrap_or(REPOSITORY_REFERENCES.as_ref()),
            out_dir: &args.out_dir,
            charts: charts.is_ok(),
        })?;
        eprintln!("wrote {}", args.out_dir.join("convergence.md").display());
        return Ok(());
    }
    let q = args.quick;
    let size = args.size.unwrap_or(if q { 24 } else { 125 });
    let photons = args.photons.unwrap_or(if q { 4_000 } else { 50_000 });
    let budgets: Vec<f64> = list(
        args.budgets.as_deref().unwrap_or(if q {
            "0.02,0.05,0.1,0.15,0.2"
        } else {
            "0.5,1,2,4,8,15,30,60"
        }),
        "--budgets",
    )?;
    let counts: Vec<u64> = list(
        args.pass_counts
            .as_deref()
            .unwrap_or(if q { "1,2,4" } else { "1,4,16,64" }),
        "--pass-counts",
    )?;
    let reference_seconds = reference::Budget {
        seconds: args.reference_seconds.unwrap_or(if q { 1.0 } else { 600.0 }),
        extend: args.extend_references,
    };
    if !(reference_seconds.seconds > 0.0 && reference_seconds.extend >= 0.0) {
        return Err("--reference-seconds must be positive and --extend-references not negative".into());
    }
    if reference_seconds.extend > 0.0 && args.reference_dir.is_none() {
        return Err(format!(
            "--extend-references writes into the references: name their folder (--reference-dir {REPOSITORY_REFERENCES} extends the repository's own)"
        ));
    }
    if budgets.is_empty() || budgets.iter().any(|b| !(b.is_finite() && *b > 0.0)) {
        return Err("--budgets must be positive seconds".into());
    }
    if counts.contains(&0) {
        return Err("--pass-counts must be at least 1".into());
    }
    let max_budget = budgets.iter().copied().fold(0.0, f64::max);
    let progressive = Progressive {
        direct: match args.direct {
            Direct::ShadowRays => Mode::ShadowRays,
            Direct::Photons => Mode::PhotonMap,
        },
        k: args.progressive_k,
        alpha: args.alpha,
        final_gather: FinalGatherOptions {
            gather_rays: args.gather_rays,
            corner_distance: args.corner_distance,
            ..FinalGatherOptions::default()
        },
        gather_samples: args.gather_samples,
    };
    progressive.final_gather.validate().map_err(|e| e.to_string())?;
    let chosen: Vec<Method> = args
        .methods
        .split(',')
        .map(|m| {
            let m = m.trim();
            Method::ALL
                .into_iter()
                .chain(Method::EXTRA)
                .find(|x| x.name() == m)
                .ok_or_else(|| format!("--methods: unknown method {m:?}"))
        })
        .collect::<Result<_, _>>()?;
    let base = RenderSettings {
        width: size,
        height: size,
        photons,
        seed: 1,
        threads: args.threads,
        ..RenderSettings::default()
    };
    let images = args.out_dir.join("images");
    std::fs::create_dir_all(&images).map_err(|e| format!("{}: {e}", images.display()))?;
    let font = chart::register_font(&args.font);
    if let Err(e) = &font {
        eprintln!("convergence: {e}; charts are not drawn");
    }
    let mut study = Study {
        command: std::env::args().skip(1).collect::<Vec<_>>().join(" "),
        size,
        photons,
        threads: args.threads,
        clock: format!("{:?}", args.clock),
        direct: format!(
            "{}, k = {}, α = {:.3}",
            match args.direct {
                Direct::ShadowRays => "shadow rays",
                Direct::Photons => "photons",
            },
            args.progressive_k,
            args.alpha
        ),
        gather: progressive.describe_gather(),
        all_pixels: args.all_pixels,
        budgets: budgets.clone(),
        scenes: Vec::new(),
        leaks: Vec::new(),
        creases: Vec::new(),
        memory: Vec::new(),
        rescored: None,
    };
    for source in args.scenes.split(',').map(str::trim) {
        let (scene, name) = study_scene::load(source)?;
        let name = name.as_str();
        let reference = reference::reference(
            name,
            &scene,
            base,
            reference_seconds,
            (&reference_dir(args, name, size), &args.results_references),
        )?;
        let mask = if args.all_pixels {
            mask::Mask::all(size, size)
        } else {
            mask::Mask::new(&scene, size, size)
        };
        let noise = mask.relative_rmse(&reference.half, &reference.image);
        eprintln!(
            "{name}: reference {} spp, its own noise {noise:.4}; {:.1} % of the pixels count",
            reference.spp,
            100.0 * mask.coverage()
        );
        if args.references_only {
            continue;
        }
        let mut runs: Vec<Run> = Vec::new();
        for &method in &chosen {
            let measure = methods::Measure {
                reference: &reference.image,
                mask: &mask,
                max_seconds: max_budget,
                clock: args.clock,
                keep: args.save_run.as_deref().map(|dir| (dir, name, &budgets[..])),
            };
            let mut run = methods::run(method, &scene, base, progressive, &measure)?;
            // The error against the noisy reference, less the reference's own noise in
            // quadrature: the two are independent, so E[measured²] = error² + noise², and this
            // is the error against the true image (0 where the difference is not resolved).
            for s in &mut run.samples {
                s.rel_rmse = (s.rel_rmse * s.rel_rmse - noise * noise).max(0.0).sqrt();
            }
            let last = run.samples.last().map_or((0, 0.0), |s| (s.passes, s.rel_rmse));
            let at =
                [4u64, 16, 64, 256].map(|n| run.after(n).map_or("—".to_owned(), |e| format!("{e:.4}")));
            eprintln!(
                "{name}: {}: {} passes, rel. RMSE {:.4}; after 4/16/64/256 passes {}",
                method.label(),
                last.0,
                last.1,
                at.join(" / ")
            );
            runs.push(run);
        }
        let chart = images.join(format!("convergence-{name}.png"));
        if font.is_ok() {
            let axis = chart::seconds_axis(&study.clock, args.threads);
            chart::draw(&chart, name, &runs, noise, &axis)?;
        }
        study.scenes.push(SceneResult {
            name: name.to_owned(),
            source: (source != name).then(|| source.to_owned()),
            reference_spp: reference.spp,
            reference_noise: noise,
            coverage: mask.coverage(),
            runs,
            chart: font.is_ok().then(|| format!("images/convergence-{name}.png")),
        });
    }
    if args.references_only {
        return Ok(());
    }
    if !args.no_per_pass {
        let memory_counts = [1, 10, 100].map(|n: u64| if args.quick { n.min(16) } else { n });
        let cornell = scenes::build("cornell-box").map_err(|e| e.to_string())?;
        let memory_base = RenderSettings {
            mode: progressive.direct,
            ..base
        };
        study.memory = memory::rows(&cornell, memory_base, &memory_counts)?;
        eprintln!("memory measured");
        // Photons for all light: the leak and the crease error are the photon estimate's.
        let photons_only = Progressive {
            direct: Mode::PhotonMap,
            ..progressive
        };
        let accordion = reference::reference(
            "accordion",
            &scenes::build("accordion").map_err(|e| e.to_string())?,
            base,
            reference::Budget {
                extend: 0.0,
                ..reference_seconds
            },
            (&reference_dir(args, "accordion", size), &args.results_references),
        )?;
        per_pass::tables(base, photons_only, &counts, &accordion.image, &mut study)?;
    }
    let path = args.out_dir.join("convergence.md");
    report::write(&path, &study)?;
    eprintln!("wrote {}", path.display());
    if let Some(dir) = &args.save_run {
        saved::save(dir, &study)?;
        eprintln!("kept the run in {}", dir.display());
    }
    Ok(())
}
