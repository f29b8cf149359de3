//! Which options apply to which mode: an option given on the command line that the chosen
//! mode would not use is refused with one line, never silently ignored.

use super::Args;
use super::choices::{MapsChoice, ModeChoice};
use clap::ArgMatches;
use clap::parser::ValueSource;
use std::path::Path;

/// What a run does, as far as options are concerned.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Run {
    /// A single-pass render in this mode (with or without `--compare`).
    Single(ModeChoice),
    /// `--mode progressive` or `--mode sppm`.
    Passes(ModeChoice),
    /// `--merge`.
    Merge,
}

/// The options that apply only to some runs, with the runs they apply to and a phrase saying
/// so. Options not listed (`--out`, `--stats-json`, `--exposure`) apply to every run.
fn applies(option: &str, run: Run, args: &Args) -> Option<&'static str> {
    use ModeChoice::*;
    let maps_mode = |m: ModeChoice| matches!(m, PhotonMap | ShadowRays | Progressive | FinalGather);
    let gltf = {
        let ext = Path::new(&args.scene).extension().and_then(|e| e.to_str());
        ext.is_some_and(|e| e.eq_ignore_ascii_case("gltf") || e.eq_ignore_ascii_case("glb"))
    };
    let ok = match (option, run) {
        (_, Run::Merge) => return Some("no merge"),
        ("maps" | "estimator", Run::Single(m) | Run::Passes(m)) => maps_mode(m),
        ("contact_gap", Run::Single(m) | Run::Passes(m)) => {
            maps_mode(m) && args.maps() == MapsChoice::Contact
        }
        ("photons" | "k", Run::Single(m) | Run::Passes(m)) => m != PathTrace,
        ("spp", Run::Single(_)) => true,
        ("spp", Run::Passes(m)) => m == Progressive,
        ("passes" | "time", run) => matches!(run, Run::Passes(_)),
        (
            "save_cache" | "load_cache" | "frames" | "orbit" | "auto_photons" | "auto_max_photons"
            | "auto_max_batches",
            run,
        ) => {
            matches!(run, Run::Single(PhotonMap | ShadowRays | FinalGather))
        }
        ("first_pass" | "direct" | "shard_index_from" | "passes_per_shard", run) => {
            run == Run::Passes(Progressive)
        }
        ("light_units", _) => gltf,
        ("emission", Run::Single(m) | Run::Passes(m)) => m != PathTrace,
        ("guide_pilot" | "guide_floor", Run::Single(m) | Run::Passes(m)) => {
            m != PathTrace && args.emission.emission == super::emission::EmissionChoice::Camera
        }
        // gather.rs refines progressive: there they need --gather-rays.
        ("gather_rays" | "cache_every" | "corner_distance", run) => {
            matches!(run, Run::Single(FinalGather) | Run::Passes(Progressive))
        }
        _ => true,
    };
    if ok {
        return None;
    }
    Some(match option {
        "maps" | "estimator" => "the photon-map modes (photon-map, shadow-rays, final-gather, progressive)",
        "contact_gap" => "--maps contact (the default) in the photon-map modes",
        "gather_rays" | "cache_every" | "corner_distance" => "--mode final-gather and --mode progressive",
        "photons" | "k" => "the modes that read photon maps (not path-trace)",
        "spp" => "the single-pass and progressive modes (SPPM traces one ray per pixel and pass)",
        "passes" | "time" => "--mode progressive and --mode sppm",
        "save_cache" | "load_cache" | "frames" | "orbit" | "auto_photons" | "auto_max_photons"
        | "auto_max_batches" => {
            "the single-pass modes that read photons (photon-map, shadow-rays, final-gather; each progressive pass traces its own)"
        }
        "first_pass" | "direct" | "shard_index_from" | "passes_per_shard" => "--mode progressive",
        "light_units" => "glTF scenes (built-in scenes are in watts already)",
        "emission" => "the modes that trace photons (not path-trace)",
        "guide_pilot" | "guide_floor" => "--emission camera in the modes that trace photons",
        _ => "other modes",
    })
}

/// The options that some runs ignore, by clap id and command-line name.
const OPTIONS: [(&str, &str); 31] = [
    ("scene", "--scene"),
    ("maps", "--maps"),
    ("estimator", "--estimator"),
    ("mode", "--mode"),
    ("photons", "--photons"),
    ("k", "--k"),
    ("size", "--size"),
    ("spp", "--samples-per-pixel"),
    ("threads", "--threads"),
    ("seed", "--seed"),
    ("passes", "--passes"),
    ("first_pass", "--first-pass"),
    ("shard_index_from", "--shard-index-from"),
    ("passes_per_shard", "--passes-per-shard"),
    ("time", "--time"),
    ("light_units", "--light-units"),
    ("direct", "--direct"),
    ("gather_rays", "--gather-rays"),
    ("cache_every", "--cache-every"),
    ("corner_distance", "--corner-distance"),
    ("contact_gap", "--contact-gap"),
    ("save_cache", "--save-cache"),
    ("load_cache", "--load-cache"),
    ("frames", "--frames"),
    ("orbit", "--orbit"),
    ("auto_photons", "--auto-photons"),
    ("auto_max_photons", "--auto-max-photons"),
    ("auto_max_batches", "--auto-max-batches"),
    ("emission", "--emission"),
    ("guide_pilot", "--guide-pilot"),
    ("guide_floor", "--guide-floor"),
];

/// Refuses the first option given on the command line that this run would not use.
pub fn refuse_inapplicable(args: &Args, matches: &ArgMatches) -> Result<(), String> {
    let run = if !args.merge.is_empty() {
        Run::Merge
    } else if args.mode.is_progressive() {
        Run::Passes(args.mode)
    } else {
        Run::Single(args.mode)
    };
    for (id, name) in OPTIONS {
        if matches.value_source(id) != Some(ValueSource::CommandLine) {
            continue;
        }
        // --merge takes everything but its outputs and the preview's exposure from the
        // shards; the modes take all of the scene options.
        let merge_only_ignores = matches!(run, Run::Merge);
        let scene_option = matches!(id, "scene" | "mode" | "size" | "threads" | "seed");
        if scene_option && !merge_only_ignores {
            continue;
        }
        if let Some(where_) = applies(id, run, args) {
            return Err(match run {
                Run::Merge => format!(
                    "{name} does not apply to --merge: the shards carry their scene and settings; drop it"
                ),
                Run::Single(m) | Run::Passes(m) => {
                    format!("{name} does not apply to --mode {m}: it is used by {where_} only; drop it")
                }
            });
        }
    }
    Ok(())
}
