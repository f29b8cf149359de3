//! Query results: a reusable buffer of neighbours plus the search extent.

/// One found photon.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Neighbour {
    /// Index into the tree ([`crate::PhotonTree::get`]).
    pub index: u32,
    /// Distance from the query point under the query's metric (not squared).
    pub distance: f32,
}

/// Reusable result buffer of a k-nearest query; keep one per thread.
#[derive(Clone, Debug, Default)]
pub struct Neighbours {
    found: Vec<Neighbour>,
    extent: f32,
    partial: bool,
}

impl Neighbours {
    /// An empty buffer.
    pub fn new() -> Self {
        Self::default()
    }
    /// The neighbours found (order unspecified).
    pub fn as_slice(&self) -> &[Neighbour] {
        &self.found
    }
    /// The search extent: the k-th distance, or the maximum distance when fewer than k were found.
    pub fn extent(&self) -> f32 {
        self.extent
    }
    /// True when fewer than k photons lay within the maximum distance.
    pub fn is_partial(&self) -> bool {
        self.partial
    }
}
