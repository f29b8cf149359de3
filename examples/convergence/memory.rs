//! Peak heap of progressive and SPPM runs of growing pass counts, measured by the counting
//! allocator: it stays at one pass's photons, the pilot's and the running sum, however many
//! passes run.

use super::tracking_allocator::{peak, reset_peak};
use photon_maps::render::progressive::{
    ProgressiveRenderer, ProgressiveSettings, SppmRenderer, SppmSettings,
};
use photon_maps::render::{EstimatorKind, RenderSettings};
use photon_maps::trace::{CreaseAngle, Partitioner, Scene};

/// One run's figures.
#[derive(serde::Serialize, serde::Deserialize)]
pub struct MemoryRow {
    pub method: String,
    pub passes: u64,
    pub photons: u64,
    /// Peak heap bytes during the run, above what was live before it.
    pub peak: usize,
    /// The largest pass's photon trees, the pilot's trees and sites, and the running sum
    /// (bytes, as the renderer's statistics count them).
    pub pass_tree_bytes: u64,
    pub pilot_bytes: u64,
    pub accumulation_bytes: u64,
}

/// Runs progressive cube (crease maps) and SPPM for each of `counts` passes on `scene`.
pub fn rows(scene: &Scene, base: RenderSettings, counts: &[u64]) -> Result<Vec<MemoryRow>, String> {
    let mut out = Vec::new();
    for &passes in counts {
        for method in ["progressive cube", "SPPM"] {
            let before = reset_peak();
            let stats = if method == "SPPM" {
                SppmRenderer::new(SppmSettings::new(base, passes))
                    .render(scene, &())
                    .map_err(|e| e.to_string())?
                    .stats
            } else {
                let settings = ProgressiveSettings::new(base, passes);
                let crease = CreaseAngle::default()
                    .partition(scene.clone())
                    .map_err(|e| e.to_string())?;
                ProgressiveRenderer::new(EstimatorKind::GeometryCube, settings)
                    .render(&crease, &())
                    .map_err(|e| e.to_string())?
                    .stats
            };
            out.push(MemoryRow {
                method: method.to_owned(),
                passes,
                photons: stats.photons_emitted,
                peak: peak().saturating_sub(before),
                pass_tree_bytes: stats.pass_tree_bytes,
                pilot_bytes: stats.pilot_bytes,
                accumulation_bytes: stats.accumulation_bytes,
            });
        }
    }
    Ok(out)
}
