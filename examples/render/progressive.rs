//! `--mode progressive|sppm` and `--merge`: progressive renders in shards of passes whose
//! merge has the bits of one run of all their passes, and the SPPM baseline. Kept apart from
//! the single-pass command line.

use super::files::{NamedFile, check_run_outputs, scene_dependencies, scene_input, scene_inputs};
use super::report::Setup;
use super::{
    Args, ModeChoice, contacts_json, contacts_summary, json_number, json_string, load_scene, origin_json,
    origin_summary, say,
};
use indicatif::{ProgressBar, ProgressStyle};
use photon_maps::render::image::write_atomically;
use photon_maps::render::progressive::{
    ProgressiveRenderer, ProgressiveSettings, ProgressiveStats, Shard, ShardError, SppmRenderer, SppmSettings,
};
use photon_maps::render::{EstimatorKind, Progress, RenderSettings};
use std::fmt::Write as _;
use std::io::Write as _;
use std::path::{Path, PathBuf};
use std::time::Duration;

/// Runs `--mode progressive` or `--mode sppm` with the common settings already parsed.
pub fn run(args: &Args, mut settings: RenderSettings, estimator: EstimatorKind) -> Result<(), String> {
    if args.compare {
        return Err(
            "--compare renders single passes; it does not combine with --mode progressive|sppm".into(),
        );
    }
    let budget = match args.time {
        // Refuses negative, NaN, infinite and too large (about 1.8e19 s) budgets.
        Some(t) => Some(
            Duration::try_from_secs_f64(t)
                .map_err(|_| format!("--time must be a number of seconds from 0 to 1.8e19, got {t}"))?,
        ),
        None => None,
    };
    let passes = match (args.passes, budget) {
        (None, None) => Some(16),
        (p, _) => p,
    };
    let sppm = args.mode == ModeChoice::Sppm;
    if sppm && args.first_pass != 0 {
        return Err("--first-pass: SPPM runs are not shardable".into());
    }
    // Each progressive pass renders like `photon-map` (photons for all light) or
    // `shadow-rays`, as --direct says; SPPM always has shadow rays for direct light.
    settings.mode = args.direct.mode();
    if super::gather::gathers(args) {
        // A final gather per pass (direct light by shadow rays whatever --direct says).
        settings.mode = photon_maps::render::Mode::FinalGather;
    }
    let progressive_settings = ProgressiveSettings {
        first_pass: args.first_pass,
        passes,
        time_budget: budget,
        ..ProgressiveSettings::new(settings, 1)
    };
    if sppm {
        SppmSettings {
            passes,
            time_budget: budget,
            ..SppmSettings::new(settings, 1)
        }
        .validate()
    } else {
        progressive_settings.validate()
    }
    .map_err(|e| e.to_string())?;
    let (scene_name, scene_id) = scene_identity(&args.scene)?;
    let scene_id = scene_id + &light_units_applied(args);
    let base = args
        .out
        .clone()
        .unwrap_or_else(|| super::default_out(&scene_name));
    let dependencies = scene_dependencies(&args.scene);
    let inputs = scene_inputs(&args.scene, &dependencies);
    let (exr_path, png_path) = check_run_outputs(&base, args.stats_json.as_deref(), &inputs)?;
    let bar = PassBar::new(passes);
    let heap_before = crate::tracking_allocator::reset_peak();
    let mut timer = photon_maps::geom::StepTimer::start();
    let scene = load_scene(&args.scene, args.light_units.into())?.0;
    let mut setup = Setup {
        load: timer.lap(),
        partition: None,
    };
    let origin_offset = scene.origin_offset().to_array();
    let (image, stats, range, identity, contacts) = if sppm {
        let s = SppmSettings {
            passes,
            time_budget: budget,
            ..SppmSettings::new(settings, 1)
        };
        let out = SppmRenderer::new(s)
            .render(&scene, &bar)
            .map_err(|e| e.to_string())?;
        bar.0.finish_and_clear();
        out.image.write_exr(&exr_path).map_err(|e| e.to_string())?;
        let identity = format!("sppm k={} photons={} seed={}", args.k, args.photons, args.seed);
        let contacts = (String::new(), "null".to_owned());
        (
            out.image,
            out.stats.clone(),
            0..out.stats.passes,
            identity,
            contacts,
        )
    } else {
        let partition = args.maps().partitioner(args.contact_gap)?;
        timer.lap();
        let partitioned = partition
            .partition(scene)
            .map_err(crate::choices::partition_message)?;
        setup.partition = Some(timer.lap());
        let s = progressive_settings;
        let out = ProgressiveRenderer::new(estimator, s)
            .render(&partitioned, &bar)
            .map_err(|e| e.to_string())?;
        bar.0.finish_and_clear();
        // The library's identity names the settings, the estimator and the partition; the
        // scene's (file and light units) is the command line's.
        let identity = out.identity.clone();
        let a = &out.accumulation;
        let shard = out.shard(&scene_id).map_err(|e| e.to_string())?;
        shard.write_exr(&exr_path).map_err(|e| e.to_string())?;
        let contacts = (
            contacts_summary(partitioned.record()),
            contacts_json(partitioned.record()),
        );
        (a.mean(), out.stats, a.pass_range(), identity, contacts)
    };
    let heap_peak = crate::tracking_allocator::peak().saturating_sub(heap_before);
    image
        .write_png(&png_path, args.exposure())
        .map_err(|e| e.to_string())?;
    let m = image.mean();
    // Power that hit a surface within a millimetre of its light: a light facing into a wall.
    let near = if stats.near_light_fraction >= 0.01 {
        format!(
            " ({:.1} % of the emitted power hit a surface within 1 mm of its light: facing into a wall? an area light faces edge_u × edge_v)",
            100.0 * stats.near_light_fraction
        )
    } else {
        String::new()
    };
    let emission = super::emission::summary(
        stats.emission.as_ref(),
        stats.photons_emitted,
        stats.photons_traced,
    );
    say(&format!(
        "{scene_name} [{}]: passes {}..{} ({}), {} photons in all{near}{emission}{}{}: pilot {:.3} s, trace {:.3} s, precompute {:.3} s, render {:.3} s, total {:.3} s, peak heap {:.1} MiB (one pass's photon trees {:.1} MiB), mean rgb ({:.4}, {:.4}, {:.4})",
        args.mode,
        range.start,
        range.end,
        count(stats.passes, "pass", "passes"),
        stats.photons_emitted,
        contacts.0,
        origin_summary(origin_offset),
        stats.pilot.as_secs_f64(),
        stats.trace.as_secs_f64(),
        stats.precompute.as_secs_f64(),
        stats.render.as_secs_f64(),
        stats.total().as_secs_f64(),
        heap_peak as f64 / (1 << 20) as f64,
        stats.pass_tree_bytes as f64 / (1 << 20) as f64,
        m.x,
        m.y,
        m.z
    ));
    say(&format!(
        "wrote {} and {}",
        exr_path.display(),
        png_path.display()
    ));
    if let Some(path) = &args.stats_json {
        let json = stats_json(
            &args.mode.to_string(),
            &scene_id,
            &identity,
            range,
            Some((&stats, heap_peak, &contacts.1, origin_offset, setup)),
            m.to_array(),
        );
        write_atomically(path, |w| w.write_all(json.as_bytes()))
            .map_err(|e| format!("{}: {e}", path.display()))?;
        say(&format!("wrote {}", path.display()));
    }
    Ok(())
}

