//! Renders a built-in scene or a glTF file with a chosen photon-map partition, estimator and
//! mode, and writes an EXR, an sRGB PNG preview and optionally the figures as JSON.
//! `--compare` renders the report's four variants into one 2×2 grid.
//!
//! `cargo run --release --example render -- --scene cornell-box --maps crease --estimator cube`

use clap::{CommandFactory, FromArgMatches, Parser};
use photon_maps::render::image::{check_image_size, write_atomically};
use photon_maps::render::{EstimatorKind, Image, RenderError, RenderSettings, Renderer};
use std::io::Write as _;
use std::path::{Path, PathBuf};
use std::process::ExitCode;

#[path = "render/applies.rs"]
mod applies;
#[path = "render/auto.rs"]
mod auto;
#[path = "render/cache.rs"]
mod cache;
#[path = "render/choices.rs"]
mod choices;
#[path = "render/compare.rs"]
mod compare;
#[path = "render/emission.rs"]
mod emission;
#[path = "render/files.rs"]
mod files;
#[path = "render/flythrough.rs"]
mod flythrough;
#[path = "render/gather.rs"]
mod gather;
#[path = "render/progressive.rs"]
mod progressive;
#[path = "render/report.rs"]
mod report;
#[path = "render/shard.rs"]
mod shard;
#[path = "render/tile_bar.rs"]
mod tile_bar;
// Counts heap bytes so that progressive runs can report their peak (an atomic add per
// allocation; the render loops do not allocate once warm).
#[path = "../tests/support/tracking_allocator.rs"]
mod tracking_allocator;

use choices::{DirectChoice, EstimatorChoice, LightUnitsChoice, MapsChoice, ModeChoice, parse_image_size};
use files::{check_run_outputs, load_scene, say, scene_dependencies, scene_inputs, scene_name};
use report::{
    Record, contacts_json, contacts_summary, json_number, json_object, json_string, origin_json,
    origin_summary, summary,
};
use tile_bar::TileBar;

