//! One pass's photons: a kd-tree per map, and nothing else. A map's polygons never change from
//! pass to pass, so the renderers take them from the pilot maps built once; and photons of
//! kinds the pass never gathers (direct ones, when shadow rays carry direct light) are not put
//! in the trees, as pbrt-v4's SPPM deposits none at a path's first hit.

use crate::emission::emitter::Emitter;
use crate::error::RenderError;
use crate::progress::Progress;
use crate::progressive::accumulation::ProgressiveStats;
use crate::settings::RenderSettings;
use pm_kdtree::{KindMask, PhotonTree};
use pm_trace::{MapAssignment, MapError, Scene};
use rayon::prelude::*;
use std::time::Instant;

/// The photon trees of one pass, indexed by map id, the photons stored in them, and the share
/// of the pass's power whose first hit lay within 1 mm of its light.
pub(crate) struct PassMaps {
    pub(crate) trees: Vec<PhotonTree>,
    pub(crate) emitted: u64,
    pub(crate) traced: u64,
    pub(crate) stored: u64,
    pub(crate) near_light_fraction: f64,
}

impl PassMaps {
    /// Heap bytes of the trees.
    pub(crate) fn heap_bytes(&self) -> u64 {
        self.trees.iter().map(|t| t.heap_bytes() as u64).sum()
    }
}

/// Traces pass `pass`'s photons (streams `(seed, pass, path)`, emitted as `emitter` says)
/// and builds one kd-tree per map of the photons of the kinds `kinds` accepts, in parallel.
pub(crate) fn trace_pass(
    scene: &Scene,
    assignment: &MapAssignment,
    settings: &RenderSettings,
    emitter: &Emitter,
    pass: u64,
    kinds: KindMask,
) -> Result<PassMaps, RenderError> {
    let traced = emitter.trace(scene, assignment, settings, pass)?;
    let (emitted, traced_paths) = (traced.stats().emitted, traced.stats().traced);
    let stored = traced.stats().total_stored();
    let near_light_fraction = traced.stats().near_light_fraction;
    let (photons, _) = traced.into_parts();
    let trees = photons
        .into_par_iter()
        .enumerate()
        .map(|(map, mut photons)| {
            if !kinds.accepts_all() {
                photons.retain(|p| kinds.accepts(p.kind));
            }
            PhotonTree::build(photons).map_err(|source| MapError::Tree {
                map: map as u32,
                source,
            })
        })
        .collect::<Result<Vec<_>, _>>()?;
    Ok(PassMaps {
        trees,
        emitted,
        traced: traced_paths,
        stored,
        near_light_fraction,
    })
}

/// [`trace_pass`] as a renderer runs it: announced as the "trace" phase, timed, and counted
/// into `stats` as the pass after `done` passes.
#[allow(clippy::too_many_arguments)]
pub(crate) fn trace_pass_counted(
    scene: &Scene,
    assignment: &MapAssignment,
    settings: &RenderSettings,
    emitter: &Emitter,
    pass: u64,
    kinds: KindMask,
    done: u64,
    stats: &mut ProgressiveStats,
    progress: &dyn Progress,
) -> Result<PassMaps, RenderError> {
    progress.phase("trace");
    let t = Instant::now();
    let maps = trace_pass(scene, assignment, settings, emitter, pass, kinds)?;
    stats.trace += t.elapsed();
    stats.photons_emitted += maps.emitted;
    stats.photons_traced += maps.traced;
    stats.photons_stored += maps.stored;
    stats.add_near_light(done, maps.near_light_fraction);
    stats.pass_tree_bytes = stats.pass_tree_bytes.max(maps.heap_bytes());
    Ok(maps)
}