/// `--merge SHARD.exr … --out OUT.exr`: the image one run of all the shards' passes gives,
/// bit for bit; the shards are read one at a time into one running sum.
pub fn merge(args: &Args, shards: &[PathBuf]) -> Result<(), String> {
    let out = args.out.clone().ok_or("--merge needs --out OUT.exr")?;
    let inputs: Vec<NamedFile<'_>> = shards
        .iter()
        .map(|path| NamedFile {
            option: "shard",
            path,
        })
        .collect();
    let (exr_path, png_path) = check_run_outputs(&out, args.stats_json.as_deref(), &inputs)?;
    let merged = Shard::merge_files(shards).map_err(|e| match e {
        ShardError::SettingsMismatch { a, b } => settings_differ(&a, &b),
        e => e.to_string(),
    })?;
    merged.write_exr(&exr_path).map_err(|e| e.to_string())?;
    let mean = merged.mean();
    mean.write_png(&png_path, args.exposure())
        .map_err(|e| e.to_string())?;
    let range = merged.pass_range();
    let m = mean.mean();
    say(&format!(
        "merged {}: passes {}..{} of {}, mean rgb ({:.4}, {:.4}, {:.4})",
        count(shards.len() as u64, "shard", "shards"),
        range.start,
        range.end,
        merged.scene(),
        m.x,
        m.y,
        m.z
    ));
    say(&format!(
        "wrote {} and {}",
        exr_path.display(),
        png_path.display()
    ));
    if let Some(path) = &args.stats_json {
        let json = stats_json(
            "merge",
            merged.scene(),
            merged.settings(),
            range,
            None,
            m.to_array(),
        );
        write_atomically(path, |w| w.write_all(json.as_bytes()))
            .map_err(|e| format!("{}: {e}", path.display()))?;
        say(&format!("wrote {}", path.display()));
    }
    Ok(())
}

