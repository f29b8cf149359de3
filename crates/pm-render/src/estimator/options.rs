//! Parameters shared by every estimator: k, the maximum search distance, back-face rejection
//! and which photon kinds to gather.

use crate::error::RenderError;
use pm_geom::Aabb;
use pm_kdtree::KindMask;

/// Parameters of an irradiance estimate.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct EstimatorOptions {
    /// Number of photons to gather (≥ 1; default 100).
    pub k: usize,
    /// Largest search distance (metres; default 10 % of the scene's bounding-box diagonal).
    /// When fewer than `k` photons lie within it, the estimate uses this extent.
    pub max_distance: f32,
    /// Drop photons whose travel direction `ω` satisfies `ω·n ≥ 0` (arriving from behind the
    /// viewed side). Off by default, as in Ball & Stejko's basic variant. The geometry estimators
    /// weight by `max(0, −n·ω)` and so ignore such photons either way.
    pub reject_behind: bool,
    /// Photon kinds gathered ([`KindMask::NOT_DIRECT`] when direct light comes from shadow rays).
    pub kinds: KindMask,
    /// Leave out a k-nearest search's boundary photon (the k-th, whose distance is the
    /// extent), counting only the photons strictly inside the volume. On a locally uniform
    /// photon density that makes the estimate unbiased: the volume's expected photon count
    /// μ is Gamma(k)-distributed and E[(k − 1)/μ] = 1, where counting all k is k/(k − 1) too
    /// bright (1 % at k = 100). Off by default (Jensen's estimate, as Ball & Stejko have it);
    /// the radiance cache turns it on. No effect where fewer than k photons were found
    /// (the extent is then the maximum distance, fixed beforehand).
    pub leave_out_boundary: bool,
}

impl EstimatorOptions {
    /// The default number of photons gathered.
    pub const DEFAULT_K: usize = 100;

    /// Defaults for a scene with these bounds: k = 100, maximum distance 10 % of the diagonal.
    pub fn for_scene(bounds: &Aabb) -> Self {
        Self::with_max_distance(0.1 * bounds.diagonal())
    }

    /// Defaults with an explicit maximum distance.
    pub fn with_max_distance(max_distance: f32) -> Self {
        EstimatorOptions {
            k: Self::DEFAULT_K,
            max_distance,
            reject_behind: false,
            kinds: KindMask::ALL,
            leave_out_boundary: false,
        }
    }

    /// Checks that k ≥ 1 and the maximum distance is positive and finite.
    pub fn validate(&self) -> Result<(), RenderError> {
        if self.k == 0 {
            return Err(RenderError::ZeroK);
        }
        if !(self.max_distance.is_finite() && self.max_distance > 0.0) {
            return Err(RenderError::BadMaxDistance(self.max_distance));
        }
        Ok(())
    }
}
