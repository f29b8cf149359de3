//! Renders a built-in scene or a glTF file with a chosen photon-map partition, estimator and
//! mode, and writes an EXR, an sRGB PNG preview and optionally the figures as JSON.
//! `--compare` renders the paper's four variants into one 2×2 grid.
//!
//! `cargo run --release --example render -- --scene cornell-box --maps crease --estimator cube`

use clap::Parser;
use indicatif::{ProgressBar, ProgressStyle};
use photon_maps::render::image::{check_image_size, check_output_path, write_atomically};
use photon_maps::render::{
    EstimatorKind, Image, Mode, Progress, RenderError, RenderSettings, RenderStats, Renderer,
    parse_image_size,
};
use photon_maps::trace::{Contact, CreaseAngle, Partitioner, Scene, SingleMap, scenes};
use std::fmt::Write as _;
use std::fs;
use std::io::Write as _;
use std::path::{Path, PathBuf};
use std::process::ExitCode;

#[path = "render/progressive.rs"]
mod progressive;

/// Photon-mapped rendering without light leaks (multiple photon maps, geometry-based area).
#[derive(Parser, Debug)]
#[command(version, about)]
struct Args {
    /// A built-in scene (cornell-box, lit-unlit-rooms, colored-rooms, accordion,
    /// touching-rooms) or a .gltf/.glb file.
    #[arg(long, default_value = "cornell-box")]
    scene: String,
    /// Photon-map partition: single | crease | contact.
    #[arg(long, default_value = "crease")]
    maps: String,
    /// Radiance estimator: disc | cube | ball.
    #[arg(long, default_value = "cube")]
    estimator: String,
    /// Render mode: visualize | shadow-rays | path-trace | progressive | sppm.
    #[arg(long, default_value = "visualize")]
    mode: String,
    /// Photon paths emitted from the lights.
    #[arg(long, default_value_t = 100_000)]
    photons: u32,
    /// Photons gathered per estimate.
    #[arg(long, default_value_t = 100)]
    k: usize,
    /// Image size, WIDTHxHEIGHT.
    #[arg(long, default_value = "500x500")]
    size: String,
    /// Samples per pixel.
    #[arg(long, default_value_t = 1)]
    spp: u32,
    /// Worker threads (0 = all cores).
    #[arg(long, default_value_t = 0)]
    threads: usize,
    /// Seed of all random streams.
    #[arg(long, default_value_t = 0)]
    seed: u64,
    /// Exposure of the PNG preview, in stops (negative darkens).
    #[arg(long, default_value_t = 0.0, allow_negative_numbers = true)]
    exposure: f32,
    /// Output path; its .exr and .png siblings are written (default out/<scene>.exr).
    #[arg(long)]
    out: Option<PathBuf>,
    /// Write the figures of the render(s) as JSON here.
    #[arg(long)]
    stats_json: Option<PathBuf>,
    /// Render the paper's four variants (basic, multiple maps, geometry area, both) into a
    /// 2×2 grid.
    #[arg(long)]
    compare: bool,
    /// Progressive and SPPM modes: passes to render (default 16 without --time).
    #[arg(long)]
    passes: Option<u64>,
    /// Progressive mode: the first pass of this shard.
    #[arg(long, default_value_t = 0)]
    first_pass: u64,
    /// Progressive and SPPM modes: stop after the pass that spends this many seconds.
    #[arg(long)]
    time: Option<f64>,
    /// Merge progressive shards (EXR files) into --out.
    #[arg(long, num_args = 1..)]
    merge: Vec<PathBuf>,
}

/// Makes a partitioner.
type MakePartitioner = fn() -> Box<dyn Partitioner>;

/// The partitions by command-line name; adding one is one line here.
const PARTITIONS: &[(&str, MakePartitioner)] = &[
    ("single", || Box::new(SingleMap)),
    ("crease", || Box::new(CreaseAngle::default())),
    ("contact", || Box::new(Contact::default())),
];