/// ` light_units=…` for a glTF scene, whose lights it converts; nothing for a built-in scene,
/// whose lights are in watts already (the identity records only what applied).
fn light_units_applied(args: &Args) -> String {
    match scene_input(&args.scene) {
        Some(_) => format!(" light_units={}", args.light_units),
        None => String::new(),
    }
}

/// `n` and the noun in the number it takes: "1 pass", "2 passes".
fn count(n: u64, one: &str, many: &str) -> String {
    format!("{n} {}", if n == 1 { one } else { many })
}

/// The scene's name for output files, and its identity for shards: the name and a 64-bit
/// FNV-1a hash of the glTF file's bytes (or of the built-in scene's name).
fn scene_identity(arg: &str) -> Result<(String, String), String> {
    let name = super::files::scene_name(arg);
    let path = Path::new(arg);
    let fnv = |h: u64, bytes: &[u8]| {
        bytes
            .iter()
            .fold(h, |h, &b| (h ^ u64::from(b)).wrapping_mul(0x0000_0100_0000_01b3))
    };
    let mut hash = 0xcbf2_9ce4_8422_2325u64;
    if path.is_file() {
        // The loader has checked it is a regular file within its size limit; hashed in chunks.
        use std::io::Read as _;
        let mut file = std::fs::File::open(path).map_err(|e| format!("{arg}: {e}"))?;
        let mut chunk = vec![0u8; 1 << 16];
        loop {
            let n = file.read(&mut chunk).map_err(|e| format!("{arg}: {e}"))?;
            if n == 0 {
                break;
            }
            hash = fnv(hash, &chunk[..n]);
        }
    } else {
        hash = fnv(hash, arg.as_bytes());
    }
    Ok((name.clone(), format!("{name} fnv1a64:{hash:016x}")))
}

/// The refusal of shards rendered with other settings, naming the settings that differ: the
/// `key=value` tokens of the two settings identities (the words before the first `=` token,
/// "progressive v3" or "sppm", compared as `renderer`).
pub fn settings_differ(a: &str, b: &str) -> String {
    fn tokens(identity: &str) -> Vec<(String, String)> {
        let mut renderer = Vec::new();
        let mut pairs = Vec::new();
        for token in identity.split_whitespace() {
            match token.split_once('=') {
                Some((key, value)) => pairs.push((key.to_owned(), value.to_owned())),
                None if pairs.is_empty() => renderer.push(token),
                None => pairs.push((token.to_owned(), String::new())),
            }
        }
        pairs.insert(0, ("renderer".to_owned(), renderer.join(" ")));
        pairs
    }
    let (a, b) = (tokens(a), tokens(b));
    let value = |pairs: &[(String, String)], key: &str| {
        pairs
            .iter()
            .find(|(k, _)| k == key)
            .map_or_else(|| "(none)".to_owned(), |(_, v)| v.clone())
    };
    let mut keys: Vec<&str> = a.iter().map(|(k, _)| k.as_str()).collect();
    keys.extend(
        b.iter()
            .map(|(k, _)| k.as_str())
            .filter(|k| !a.iter().any(|(x, _)| x == k)),
    );
    let differ: Vec<String> = keys
        .into_iter()
        .filter(|k| value(&a, k) != value(&b, k))
        .map(|k| format!("{k} {} against {}", value(&a, k), value(&b, k)))
        .collect();
    if differ.is_empty() {
        // Tokens equal but the strings not (spacing): show both.
        return format!(
            "shards with different settings: '{}' and '{}'",
            a.iter()
                .map(|(k, v)| format!("{k}={v}"))
                .collect::<Vec<_>>()
                .join(" "),
            b.iter()
                .map(|(k, v)| format!("{k}={v}"))
                .collect::<Vec<_>>()
                .join(" ")
        );
    }
    format!(
        "shards with different settings, which must all match: {}",
        differ.join(", ")
    )
}

