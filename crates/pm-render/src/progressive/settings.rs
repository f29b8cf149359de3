//! What a progressive render is asked for: its render settings, α, the pass range and a time
//! budget, their checks, and the text naming everything that changes its image.

use super::pass_sum::PassSums;
use crate::error::RenderError;
use crate::limits::MAX_PASS;
use crate::mode::Mode;
use crate::settings::RenderSettings;
use std::time::Duration;

/// The version of the progressive algorithm, part of [`ProgressiveSettings::identity`]: bumped
/// whenever the same settings would render a different image (v2: pilot extents at sparse
/// sites, computed once; v3: ray offsets by each hit's rounding error, the final gather's cache
/// in full precision; v4: triangle hit points moved onto the triangle's plane), so that shards
/// of different versions are never merged.
pub const PROGRESSIVE_VERSION: &str = "v4";

/// Settings of a progressive render.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ProgressiveSettings {
    /// Image, photons *per pass*, k (for the pilot's extents), maximum distance, seed,
    /// threads. `mode` must be [`Mode::PhotonMap`] (photons for all light),
    /// [`Mode::ShadowRays`] (direct light by shadow rays, photons for the rest) or
    /// [`Mode::FinalGather`] (a final gather per pass: the pass's caustic photons and cache,
    /// each read in the pass's fixed volume; a gather hit reads the cache only from a point
    /// within that volume and estimates afresh otherwise, so the gather converges too).
    pub render: RenderSettings,
    /// Knaus & Zwicker's α in (0, 1): the share of the previous pass's volume kept (default 2/3).
    pub alpha: f32,
    /// The first pass rendered (0 for a whole run; a shard's start otherwise).
    pub first_pass: u64,
    /// Passes to render; `None` renders until the time budget is spent.
    pub passes: Option<u64>,
    /// Stop after the pass that spends this budget (wall time, including the pilot).
    pub time_budget: Option<Duration>,
}

impl ProgressiveSettings {
    /// The default α.
    pub const DEFAULT_ALPHA: f32 = 2.0 / 3.0;

    /// `passes` passes from pass 0 with α = 2/3 and `render`'s settings.
    pub fn new(render: RenderSettings, passes: u64) -> Self {
        ProgressiveSettings {
            render,
            alpha: Self::DEFAULT_ALPHA,
            first_pass: 0,
            passes: Some(passes),
            time_budget: None,
        }
    }

    /// Checks the render settings, the mode, α, that the exact sums fit
    /// [`crate::image::MAX_PIXEL_STATE_BYTES`], and that the run will stop.
    pub fn validate(&self) -> Result<(), RenderError> {
        self.render.validate()?;
        crate::image::check_pixel_state(self.render.width, self.render.height, PassSums::BYTES_PER_PIXEL)?;
        if !matches!(
            self.render.mode,
            Mode::PhotonMap | Mode::ShadowRays | Mode::FinalGather
        ) {
            return Err(RenderError::UnsupportedMode(self.render.mode));
        }
        if !(self.alpha > 0.0 && self.alpha < 1.0) {
            return Err(RenderError::BadAlpha(self.alpha));
        }
        match (self.passes, self.time_budget) {
            (Some(0), _) | (None, None) => return Err(RenderError::ZeroPasses),
            _ => {}
        }
        // The passes must end by u64::MAX, whose streams are the pilot's.
        let last = self
            .first_pass
            .checked_add(self.passes.unwrap_or(1) - 1)
            .filter(|&last| last <= MAX_PASS);
        match last {
            Some(_) => Ok(()),
            None => Err(RenderError::PassRange {
                first_pass: self.first_pass,
                passes: self.passes,
            }),
        }
    }

    /// A text naming every setting that changes the image (not the pass range, threads or
    /// tiles), and the version of the algorithm ([`PROGRESSIVE_VERSION`]): shards merge only
    /// when theirs are equal.
    pub fn identity(&self) -> String {
        let s = &self.render;
        let max_distance = s
            .max_distance
            .map_or_else(|| "default".to_owned(), |d| format!("{d:e}"));
        // The final gather's parameters change its image (and only its).
        let gather = if s.mode == Mode::FinalGather {
            let g = &s.final_gather;
            format!(
                " gather_rays={} cache_every={} corner_distance={}",
                g.gather_rays,
                g.cache_every,
                g.corner_distance
                    .map_or_else(|| "default".to_owned(), |d| format!("{d:e}"))
            )
        } else {
            String::new()
        };
        format!(
            "progressive {PROGRESSIVE_VERSION} size={}x{} spp={} photons={} k={} max_distance={} reject_behind={} mode={} seed={} alpha={:e}",
            s.width,
            s.height,
            s.samples_per_pixel,
            s.photons,
            s.k,
            max_distance,
            s.reject_behind,
            s.mode,
            s.seed,
            self.alpha
        ) + &gather
            + &s.emission
                .identity()
                .map_or_else(String::new, |e| format!(" emission={e}"))
    }
}
