//! What a trace returns: the photons of each map, in path order, and statistics of the run.

use pm_kdtree::Photon;

/// Statistics of one tracing run.
#[derive(Clone, Debug, PartialEq)]
pub struct TraceStats {
    /// Paths emitted.
    pub emitted: u64,
    /// Photons stored per map, indexed by `PhotonKind as usize` (direct, indirect, caustic).
    pub stored: Vec<[u64; 3]>,
    /// The share of the emitted power (summed over channels) whose first hit lay on a surface
    /// within [`NEAR_LIGHT_DISTANCE`](super::NEAR_LIGHT_DISTANCE) (1 mm) of its light — the plane of the surface at the
    /// hit passes that close to where the photon left the light: 0 for lights that face into
    /// the scene, near 1 for a light facing into the wall or ceiling it sits on (an area light
    /// emits towards `edge_u × edge_v`: swapping its edges turns it round). That power still
    /// lights the scene, but from the wrong place.
    pub near_light_fraction: f64,
    /// Wall-clock seconds spent tracing.
    pub seconds: f64,
}

impl TraceStats {
    /// Photons stored over all maps and kinds.
    pub fn total_stored(&self) -> u64 {
        self.stored.iter().flatten().sum()
    }
}

/// The photons of each map, in path order, with statistics.
#[derive(Clone, Debug, PartialEq)]
pub struct TracedPhotons {
    pub(super) photons: Vec<Vec<Photon>>,
    pub(super) stats: TraceStats,
}

impl TracedPhotons {
    /// Photons per map (`photons_per_map()[map]`).
    pub fn photons_per_map(&self) -> &[Vec<Photon>] {
        &self.photons
    }

    /// The photons of one map. Panics when `map` is not below the map count (the length of
    /// [`TracedPhotons::photons_per_map`]), like slice indexing.
    pub fn photons(&self, map: u32) -> &[Photon] {
        &self.photons[map as usize]
    }

    /// Statistics.
    pub fn stats(&self) -> &TraceStats {
        &self.stats
    }

    /// Photons per map and statistics, by value.
    pub fn into_parts(self) -> (Vec<Vec<Photon>>, TraceStats) {
        (self.photons, self.stats)
    }
}