fn stats_json(
    mode: &str,
    scene: &str,
    settings: &str,
    range: std::ops::Range<u64>,
    stats: Option<(&ProgressiveStats, usize, &str, [f64; 3], Setup)>,
    mean: [f32; 3],
) -> String {
    let mut o = String::from("{");
    let _ = write!(
        o,
        "\"mode\": {}, \"scene\": {}, \"settings\": {}, \"first_pass\": {}, \"end_pass\": {}, \"passes\": {}, ",
        json_string(mode),
        json_string(scene),
        json_string(settings),
        range.start,
        range.end,
        range.end - range.start,
    );
    if let Some((s, heap_peak, contacts, origin_offset, setup)) = stats {
        let _ = write!(o, "\"contacts\": {contacts}, ");
        let _ = write!(o, "\"setup_seconds\": {}, ", setup.json());
        let _ = write!(o, "\"origin_offset\": {}, ", origin_json(origin_offset));
        let _ = write!(
            o,
            "\"memory_bytes\": {{\"peak_heap\": {heap_peak}, \"pass_trees\": {}, \"pilot\": {}, \"accumulation\": {}}}, ",
            s.pass_tree_bytes, s.pilot_bytes, s.accumulation_bytes
        );
        o.push_str(&super::emission::json(s.emission.as_ref(), s.photons_traced));
        let _ = write!(
            o,
            "\"photons_emitted\": {}, \"photons_stored\": {}, \"near_light_fraction\": {}, \"map_count\": {}, \"maps_read\": {}, \"threads\": {}, \"seconds\": {{\"pilot\": {}, \"trace\": {}, \"precompute\": {}, \"render\": {}, \"total\": {}}}, ",
            s.photons_emitted,
            s.photons_stored,
            json_number(s.near_light_fraction),
            s.map_count,
            s.maps_read,
            s.threads,
            json_number(s.pilot.as_secs_f64()),
            json_number(s.trace.as_secs_f64()),
            json_number(s.precompute.as_secs_f64()),
            json_number(s.render.as_secs_f64()),
            json_number(s.total().as_secs_f64()),
        );
    }
    let _ = writeln!(
        o,
        "\"mean_rgb\": [{}, {}, {}]}}",
        json_number(mean[0] as f64),
        json_number(mean[1] as f64),
        json_number(mean[2] as f64)
    );
    o
}

/// An indicatif bar of passes, with elapsed time and photons traced (hidden without a TTY).
struct PassBar(ProgressBar);

impl PassBar {
    fn new(passes: Option<u64>) -> Self {
        let bar = ProgressBar::new(passes.unwrap_or(0));
        let template = if passes.is_some() {
            "{msg:>10} [{bar:40}] {pos}/{len} passes {elapsed} {prefix} photons"
        } else {
            "{msg:>10} {pos} passes {elapsed} {prefix} photons"
        };
        if let Ok(style) = ProgressStyle::with_template(template) {
            bar.set_style(style.progress_chars("=> "));
        }
        bar.set_prefix("0");
        PassBar(bar)
    }
}

impl Progress for PassBar {
    fn phase(&self, name: &'static str) {
        self.0.set_message(name);
    }
    fn tiles_done(&self, _done: usize, _total: usize) {}
    fn pass_done(&self, passes: u64, photons: u64) {
        self.0.set_position(passes);
        self.0.set_prefix(photons.to_string());
    }
}