/// Photon-mapped rendering without light leaks (multiple photon maps, geometry-based area).
#[derive(Parser, Debug)]
#[command(version, about)]
struct Args {
    /// A built-in scene (cornell-box, lit-unlit-rooms, colored-rooms, accordion,
    /// touching-rooms, glossy-cornell-box; the rooms built from solid boxes: solid-rooms-stand, solid-rooms-pierce,
    /// solid-rooms-gap, solid-rooms-sunk-box, solid-rooms-double-floor, solid-rooms-tee), a scale
    /// scene (split-rooms-N: lit-unlit-rooms with every face split
    /// N×N; cube-field-N: N cubes; doorway-rooms-N: N lit rooms joined by doorways, seen from
    /// the first) or a .gltf/.glb file.
    #[arg(long, default_value = "cornell-box")]
    scene: String,
    /// Photon-map partition [default: contact; the path tracer, which reads no photon map,
    /// renders the scene as given, unsplit].
    #[arg(long, value_enum)]
    maps: Option<MapsChoice>,
    /// Radiance estimator [default: cube].
    #[arg(long, value_enum)]
    estimator: Option<EstimatorChoice>,
    /// Render mode: final-gather (the default) for clean pictures, photon-map for the
    /// report's view of the maps themselves (the default with --compare).
    #[arg(long, value_enum, default_value_t = ModeChoice::FinalGather)]
    mode: ModeChoice,
    /// Photon paths emitted from the lights; in progressive and sppm, per pass (each pass
    /// also takes one camera sample per pixel). A short --time budget gains from fewer: on a
    /// modelled kitchen at 2 s, 25000 to 35000 with --k 50 cut the progressive mode's
    /// per-pixel error by a fifth (docs/kitchen.md).
    #[arg(long, default_value_t = 100_000)]
    photons: u32,
    /// Photons gathered per estimate; in progressive, the k of the pilot's nearest-photon
    /// extents that fix each point's gather volume, and in sppm, of each pixel's first radius.
    /// Which k is best in progressive mode depends on the scene, not the budget: of 12 to 400,
    /// the lowest error at 2, 8 and 30 s came with 100 on the Cornell box, 400 on the lit/unlit
    /// and coloured rooms, 25 or 12 on the accordion, and on a modelled kitchen (12 to 100
    /// tried) 50 at 2 s (with --photons 35000), 25 at 6 s and 12 at 30 s (docs/results.md).
    #[arg(long, default_value_t = 100)]
    k: usize,
    /// Image size, WIDTHxHEIGHT.
    #[arg(long, default_value = "500x500")]
    size: String,
    /// Samples per pixel (`RenderSettings::samples_per_pixel`) [default: 16 in final-gather
    /// mode, else 1].
    #[arg(long = "samples-per-pixel", visible_alias = "spp")]
    spp: Option<u32>,
    /// Worker threads for the contact split and the render; 0 = rayon's global pool, one thread
    /// per core unless RAYON_NUM_THREADS says otherwise (`RenderSettings::threads`).
    #[arg(long, default_value_t = 0)]
    threads: usize,
    /// Seed of all random streams.
    #[arg(long, default_value_t = 0)]
    seed: u64,
    /// Exposure of the PNG preview, in stops (negative darkens) [default: 0, or with
    /// --compare picked so that about 1 % of the pixels clip].
    #[arg(long, allow_negative_numbers = true)]
    exposure: Option<f32>,
    /// Output path; its .exr and .png siblings are written (default target/out/<scene>.exr).
    #[arg(long)]
    out: Option<PathBuf>,
    /// Write the figures of the render(s) as JSON here.
    #[arg(long)]
    stats_json: Option<PathBuf>,
    /// Render the report's four variants (basic, multiple maps, geometry area, both) into a
    /// labelled 2×2 grid; sets the maps and estimator itself, and needs a photon-map mode
    /// (photon-map or shadow-rays).
    #[arg(long)]
    compare: bool,
    /// Progressive and SPPM modes: passes to render (default 16 without --time).
    #[arg(long)]
    passes: Option<u64>,
    /// Progressive mode: the first pass of this shard.
    #[arg(long, default_value_t = 0)]
    first_pass: u64,
    /// Progressive mode: the shard's passes from this scheduler's array index i (its variable
    /// SLURM_ARRAY_TASK_ID, JOB_COMPLETION_INDEX or AWS_BATCH_JOB_ARRAY_INDEX): passes i×N …
    /// i×N+N−1 with N = --passes-per-shard; `{index}` in --out and --stats-json becomes i.
    #[arg(long, value_enum)]
    shard_index_from: Option<shard::IndexSource>,
    /// Progressive mode with --shard-index-from: passes per shard (N).
    #[arg(long)]
    passes_per_shard: Option<u64>,
    /// Progressive and SPPM modes: stop after the pass that spends this many seconds.
    #[arg(long, allow_negative_numbers = true)]
    time: Option<f64>,
    /// How a glTF file's emissive strength, candela and lux become watts: `mixed` (emission
    /// 1:1, lamps ÷ 683), or `photometric` / `viewer`, which keep emitters and lamps at the
    /// file's ratio. Built-in scenes are in watts already.
    #[arg(long, value_enum, default_value_t = LightUnitsChoice::Mixed)]
    light_units: LightUnitsChoice,
    /// Progressive mode: direct light by photons (as `photon-map`) or by shadow rays with
    /// photons for the rest (as SPPM has it).
    #[arg(long, value_enum, default_value_t = DirectChoice::Photons)]
    direct: DirectChoice,
    /// Merge progressive shards (EXR files) into --out.
    #[arg(long, num_args = 1..)]
    merge: Vec<PathBuf>,
    /// Final-gather mode, and progressive mode, where it makes each pass a final gather: gather
    /// rays per camera sample [default: 4].
    #[arg(long)]
    gather_rays: Option<u32>,
    /// Final-gather mode (and progressive with --gather-rays): irradiance is precomputed at
    /// one photon in n (n ≥ 2), from the others [default: 4].
    #[arg(long)]
    cache_every: Option<u32>,
    /// Final-gather mode (and progressive with --gather-rays): gather hits closer than this
    /// (metres) take one more bounce instead of reading the cache (Jensen's corner rule; 0:
    /// never) [default: 5 % of the scene's bounding-box diagonal].
    #[arg(long)]
    corner_distance: Option<f32>,
    /// Contact maps: faces closer than this fraction of the scene's bounding-box diagonal
    /// count as touching, and no map joins across them (0 < f ≤ 0.1) [default: 0.002]. A
    /// modelled interior of small objects splits into far fewer maps with a smaller one: the
    /// obvhs kitchen (7.9 m) makes 134,420 maps at 0.002, 30,197 at 0.0001.
    #[arg(long)]
    contact_gap: Option<f32>,
    /// Single-pass modes that read photons: save the photon maps (and the final gather's
    /// irradiance cache) to this file, for later runs' --load-cache.
    #[arg(long, conflicts_with = "load_cache")]
    save_cache: Option<PathBuf>,
    /// Single-pass modes that read photons: render from the photon maps (and irradiance cache)
    /// in this file instead of tracing and building them; refused when it was made for
    /// another scene or other settings (the camera, size and samples may differ).
    #[arg(long)]
    load_cache: Option<PathBuf>,
    /// Single-pass modes that read photons: a fly-through of N frames from one photon cache
    /// (built once, or --load-cache): frame i turns the camera by i × --orbit / N degrees about
    /// the vertical axis through the scene's centre; writes <out stem>-<i>.exr and .png.
    #[arg(long)]
    frames: Option<u32>,
    /// With --frames: degrees the camera turns over the N frames (-360 to 360; 360 loops).
    #[arg(long, allow_negative_numbers = true)]
    orbit: Option<f64>,
    #[command(flatten)]
    auto: auto::AutoArgs,
    #[command(flatten)]
    emission: emission::EmissionArgs,
}

