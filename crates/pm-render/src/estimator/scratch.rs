//! The estimators' per-thread buffers.

use super::photon::GatheredPhoton;
use glam::Vec3;
use pm_geom::ClipScratch;
use pm_kdtree::{Neighbour, Neighbours};
use std::any::Any;

/// Per-thread buffers of the estimators; reuse one per worker so queries allocate nothing once
/// warm.
///
/// Estimators written outside this crate use the same building blocks as the built-in ones:
/// [`super::find_nearest`] fills [`EstimatorScratch::neighbours`], [`super::gather_found`] decodes them into
/// [`EstimatorScratch::photons`], and [`EstimatorScratch::slot`] keeps buffers of the
/// estimator's own type alive from one query to the next.
#[derive(Default)]
pub struct EstimatorScratch {
    pub(crate) neighbours: Neighbours,
    pub(crate) clip: ClipScratch,
    pub(crate) photons: Vec<GatheredPhoton>,
    /// Candidate faces that overlap the volume: (area inside, unit normal).
    pub(crate) faces: Vec<(f32, Vec3)>,
    pub(crate) candidates: Vec<u32>,
    /// Gather rays cast by the final gather on this worker since the renderer last read it.
    pub(crate) gather_rays: u64,
    /// An outside estimator's own buffers (see [`EstimatorScratch::slot`]).
    slot: Option<Box<dyn Any + Send>>,
}

impl Clone for EstimatorScratch {
    /// A copy of the built-in buffers; the estimator's own slot starts empty again (it is
    /// scratch, and its type need not be `Clone`).
    fn clone(&self) -> Self {
        EstimatorScratch {
            neighbours: self.neighbours.clone(),
            clip: self.clip.clone(),
            photons: self.photons.clone(),
            faces: self.faces.clone(),
            candidates: self.candidates.clone(),
            gather_rays: 0,
            slot: None,
        }
    }
}

impl std::fmt::Debug for EstimatorScratch {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("EstimatorScratch")
            .field("neighbours", &self.neighbours.len())
            .field("photons", &self.photons.len())
            .field("faces", &self.faces.len())
            .field("slot", &self.slot.is_some())
            .finish()
    }
}

impl EstimatorScratch {
    /// Empty scratch; grows on first use.
    pub fn new() -> Self {
        Self::default()
    }

    /// The neighbours found by the last [`super::find_nearest`], in no particular order (their
    /// indices are into the map's [`pm_kdtree::PhotonTree`], their distances under the query's metric).
    pub fn neighbours(&self) -> &[Neighbour] {
        self.neighbours.as_slice()
    }

    /// The photons decoded by the last [`super::gather_found`].
    pub fn photons(&self) -> &[GatheredPhoton] {
        &self.photons
    }

    /// The estimator's own scratch of type `T`, made with `T::default()` on first use and
    /// kept (with its capacity) for later queries on the same worker. Asking for another type
    /// replaces it, so an estimator should keep all its buffers in one type.
    pub fn slot<T: Any + Send + Default>(&mut self) -> &mut T {
        if !self.slot.as_ref().is_some_and(|s| s.is::<T>()) {
            self.slot = Some(Box::new(T::default()));
        }
        // Just made sure the slot holds a `T`.
        self.slot
            .as_mut()
            .and_then(|s| s.downcast_mut::<T>())
            .expect("slot holds a T")
    }

    /// The neighbours, the decoded photons and the estimator's own slot at once, for
    /// estimators that read the first two while writing the third.
    pub fn split<T: Any + Send + Default>(&mut self) -> (&[Neighbour], &[GatheredPhoton], &mut T) {
        self.slot::<T>();
        let slot = self
            .slot
            .as_mut()
            .and_then(|s| s.downcast_mut::<T>())
            .expect("slot holds a T");
        (self.neighbours.as_slice(), &self.photons, slot)
    }
}
