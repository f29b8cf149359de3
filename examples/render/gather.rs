//! The final gather's options of the render example (`--gather-rays`, `--cache-every`,
//! `--corner-distance`): their settings, refused in modes that do not gather.

use super::Args;
use super::choices::ModeChoice;
use photon_maps::render::FinalGatherOptions;

/// The command line's default gather rays per camera sample in final-gather mode, with
/// [`SAMPLES_PER_PIXEL`] camera samples: at equal CPU time they reach a lower error than the
/// library's 1 × 64 (`docs/final-gather-sweep.md`).
pub const GATHER_RAYS: u32 = 4;

/// The command line's default camera samples per pixel in final-gather mode.
pub const SAMPLES_PER_PIXEL: u32 = 16;

/// The final gather's options from the command line; an error when one is given in a mode
/// that does not gather (so that it is not silently ignored). `--mode progressive` gathers
/// when `--gather-rays` is given ([`gathers`]).
pub fn options(args: &Args) -> Result<FinalGatherOptions, String> {
    let given = [
        ("--gather-rays", args.gather_rays.is_some()),
        ("--cache-every", args.cache_every.is_some()),
        ("--corner-distance", args.corner_distance.is_some()),
    ];
    let applies = args.mode == ModeChoice::FinalGather || gathers(args);
    if !applies && let Some((name, _)) = given.iter().find(|(_, set)| *set) {
        return Err(if args.mode == ModeChoice::Progressive {
            format!("{name} needs --gather-rays in progressive mode (a final gather per pass)")
        } else {
            format!(
                "{name} applies to --mode final-gather (or progressive with --gather-rays) only, not {}",
                args.mode
            )
        });
    }
    let defaults = FinalGatherOptions::default();
    Ok(FinalGatherOptions {
        gather_rays: args.gather_rays.unwrap_or(GATHER_RAYS),
        cache_every: args.cache_every.unwrap_or(defaults.cache_every),
        corner_distance: args.corner_distance.or(defaults.corner_distance),
    })
}

/// True for `--mode progressive --gather-rays N`: each pass is a final gather with the pass's
/// photons and fixed volumes (the consistent final gather).
pub fn gathers(args: &Args) -> bool {
    args.mode == ModeChoice::Progressive && args.gather_rays.is_some()
}
