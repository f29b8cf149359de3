//! An automatic photon count: photons traced in doubling batches until the irradiance the
//! renderer's estimator reads at a fixed set of probe points changes less than a threshold
//! between batches.
//!
//! **Exactness.** Batch `k` holds paths `0..start·2ᵏ` of one photon stream: batch `k + 1`
//! traces only the new paths `start·2ᵏ..start·2ᵏ⁺¹` ([`pm_trace::trace_photon_paths`], each
//! path its own random stream `(seed, path index)`) and halves the power of the photons held
//! (a path's power is `Φ / N`; with `N` doubled, a power of two, halving is exact in floating
//! point and a path's decisions do not depend on the scale of its power). So the maps at the
//! count the run stops at are, bit for bit, the maps of a plain run with that count and seed,
//! and so is every image rendered from them.
//!
//! **The estimate compared.** Probe points are photons of the first batch (about
//! [`AutoPhotons::probes`] of them, evenly over the stored order), each placed on its surface
//! as a cache point is, with the extent of the estimator's k-nearest search there in the first
//! batch. After each batch the irradiance in that *fixed* volume is estimated from the whole
//! map ([`crate::FixedVolumeEstimator::irradiance_within`], all photon kinds, as the final gather's
//! cache reads them) and compared with the previous batch's as a relative RMS change over
//! probes and channels, `sqrt(Σ (Eₖ − Eₖ₋₁)² / Σ Eₖ²)`. The volume is fixed because a
//! k-nearest estimate's relative noise is about `1/sqrt(k)` whatever the photon count (only
//! its radius, its blur, shrinks): its change between batches would not fall. In a fixed
//! volume the photons found double with each batch, so the change falls as `1/sqrt(N)`: the
//! rule stops when the lighting at the scale of the first batch's gather radius is resolved
//! to the threshold. With about k photons per volume at the start, the first change is about
//! `1/sqrt(2k)` (0.07 for k = 100) and each doubling divides it by about √2.
//!
//! **Cost.** Tracing costs what the final count costs (no path is traced twice); the maps are
//! built once per batch (about twice the final build over the doubling series) and the probes
//! are one k-nearest estimate each per batch, negligible.
//!
//! **Caveat.** The stopping count is data-dependent: renders made at "the count the rule
//! chose" are not an unbiased sample of renders at a fixed count (a batch that happens to
//! agree with the previous one stops early). Each render is still exactly the render at its
//! count; for an unbiased study fix `photons` to the count found.

mod render;
pub(crate) mod settings;
mod trace;

pub use settings::{AutoBatch, AutoPhotons, AutoPhotonsReport};
pub use trace::{relative_change, trace_auto};
