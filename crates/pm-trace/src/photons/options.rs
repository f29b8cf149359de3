//! What to trace, and the bounds on one trace: paths, stored photons, and the distance that
//! counts a first hit as next to its light.

/// How close to its light the surface of a photon's first hit must pass (1 mm: the distance
/// from where the photon left the light to the plane of the surface at its hit) to count in
/// [`TraceStats::near_light_fraction`](super::TraceStats::near_light_fraction).
pub const NEAR_LIGHT_DISTANCE: f32 = 1e-3;

/// The most photon paths one call to [`trace_photons`](super::trace_photons) traces: 2²⁵ (33,554,432). More are
/// refused with [`TraceError::TooManyPhotons`](crate::error::TraceError::TooManyPhotons) before anything is allocated.
pub const MAX_PHOTON_PATHS: u32 = 1 << 25;

/// The most photons one call to [`trace_photons`](super::trace_photons) stores over all maps: 2²⁶ (67,108,864, 40
/// bytes each while tracing, 2.5 GiB). Paths store one photon per diffuse bounce (up to
/// `max_bounces`), so the count is checked as the waves are merged and the run stops with
/// [`TraceError::TooManyPhotonsStored`](crate::error::TraceError::TooManyPhotonsStored) once past it.
pub const MAX_STORED_PHOTONS: u64 = 1 << 26;

/// What to trace.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct TraceOptions {
    /// Number of emitted photon paths (each starts with `Φ_total / photons` on average).
    pub photons: u32,
    /// Seed of the random streams (path `i` of pass `p` draws from
    /// [`Rng::for_pass`](crate::rng::Rng::for_pass)`(seed, p, i)`).
    pub seed: u64,
    /// Pass of a progressive render: each pass traces a fresh, independent set of paths.
    /// Pass 0 (the default) is a single render's trace: `Rng::for_pass(seed, 0, i)` is
    /// `Rng::new(seed, i)`.
    pub pass: u64,
    /// Longest path (surface interactions); Russian roulette ends paths long before in
    /// practice. The cut-off loses the power of longer paths.
    pub max_bounces: u32,
}

impl Default for TraceOptions {
    /// 100,000 photons (Ball & Stejko's count), seed 0, pass 0, at most 64 bounces.
    fn default() -> Self {
        TraceOptions {
            photons: 100_000,
            seed: 0,
            pass: 0,
            max_bounces: 64,
        }
    }
}
