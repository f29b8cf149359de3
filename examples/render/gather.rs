//! The final gather's options of the render example (`--gather-rays`, `--cache-every`,
//! `--corner-distance`): their settings, refused in modes that do not gather.

use super::Args;
use super::choices::ModeChoice;
use photon_maps::render::FinalGatherOptions;

/// The final gather's options from the command line; an error when one is given in a mode
/// that does not gather (so that it is not silently ignored).
pub fn options(args: &Args) -> Result<FinalGatherOptions, String> {
    let given = [
        ("--gather-rays", args.gather_rays.is_some()),
        ("--cache-every", args.cache_every.is_some()),
        ("--corner-distance", args.corner_distance.is_some()),
    ];
    if args.mode != ModeChoice::FinalGather
        && let Some((name, _)) = given.iter().find(|(_, set)| *set)
    {
        return Err(format!(
            "{name} applies to --mode final-gather only, not {}",
            args.mode
        ));
    }
    let defaults = FinalGatherOptions::default();
    Ok(FinalGatherOptions {
        gather_rays: args.gather_rays.unwrap_or(defaults.gather_rays),
        cache_every: args.cache_every.unwrap_or(defaults.cache_every),
        corner_distance: args.corner_distance.unwrap_or(defaults.corner_distance),
    })
}
