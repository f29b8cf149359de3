//! Render modes: what radiance a camera ray carries. `PhotonMap` reads the photon maps at
//! the first diffuse hit, `ShadowRays` adds direct light by shadow rays, `PathTrace` is the
//! unbiased reference, `FinalGather` reads the maps through one gathered bounce. Each mode is
//! a choice of [`crate::source`] for the render core.

use std::fmt;

/// How a camera ray's radiance is computed.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Mode {
    /// Follow specular bounces from the eye, then at the first diffuse hit return emission +
    /// `albedo/π · E` from that surface's photon map (the main results of Ball & Stejko's report).
    /// The default. Called `Visualize` before (the deprecated [`Mode::Visualize`] is it; the
    /// render example still reads the name `visualize`).
    PhotonMap,
    /// Direct light by shadow rays to every light, plus the photon map without direct photons
    /// for the rest (Image 1 of Ball & Stejko's report).
    ShadowRays,
    /// An unbiased path tracer with next-event estimation, combined with its diffuse bounces by
    /// multiple importance sampling (power heuristic) where every light supports it
    /// ([`pm_trace::Light::supports_mis`]), and Russian roulette (the reference).
    PathTrace,
    /// Final gathering (Jensen 1996, with Christensen's precomputed irradiance): specular
    /// bounces from the eye to the first diffuse hit x; there direct light by shadow rays
    /// combined with the gather rays that hit lights by multiple importance sampling (power
    /// heuristic, where every light supports it), caustics from the photons of kind caustic
    /// in x's map, and the rest by
    /// [`crate::FinalGatherOptions::gather_rays`] cosine-weighted rays whose diffuse hits read the
    /// [`crate::RadianceCache`] in their own map. Clean images at a fraction of a path tracer's time;
    /// the cache's blur is hidden behind the gathered hemisphere.
    FinalGather,
}

impl Mode {
    /// All modes, in command-line order.
    pub const ALL: [Mode; 4] = [
        Mode::PhotonMap,
        Mode::ShadowRays,
        Mode::PathTrace,
        Mode::FinalGather,
    ];

    /// The old name of [`Mode::PhotonMap`].
    #[deprecated(since = "0.1.0", note = "renamed `Mode::PhotonMap`")]
    #[allow(non_upper_case_globals)]
    pub const Visualize: Mode = Mode::PhotonMap;

    /// The command-line name: `photon-map`, `shadow-rays`, `path-trace` or `final-gather`.
    pub const fn name(self) -> &'static str {
        match self {
            Mode::PhotonMap => "photon-map",
            Mode::ShadowRays => "shadow-rays",
            Mode::PathTrace => "path-trace",
            Mode::FinalGather => "final-gather",
        }
    }

    /// True when the mode reads photon maps (every mode but [`Mode::PathTrace`]).
    pub const fn uses_photons(self) -> bool {
        !matches!(self, Mode::PathTrace)
    }
}

impl fmt::Display for Mode {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.name())
    }
}
