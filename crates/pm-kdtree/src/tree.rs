//! The implicit kd-tree over compact photons.

use crate::{BuildError, CompactPhoton, KindMask, Metric, Neighbours};
use glam::Vec3;

/// A kd-tree of photons in an implicit layout (no per-node pointers).
#[derive(Clone, Debug, Default)]
pub struct PhotonTree {
    photons: Vec<CompactPhoton>,
}

impl PhotonTree {
    /// Builds the tree (reorders the photons). Errors on non-finite positions.
    pub fn build(photons: Vec<CompactPhoton>) -> Result<Self, BuildError> {
        let _ = photons;
        todo!("pm-kdtree issue")
    }
    /// Number of photons.
    pub fn len(&self) -> usize {
        self.photons.len()
    }
    /// True when empty.
    pub fn is_empty(&self) -> bool {
        self.photons.is_empty()
    }
    /// Photon `index` (tree order).
    pub fn get(&self, index: u32) -> CompactPhoton {
        self.photons[index as usize]
    }
    /// The `k` nearest photons to `query` under metric `M` within `max_distance` whose kind is
    /// in `kinds`, written into `out`.
    pub fn nearest_k<M: Metric>(&self, query: Vec3, k: usize, max_distance: f32, kinds: KindMask, out: &mut Neighbours) {
        let _ = (query, k, max_distance, kinds, out);
        todo!("pm-kdtree issue")
    }
    /// Calls `f(index, distance)` for every photon within `radius` of `query` under `M`.
    pub fn for_each_within<M: Metric>(&self, query: Vec3, radius: f32, f: impl FnMut(u32, f32)) {
        let _ = (query, radius, f);
        todo!("pm-kdtree issue")
    }
}
