//! `--save-cache` and `--load-cache`: a single-pass render that builds its photon maps (and
//! final-gather cache) and saves them, or loads them from a file instead of tracing.

use super::Args;
use photon_maps::render::cache_file::{load_cache_file, save_cache_file};
use photon_maps::render::{EstimatorKind, Progress, RenderStats, Rendered, Renderer};
use photon_maps::trace::Partitioned;
use std::time::{Duration, Instant};

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
    let mut stats = RenderStats {
        threads: match renderer.settings().threads {
            0 => rayon::current_num_threads(),
            n => n,
        },
        ..RenderStats::default()
    };
    let start = Instant::now();
    let (cache, what) = match (&args.load_cache, &args.save_cache) {
        (Some(path), _) => {
            progress.phase("load cache");
            let cache = load_cache_file(path, renderer, partitioned)
                .map_err(|e| format!("--load-cache {}: {e}", path.display()))?;
            cache.record_figures(renderer.settings().k, &mut stats);
            (cache, "loaded")
        }
        (None, Some(path)) => {
            let cache = renderer
                .build_photon_cache(partitioned, progress, &mut stats)
                .map_err(|e| e.to_string())?;
            let saving = Instant::now();
            progress.phase("save cache");
            save_cache_file(path, renderer, partitioned, &cache)
                .map_err(|e| format!("--save-cache {}: {e}", path.display()))?;
            // Only the write is the file's time; tracing and building are timed apart.
            return render_from(
                renderer,
                partitioned,
                &cache,
                progress,
                stats,
                "saved",
                saving.elapsed(),
            );
        }
        (None, None) => return Err("no cache file named".into()),
    };
    render_from(
        renderer,
        partitioned,
        &cache,
        progress,
        stats,
        what,
        start.elapsed(),
    )
}

fn render_from(
    renderer: &Renderer<EstimatorKind>,
    partitioned: &Partitioned,
    cache: &photon_maps::render::PhotonCache,
    progress: &dyn Progress,
    mut stats: RenderStats,
    what: &'static str,
    file_time: Duration,
) -> Result<(Rendered, CacheUse), String> {
    let image = renderer
        .render_from_cache(partitioned.scene(), cache, progress, &mut stats)
        .map_err(|e| e.to_string())?;
    Ok((
        Rendered { image, stats },
        CacheUse {
            what,
            seconds: file_time.as_secs_f64(),
        },
    ))
}