impl Args {
    /// `--maps`, or its default.
    fn maps(&self) -> MapsChoice {
        self.maps.unwrap_or(MapsChoice::Contact)
    }

    /// `--estimator`, or its default.
    fn estimator(&self) -> EstimatorKind {
        self.estimator.unwrap_or(EstimatorChoice::Cube).into()
    }

    /// `--samples-per-pixel`, or its default: 16 camera samples of 4 gather rays (`gather.rs`)
    /// in final-gather mode, 1 in the others.
    fn spp(&self) -> u32 {
        self.spp.unwrap_or(if self.mode == ModeChoice::FinalGather {
            gather::SAMPLES_PER_PIXEL
        } else {
            1
        })
    }

    /// `--exposure`, or 0 stops.
    fn exposure(&self) -> f32 {
        self.exposure.unwrap_or(0.0)
    }
}

/// One render of a run: its label and choices.
struct Variant {
    label: &'static str,
    maps: MapsChoice,
    estimator: EstimatorKind,
}

fn main() -> ExitCode {
    let matches = Args::command().get_matches();
    let mut args = match Args::from_arg_matches(&matches) {
        Ok(args) => args,
        Err(e) => e.exit(),
    };
    // The report's 2×2 grid is of photon maps seen directly: its mode unless one is named.
    if args.compare && matches.value_source("mode") != Some(clap::parser::ValueSource::CommandLine) {
        args.mode = ModeChoice::PhotonMap;
    }
    let result = applies::refuse_inapplicable(&args, &matches)
        .and_then(|()| shard::resolve(&mut args, &matches))
        .and_then(|()| run(&args));
    match result {
        Ok(()) => ExitCode::SUCCESS,
        Err(message) => {
            eprintln!("render: {message}");
            ExitCode::FAILURE
        }
    }
}

