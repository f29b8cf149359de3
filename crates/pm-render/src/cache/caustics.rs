//! Jensen's caustic maps of a radiance cache: each photon map's caustic photons in a tree of
//! their own, made the same way whether the cache is built or read back from a file.

use crate::error::RenderError;
use pm_kdtree::{Photon, PhotonKind, PhotonTree};

/// Per tree, its photons of kind caustic alone in a tree of their own (their powers
/// re-encoded relative to that tree's scale). Deterministic: the same trees give the same
/// caustic trees, bit for bit.
pub(crate) fn caustic_trees(trees: &[&PhotonTree]) -> Result<Vec<PhotonTree>, RenderError> {
    trees
        .iter()
        .map(|tree| {
            let scale = tree.power_scale();
            let photons: Vec<Photon> = tree
                .iter()
                .filter(|p| p.kind() == PhotonKind::Caustic)
                .map(|p| p.decode(scale))
                .collect();
            PhotonTree::build(photons).map_err(|e| RenderError::BadFinalGather(e.to_string()))
        })
        .collect()
}