fn partitioner(name: &str) -> Result<Box<dyn Partitioner>, String> {
    match PARTITIONS.iter().find(|(n, _)| *n == name) {
        Some((_, make)) => Ok(make()),
        None => {
            let names: Vec<&str> = PARTITIONS.iter().map(|(n, _)| *n).collect();
            Err(format!("unknown maps '{name}' (expected {})", names.join("|")))
        }
    }
}

/// One render of a run: its label and choices.
struct Variant {
    label: &'static str,
    maps: String,
    estimator: EstimatorKind,
}

/// The figures of one finished render, for the summary and the JSON.
struct Record<'a> {
    args: &'a Args,
    scene: &'a str,
    variant: &'a Variant,
    settings: &'a RenderSettings,
    stats: RenderStats,
    mean: [f32; 3],
}

fn main() -> ExitCode {
    let args = Args::parse();
    match run(&args) {
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
    let (width, height) = parse_image_size(&args.size).map_err(|e| e.to_string())?;
    let progressive_mode = matches!(args.mode.as_str(), "progressive" | "sppm");
    let mode: Mode = if progressive_mode { "visualize" } else { &args.mode }
        .parse()
        .map_err(|e: RenderError| e.to_string())?;
    let estimator: EstimatorKind = args.estimator.parse().map_err(|e: RenderError| e.to_string())?;
    partitioner(&args.maps)?;
    let settings = RenderSettings {
        width,
        height,
        samples_per_pixel: args.spp,
        photons: args.photons,
        k: args.k,
        mode,
        seed: args.seed,
        threads: args.threads,
        ..RenderSettings::default()
    };
    settings.validate().map_err(|e| e.to_string())?;
    if args.compare {
        // The 2×2 grid is checked with the settings, not after four renders.
        check_image_size(2 * width, 2 * height).map_err(|e| format!("--compare grid: {e}"))?;
    }
    if !args.exposure.is_finite() {
        return Err(RenderError::BadExposure(args.exposure).to_string());
    }
    if progressive_mode {
        return progressive::run(args, settings, estimator);
    }

    let (scene, scene_name) = load_scene(&args.scene)?;
    let base = args
        .out
        .clone()
        .unwrap_or_else(|| Path::new("out").join(format!("{scene_name}.exr")));
    if base.is_dir() {
        return Err(format!(
            "--out {} is a folder; name a file (its .exr and .png siblings are written)",
            base.display()
        ));
    }
    let (exr_path, png_path) = (base.with_extension("exr"), base.with_extension("png"));
    // Fail on an unwritable output before spending time on the render.
    let outputs: Vec<&Path> = [Some(&exr_path), Some(&png_path), args.stats_json.as_ref()]
        .into_iter()
        .flatten()
        .map(PathBuf::as_path)
        .collect();
    for path in &outputs {
        check_writable(path)?;
    }
    refuse_shared_outputs(&outputs)?;

    let variants: Vec<Variant> = if args.compare {
        [
            ("basic", "single", EstimatorKind::Disc),
            ("multiple maps", "crease", EstimatorKind::Disc),
        ]
        .into_iter()
        .chain([
            ("geometry area", "single", EstimatorKind::GeometryCube),
            ("both", "crease", EstimatorKind::GeometryCube),
        ])
        .map(|(label, maps, estimator)| Variant {
            label,
            maps: maps.to_owned(),
            estimator,
        })
        .collect()
    } else {
        vec![Variant {
            label: "render",
            maps: args.maps.clone(),
            estimator,
        }]
    };

    let mut images = Vec::new();
    let mut records = Vec::new();
    // The file is parsed once. A partition may re-mesh the scene (contact splits faces); only
    // `--compare` renders several variants, and its partitions (single, crease) leave the
    // scene as it is, so the prepared scene serves the next variant.
    let mut scene = Some(scene);
    for variant in &variants {
        let partition = partitioner(&variant.maps)?;
        let prepared = partition
            .prepare_scene(scene.take().ok_or("no scene")?)
            .map_err(|e| e.to_string())?;
        let scene = scene.insert(prepared);
        let bar = TileBar::new(variant.label);
        let out = Renderer::new(variant.estimator, settings)
            .render(scene, &*partition, &bar)
            .map_err(|e| e.to_string())?;
        bar.0.finish_and_clear();
        let mean = out.image.mean().to_array();
        let record = Record {
            args,
            scene: &scene_name,
            variant,
            settings: &settings,
            stats: out.stats,
            mean,
        };
        say(&summary(&record));
        records.push(record);
        images.push(out.image);
    }

    let image = if args.compare {
        Image::grid_2x2([&images[0], &images[1], &images[2], &images[3]]).map_err(|e| e.to_string())?
    } else {
        images.pop().ok_or("nothing rendered")?
    };
    image.write_exr(&exr_path).map_err(|e| e.to_string())?;
    image
        .write_png(&png_path, args.exposure)
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

/// A built-in scene by name, or a glTF file by path; also the name used for output files.
fn load_scene(arg: &str) -> Result<(Scene, String), String> {
    let lower = arg.to_ascii_lowercase();
    let is_file = lower.ends_with(".gltf") || lower.ends_with(".glb") || arg.contains(['/', '\\']);
    if !is_file {
        return scenes::build(arg)
            .map(|s| (s, arg.to_owned()))
            .map_err(|e| e.to_string());
    }
    let path = Path::new(arg);
    if !path.is_file() {
        return Err(format!("scene file not found: {arg}"));
    }
    let name = path
        .file_stem()
        .and_then(|s| s.to_str())
        .unwrap_or("scene")
        .to_owned();
    load_gltf(path).map(|s| (s, name))
}

/// Prints a line to stdout; a closed pipe (`render | head -1`) is not an error worth a panic.
fn say(line: &str) {
    let _ = writeln!(std::io::stdout().lock(), "{line}");
}

/// A glTF scene through pm-trace's safe loader.
fn load_gltf(path: &Path) -> Result<Scene, String> {
    photon_maps::trace::gltf::load_scene(path).map_err(|e| e.to_string())
}

/// Creates the parent folder, refuses a target that is not a regular file (a folder, a
/// device, a FIFO) and checks a file can be made beside it, so a bad path fails before the
/// render; the target itself is not opened or touched.
fn check_writable(path: &Path) -> Result<(), String> {
    let fail = |e: std::io::Error| format!("cannot write {}: {e}", path.display());
    if let Some(parent) = path.parent().filter(|p| !p.as_os_str().is_empty()) {
        fs::create_dir_all(parent).map_err(fail)?;
    }
    check_output_path(path).map_err(|e| e.to_string())?;
    // An empty atomic write to a file that is then removed: the target is never named.
    let probe = path.with_file_name(format!(
        ".{}.probe-{}",
        path.file_name().and_then(|n| n.to_str()).unwrap_or("out"),
        std::process::id()
    ));
    write_atomically(&probe, |_| Ok(())).map_err(fail)?;
    fs::remove_file(&probe).ok();
    Ok(())
}

/// Refuses two outputs that are one file (`--stats-json` naming the image, or a link to it).
fn refuse_shared_outputs(outputs: &[&Path]) -> Result<(), String> {
    let identity = |path: &Path| -> PathBuf {
        // Existing files (and links to them) by their canonical path; new ones by their
        // canonical folder and name.
        if let Ok(p) = fs::canonicalize(path) {
            return p;
        }
        let folder = path.parent().filter(|p| !p.as_os_str().is_empty());
        let folder = folder.map_or_else(|| fs::canonicalize("."), fs::canonicalize);
        match (folder, path.file_name()) {
            (Ok(folder), Some(name)) => folder.join(name),
            _ => path.to_path_buf(),
        }
    };
    for (i, a) in outputs.iter().enumerate() {
        for b in &outputs[i + 1..] {
            if identity(a) == identity(b) {
                return Err(format!(
                    "outputs {} and {} are the same file; give each output its own path",
                    a.display(),
                    b.display()
                ));
            }
        }
    }
    Ok(())
}

fn summary(r: &Record<'_>) -> String {
    let s = &r.stats;
    // Path tracing reads no photon maps: say so rather than "crease (0), estimator cube".
    let lighting = if s.photons_emitted == 0 {
        "no photon maps".to_string()
    } else {
        format!(
            "maps {} ({}), estimator {}",
            r.variant.maps, s.map_count, r.variant.estimator
        )
    };
    // Channels too dim for their map's power codes (over 10¹² below its brightest): say so.
    let below = match s.photon_channels_below_range {
        0 => String::new(),
        n => format!(", {n} power channels below the map's range stored as zero"),
    };
    format!(
        "{} [{}]: {lighting}, mode {}, {}x{}, {} photons ({} stored{below}): trace {:.3} s, build {:.3} s, render {:.3} s, total {:.3} s, mean rgb ({:.4}, {:.4}, {:.4})",
        r.scene,
        r.variant.label,
        r.settings.mode,
        r.settings.width,
        r.settings.height,
        s.photons_emitted,
        s.photons_stored,
        s.trace.as_secs_f64(),
        s.build.as_secs_f64(),
        s.render.as_secs_f64(),
        s.total().as_secs_f64(),
        r.mean[0],
        r.mean[1],
        r.mean[2],
    )
}

fn json_object(r: &Record<'_>) -> String {
    let s = &r.stats;
    let mut o = String::from("{");
    let _ = write!(
        o,
        "\"scene\": {}, \"variant\": {}, \"maps\": {}, \"estimator\": {}, \"mode\": {}, ",
        json_string(r.scene),
        json_string(r.variant.label),
        json_string(&r.variant.maps),
        json_string(r.variant.estimator.name()),
        json_string(r.settings.mode.name()),
    );
    let _ = write!(
        o,
        "\"width\": {}, \"height\": {}, \"spp\": {}, \"k\": {}, \"photons_emitted\": {}, \"photons_stored\": {}, \"photon_channels_below_range\": {}, \"map_count\": {}, \"threads\": {}, \"seed\": {}, ",
        r.settings.width,
        r.settings.height,
        r.settings.samples_per_pixel,
        r.settings.k,
        s.photons_emitted,
        s.photons_stored,
        s.photon_channels_below_range,
        s.map_count,
        s.threads,
        r.args.seed,
    );
    let _ = write!(
        o,
        "\"seconds\": {{\"trace\": {}, \"build\": {}, \"render\": {}, \"total\": {}}}, \"mean_rgb\": [{}, {}, {}]}}",
        json_number(s.trace.as_secs_f64()),
        json_number(s.build.as_secs_f64()),
        json_number(s.render.as_secs_f64()),
        json_number(s.total().as_secs_f64()),
        json_number(r.mean[0] as f64),
        json_number(r.mean[1] as f64),
        json_number(r.mean[2] as f64),
    );
    o
}

fn json_string(s: &str) -> String {
    let mut out = String::from("\"");
    for c in s.chars() {
        match c {
            '"' => out.push_str("\\\""),
            '\\' => out.push_str("\\\\"),
            c if (c as u32) < 0x20 => {
                let _ = write!(out, "\\u{:04x}", c as u32);
            }
            c => out.push(c),
        }
    }
    out.push('"');
    out
}

/// JSON has no NaN or infinity: write them as null.
fn json_number(x: f64) -> String {
    if x.is_finite() {
        format!("{x}")
    } else {
        "null".to_owned()
    }
}

/// An indicatif bar fed by the renderer's progress callbacks (hidden when stderr is no TTY).
struct TileBar(ProgressBar);

impl TileBar {
    fn new(label: &str) -> Self {
        let bar = ProgressBar::new(0);
        if let Ok(style) = ProgressStyle::with_template("{msg:>24} [{bar:40}] {pos}/{len} tiles {elapsed}") {
            bar.set_style(style.progress_chars("=> "));
        }
        bar.set_message(label.to_owned());
        TileBar(bar)
    }
}

impl Progress for TileBar {
    fn phase(&self, name: &'static str) {
        self.0.set_message(name);
    }
    fn tiles_done(&self, _done: usize, total: usize) {
        if self.0.length() != Some(total as u64) {
            self.0.set_length(total as u64);
        }
        self.0.inc(1);
    }
}
