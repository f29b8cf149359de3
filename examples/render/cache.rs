//! `--save-cache` and `--load-cache`: a single-pass render that builds its photon maps (and
//! final-gather cache) and saves them, or loads them from a file instead of tracing.

use super::Args;
use photon_maps::render::cache_file::{load_cache_file, save_cache_file};
use photon_maps::render::{EstimatorKind, PhotonCache, Progress, RenderStats, Rendered, Renderer};
use photon_maps::trace::{Camera, Partitioned};
use std::time::Instant;

/// What happened to the cache file, for the summary and the JSON.
pub struct CacheUse {
    /// `"saved"` or `"loaded"`.
    pub what: &'static str,
    /// Seconds spent writing or reading the file.
    pub seconds: f64,
}

/// The render of `partitioned` from photons loaded from `--load-cache`, or built and saved to
/// `--save-cache`: the image is the bits of a render without either option.
pub fn render_with_cache_file(
    args: &Args,
    renderer: &Renderer<EstimatorKind>,
    partitioned: &Partitioned,
    progress: &dyn Progress,
) -> Result<(Rendered, CacheUse), String> {
    let camera = *partitioned.scene().camera();
    let (cache, mut stats, used) = obtain_cache(args, renderer, partitioned, &[camera], progress)?;
    let used = used.ok_or("no cache file named")?;
    let image = renderer
        .render_from_cache(partitioned.scene(), &cache, progress, &mut stats)
        .map_err(|e| e.to_string())?;
    Ok((Rendered { image, stats }, used))
}

/// The photon cache of a run: loaded from `--load-cache`, or built (and saved to
/// `--save-cache` if named); with the set-up's figures (trace, build, precompute, or the
/// load's counts) and what was done with a file. A built cache's camera-driven emission
/// learns what `cameras` (the frames it will render) see.
pub fn obtain_cache(
    args: &Args,
    renderer: &Renderer<EstimatorKind>,
    partitioned: &Partitioned,
    cameras: &[Camera],
    progress: &dyn Progress,
) -> Result<(PhotonCache, RenderStats, Option<CacheUse>), String> {
    let mut stats = RenderStats {
        threads: match renderer.settings().threads {
            0 => rayon::current_num_threads(),
            n => n,
        },
        ..RenderStats::default()
    };
    if let Some(path) = &args.load_cache {
        let start = Instant::now();
        progress.phase("load cache");
        let cache = load_cache_file(path, renderer, partitioned)
            .map_err(|e| format!("--load-cache {}: {e}", path.display()))?;
        cache.record_figures(renderer.settings().k, &mut stats);
        let used = CacheUse {
            what: "loaded",
            seconds: start.elapsed().as_secs_f64(),
        };
        return Ok((cache, stats, Some(used)));
    }
    let cache = match args.auto.settings(args.photons)? {
        Some(auto) => renderer.build_photon_cache_auto(partitioned, &auto, progress, &mut stats),
        None => renderer.build_photon_cache_seen_from(partitioned, cameras, progress, &mut stats),
    }
    .map_err(|e| e.to_string())?;
    let Some(path) = &args.save_cache else {
        return Ok((cache, stats, None));
    };
    // Only the write is the file's time; tracing and building are timed apart.
    let saving = Instant::now();
    progress.phase("save cache");
    save_cache_file(path, renderer, partitioned, &cache)
        .map_err(|e| format!("--save-cache {}: {e}", path.display()))?;
    let used = CacheUse {
        what: "saved",
        seconds: saving.elapsed().as_secs_f64(),
    };
    Ok((cache, stats, Some(used)))
}
