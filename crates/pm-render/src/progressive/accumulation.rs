//! What a progressive render gives back: the exact running sum of its passes, and its counts,
//! timings and memory.

use super::pass_sum::PassSums;
use crate::error::RenderError;
use crate::image::Image;
use std::ops::Range;
use std::time::Duration;

/// The running sum of a progressive render's passes, kept exactly (see [`PassSums`]): the
/// merge of shards of passes gives the same bits as one run of them.
#[derive(Clone, Debug, PartialEq)]
pub struct Accumulation {
    pub(super) sums: PassSums,
    pub(super) first_pass: u64,
    pub(super) passes: u64,
}

impl Accumulation {
    /// An empty sum starting at pass `first_pass`.
    pub fn new(width: u32, height: u32, first_pass: u64) -> Result<Self, RenderError> {
        Ok(Accumulation {
            sums: PassSums::new(width, height)?,
            first_pass,
            passes: 0,
        })
    }

    /// The passes summed.
    pub fn pass_range(&self) -> Range<u64> {
        self.first_pass..self.first_pass + self.passes
    }

    /// Number of passes summed.
    pub fn passes(&self) -> u64 {
        self.passes
    }

    /// The per-pixel sums of the passes' radiance.
    pub fn sums(&self) -> &PassSums {
        &self.sums
    }

    /// The mean of the passes: the progressive estimate (black before any pass).
    pub fn mean(&self) -> Image {
        self.sums.mean(self.passes)
    }
}

/// Counts and timings of a progressive render.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct ProgressiveStats {
    /// Passes rendered.
    pub passes: u64,
    /// Photon paths emitted over all passes (not counting the pilot).
    pub photons_emitted: u64,
    /// Photon paths traced on over all passes: `photons_emitted` less those camera-driven
    /// emission dropped at their lights.
    pub photons_traced: u64,
    /// What camera-driven emission learnt (once, before the passes; its time is part of
    /// [`Self::pilot`]); `None` for uniform emission.
    pub emission: Option<crate::emission::choice::EmissionReport>,
    /// Photons stored over all passes.
    pub photons_stored: u64,
    /// The share of the emitted power whose first hit lay within 1 mm of its light, averaged
    /// over the passes ([`crate::RenderStats::near_light_fraction`]): near 1 when a light faces
    /// into the wall or ceiling it sits on.
    pub near_light_fraction: f64,
    /// Number of photon maps.
    pub map_count: u32,
    /// Maps whose polygons the passes have read (each built the first time an estimate fell
    /// in it): the maps the camera's paths reach, a small share of a finely split scene's.
    /// Zero for SPPM, which reads no polygons.
    pub maps_read: u32,
    /// Worker threads used.
    pub threads: usize,
    /// Partitioning the scene, learning camera-driven emission, and tracing and building the
    /// pilot maps.
    pub pilot: Duration,
    /// Photon tracing and map building, summed over passes.
    pub trace: Duration,
    /// Rendering, summed over passes.
    pub render: Duration,
    /// Precomputing the final gather's irradiance caches, summed over passes (zero in the
    /// other modes).
    pub precompute: Duration,
    /// Wall time of the whole run, pilot and the observer's own time included ([`Self::total`]).
    pub wall: Duration,
    /// Heap bytes of the largest pass's photon trees: the photons one pass holds (earlier
    /// passes' are dropped before the next is traced; tracing needs about twice this while
    /// the photons are sorted into trees).
    pub pass_tree_bytes: u64,
    /// Heap bytes of the pilot's photon trees and sites (zero for SPPM, which has no pilot).
    pub pilot_bytes: u64,
    /// Heap bytes of the running sum (SPPM: its per-pixel state).
    pub accumulation_bytes: u64,
}

impl ProgressiveStats {
    /// The whole run's wall time (as [`crate::RenderStats::total`] is a one-shot render's).
    pub fn total(&self) -> Duration {
        self.wall
    }

    /// Folds pass number `done` (counting from 0) into the mean near-light fraction; every
    /// pass emits the same number of photon paths, so each weighs the same.
    pub(crate) fn add_near_light(&mut self, done: u64, fraction: f64) {
        self.near_light_fraction += (fraction - self.near_light_fraction) / (done + 1) as f64;
    }
}

/// A progressive render's sum and figures.
#[derive(Clone, Debug)]
pub struct ProgressiveRendered {
    /// The sum of the passes (its [`Accumulation::mean`] is the image).
    pub accumulation: Accumulation,
    /// Counts and timings.
    pub stats: ProgressiveStats,
    /// Everything that changes the image ([`super::ProgressiveRenderer::identity`]): shards
    /// of runs whose identities differ never merge.
    pub identity: String,
}