fn run(args: &Args) -> Result<(), String> {
    if !args.merge.is_empty() {
        return progressive::merge(args, &args.merge);
    }
    let (width, height) = parse_image_size(&args.size)?;
    let estimator = args.estimator();
    let mode = args.mode.render_mode();
    if args.compare {
        refuse_compare_conflicts(args)?;
    }
    auto::refuse_conflicts(args)?;
    let settings = RenderSettings {
        width,
        height,
        samples_per_pixel: args.spp(),
        photons: args.photons,
        k: args.k,
        mode,
        seed: args.seed,
        threads: args.threads,
        final_gather: gather::options(args)?,
        emission: args.emission.emission()?,
        ..RenderSettings::default()
    };
    settings.validate().map_err(|e| e.to_string())?;
    // The contact split runs on the current rayon pool (the renderers make their own): the
    // global pool takes the thread count asked for.
    if args.threads > 0 {
        rayon::ThreadPoolBuilder::new()
            .num_threads(args.threads)
            .build_global()
            .map_err(|e| format!("--threads {}: {e}", args.threads))?;
    }
    if args.compare {
        // The 2×2 grid is checked with the settings, not after four renders.
        check_image_size(2 * width, 2 * height).map_err(|e| format!("--compare grid: {e}"))?;
    }
    if let Some(exposure) = args.exposure.filter(|e| !e.is_finite()) {
        return Err(RenderError::BadExposure(exposure).to_string());
    }
    if args.mode.is_progressive() {
        return progressive::run(args, settings, estimator);
    }
    if args.frames.is_some() || args.orbit.is_some() {
        return flythrough::run(args, settings, estimator);
    }

    let scene_name = scene_name(&args.scene);
    let base = args.out.clone().unwrap_or_else(|| default_out(&scene_name));
    // Fail on an unwritable or clashing output before spending time on the scene or render.
    let dependencies = scene_dependencies(&args.scene);
    let mut inputs = scene_inputs(&args.scene, &dependencies);
    inputs.extend(args.load_cache.as_deref().map(|path| files::NamedFile {
        option: "--load-cache",
        path,
    }));
    let (exr_path, png_path) = check_run_outputs(&base, args.stats_json.as_deref(), &inputs)?;
    if let Some(path) = &args.save_cache {
        files::check_cache_output(path, &base, args.stats_json.as_deref(), &inputs)?;
    }
    let mut timer = photon_maps::geom::StepTimer::start();
    let (scene, _) = load_scene(&args.scene, args.light_units.into())?;
    let load_seconds = timer.lap();
    let origin_offset = scene.origin_offset().to_array();

    let variants: Vec<Variant> = if args.compare {
        compare::VARIANTS
            .iter()
            .map(|&(label, maps, estimator)| Variant {
                label,
                maps,
                estimator: estimator.into(),
            })
            .collect()
    } else {
        // The path tracer reads no photon map: no partition may change the scene it sees
        // (one map leaves the scene as given; --maps is refused in that mode).
        let maps = match args.mode {
            ModeChoice::PathTrace => MapsChoice::Single,
            _ => args.maps(),
        };
        vec![Variant {
            label: "render",
            maps,
            estimator,
        }]
    };

    let mut images = Vec::new();
    let mut records = Vec::new();
    // The file is parsed once. A partition may re-mesh the scene (contact splits faces); only
    // `--compare` renders several variants, and its partitions (single, crease) leave the
    // scene as it is, so the partitioned scene serves the next variant.
    let mut scene = Some(scene);
    for variant in &variants {
        let partition = variant.maps.partitioner(args.contact_gap)?;
        timer.lap();
        let partitioned = partition
            .partition(scene.take().ok_or("no scene")?)
            .map_err(choices::partition_message)?;
        let setup = report::Setup {
            load: load_seconds,
            partition: Some(timer.lap()),
        };
        let bar = TileBar::new(variant.label);
        let renderer = Renderer::new(variant.estimator, settings);
        let (out, cache_use) = match (&args.save_cache, &args.load_cache) {
            (None, None) => (auto::render(args, &renderer, &partitioned, &bar)?, None),
            _ => {
                let (out, used) = cache::render_with_cache_file(args, &renderer, &partitioned, &bar)?;
                (out, Some(used))
            }
        };
        let contacts = (
            contacts_summary(partitioned.record()),
            contacts_json(partitioned.record()),
        );
        scene = Some(partitioned.into_parts().0);
        bar.0.finish_and_clear();
        let mean = out.image.mean().to_array();
        let record = Record {
            args,
            scene: &scene_name,
            variant,
            settings: &settings,
            stats: out.stats,
            mean,
            contacts,
            origin_offset,
            cache: cache_use,
            setup,
        };
        say(&summary(&record));
        records.push(record);
        images.push(out.image);
    }

    let (image, preview) = if args.compare {
        let grid =
            Image::grid_2x2([&images[0], &images[1], &images[2], &images[3]]).map_err(|e| e.to_string())?;
        let exposure = args.exposure.unwrap_or_else(|| compare::auto_exposure(&grid));
        if args.exposure.is_none() {
            say(&format!(
                "preview exposure {exposure:+.2} stops (picked from the image)"
            ));
        }
        // The labels go into the preview only: the EXR keeps the radiance of every pixel.
        let mut labelled = grid.clone();
        compare::label_panels(&mut labelled, width, height, exposure);
        (grid, Some((labelled, exposure)))
    } else {
        (images.pop().ok_or("nothing rendered")?, None)
    };
    image.write_exr(&exr_path).map_err(|e| e.to_string())?;
    let (preview, exposure) = preview.unwrap_or((image, args.exposure()));
    preview
        .write_png(&png_path, exposure)
        .map_err(|e| e.to_string())?;
    say(&format!(
        "wrote {} and {}",
        exr_path.display(),
        png_path.display()
    ));
    if let Some(path) = &args.stats_json {
        let objects: Vec<String> = records.iter().map(json_object).collect();
        let text = if args.compare {
            format!("[\n{}\n]\n", objects.join(",\n"))
        } else {
            objects.join("") + "\n"
        };
        write_atomically(path, |w| w.write_all(text.as_bytes()))
            .map_err(|e| format!("{}: {e}", path.display()))?;
        say(&format!("wrote {}", path.display()));
    }
    Ok(())
}

/// Where a run writes when `--out` is not given: under `target/`, beside the build, so that a
/// run in the repository writes into none of its files.
pub fn default_out(scene_name: &str) -> PathBuf {
    Path::new("target").join("out").join(format!("{scene_name}.exr"))
}

/// Refuses what `--compare` cannot honour: it chooses the maps and estimator of each panel
/// itself, and its panels differ only in how they read photon maps.
fn refuse_compare_conflicts(args: &Args) -> Result<(), String> {
    if args.save_cache.is_some() || args.load_cache.is_some() {
        return Err("--compare renders four variants with four sets of maps; --save-cache and --load-cache hold one: drop them".into());
    }
    if args.maps.is_some() || args.estimator.is_some() {
        return Err(
            "--compare renders its four variants with their own maps and estimator; drop --maps and --estimator"
                .into(),
        );
    }
    match args.mode {
        ModeChoice::PhotonMap | ModeChoice::ShadowRays => Ok(()),
        mode => Err(format!(
            "--compare needs a photon-map mode (photon-map or shadow-rays): in {mode} mode its four panels would not differ as the report's do"
        )),
    }
}
