//! What a trace returns: the photons of each map, in path order, and statistics of the run.

use super::options::MAX_STORED_PHOTONS;
use crate::error::{PhotonFault, TraceError};
use pm_kdtree::Photon;

/// Statistics of one tracing run.
#[derive(Clone, Debug, PartialEq)]
pub struct TraceStats {
    /// Paths emitted.
    pub emitted: u64,
    /// Paths traced on from their light: `emitted` less those an
    /// [`EmissionGuide`](super::EmissionGuide) dropped there (all of them without one).
    pub traced: u64,
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
    /// Photons from a tracer of your own, ready for
    /// [`PhotonMaps::build`](super::PhotonMaps::build): `photons[m]` are the photons stored in
    /// map `m` of the assignment the maps will be built with (positions in metres, powers in
    /// watts as [`trace_photons`](super::trace_photons) stores them: each path's share of the
    /// light's power), and `emitted` is the number of photon paths traced. The statistics count
    /// the photons per map and kind; the time and the near-light fraction are zero.
    ///
    /// Refused before anything is kept: more than [`MAX_STORED_PHOTONS`] photons in all
    /// ([`TraceError::TooManyPhotonsStored`]); a photon whose position is not finite, whose
    /// direction is not finite or is zero, or whose power is not finite and non-negative
    /// ([`TraceError::InvalidPhoton`], naming the map, the index and the fault). A photon far
    /// outside the scene is refused when the maps are built (`MapError::Tree`).
    pub fn new(photons: Vec<Vec<Photon>>, emitted: u64) -> Result<Self, TraceError> {
        let total: u64 = photons.iter().map(|list| list.len() as u64).sum();
        if total > MAX_STORED_PHOTONS {
            return Err(TraceError::TooManyPhotonsStored {
                limit: MAX_STORED_PHOTONS,
            });
        }
        let mut stored = Vec::with_capacity(photons.len());
        for (map, list) in photons.iter().enumerate() {
            let mut kinds = [0u64; 3];
            for (index, photon) in list.iter().enumerate() {
                if let Some(reason) = fault(photon) {
                    return Err(TraceError::InvalidPhoton { map, index, reason });
                }
                kinds[photon.kind as usize] += 1;
            }
            stored.push(kinds);
        }
        Ok(TracedPhotons {
            photons,
            stats: TraceStats {
                emitted,
                traced: emitted,
                stored,
                near_light_fraction: 0.0,
                seconds: 0.0,
            },
        })
    }

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

/// What keeps `photon` out of a map, if anything.
fn fault(photon: &Photon) -> Option<PhotonFault> {
    if !photon.position.is_finite() {
        Some(PhotonFault::Position)
    } else if !photon.direction.is_finite() || photon.direction == glam::Vec3::ZERO {
        Some(PhotonFault::Direction)
    } else if !photon.power.is_finite() || photon.power.min_element() < 0.0 {
        Some(PhotonFault::Power)
    } else {
        None
    }
}
