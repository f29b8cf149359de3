//! The settings of an automatic photon count and what it reports.

use crate::error::RenderError;

/// How to choose the photon count automatically.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct AutoPhotons {
    /// Photon paths of the first batch; batch `k` holds `start · 2ᵏ`. At most 2²⁴ (so that
    /// every count is exact in `f32`).
    pub start: u32,
    /// Stop once the relative RMS change between two batches is below this; in (0, 1).
    pub threshold: f64,
    /// The most photon paths (at most [`pm_trace::MAX_PHOTON_PATHS`]): no batch goes past it.
    pub max_photons: u32,
    /// The most batches (at least 2: the first change needs two).
    pub max_batches: u32,
    /// About how many probe points (at least 1).
    pub probes: u32,
}

impl AutoPhotons {
    /// Probe points by default.
    pub const DEFAULT_PROBES: u32 = 1024;
    /// Batches by default.
    pub const DEFAULT_MAX_BATCHES: u32 = 12;

    /// Start at `start` paths, stop below `threshold`, with the default bounds (up to
    /// [`pm_trace::MAX_PHOTON_PATHS`], 12 batches, 1024 probes).
    pub fn new(start: u32, threshold: f64) -> Self {
        AutoPhotons {
            start,
            threshold,
            max_photons: pm_trace::MAX_PHOTON_PATHS,
            max_batches: Self::DEFAULT_MAX_BATCHES,
            probes: Self::DEFAULT_PROBES,
        }
    }

    /// Refuses a threshold outside (0, 1) ([`RenderError::BadAutoThreshold`]) and a start of
    /// 0 or past 2²⁴ or past the maximum, a maximum past [`pm_trace::MAX_PHOTON_PATHS`],
    /// fewer than 2 batches or no probes ([`RenderError::BadAutoPhotons`]).
    pub fn validate(&self) -> Result<(), RenderError> {
        if !(self.threshold > 0.0 && self.threshold < 1.0) {
            return Err(RenderError::BadAutoThreshold(self.threshold));
        }
        let bad = |m: String| Err(RenderError::BadAutoPhotons(m));
        if self.start == 0 || self.start > 1 << 24 {
            return bad(format!("start of {} photons: expected 1 to 2^24", self.start));
        }
        if self.max_photons > pm_trace::MAX_PHOTON_PATHS {
            return bad(format!(
                "maximum of {} photons: expected at most {}",
                self.max_photons,
                pm_trace::MAX_PHOTON_PATHS
            ));
        }
        if self.start > self.max_photons {
            return bad(format!(
                "start of {} photons past the maximum of {}",
                self.start, self.max_photons
            ));
        }
        if self.max_batches < 2 {
            return bad(format!("{} batches: expected at least 2", self.max_batches));
        }
        if self.probes == 0 {
            return bad("no probe points: expected at least 1".into());
        }
        Ok(())
    }
}

/// One batch of an automatic photon count.
#[derive(Clone, Debug, PartialEq)]
pub struct AutoBatch {
    /// Photon paths held after the batch.
    pub photons: u32,
    /// Relative RMS change of the probes' irradiance from the previous batch (`None` for the
    /// first).
    pub change: Option<f64>,
}

/// What an automatic photon count did.
#[derive(Clone, Debug, PartialEq)]
pub struct AutoPhotonsReport {
    /// The count it stopped at: the maps are those of a plain run with this many photons.
    pub photons: u32,
    /// The threshold asked for.
    pub threshold: f64,
    /// True when the last change fell below the threshold (false: a bound stopped it).
    pub converged: bool,
    /// Probe points compared.
    pub probes: usize,
    /// Every batch, in order.
    pub batches: Vec<AutoBatch>,
}
