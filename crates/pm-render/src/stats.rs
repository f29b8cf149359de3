//! Figures of one render: photon counts and the time of each phase.

use std::time::Duration;

/// What a render did and how long each phase took.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct RenderStats {
    /// Photon paths emitted.
    pub photons_emitted: u64,
    /// Photon paths traced on from their lights: `photons_emitted` less those camera-driven
    /// emission dropped there.
    pub photons_traced: u64,
    /// What camera-driven emission learnt and what learning cost (`None` for uniform
    /// emission or a mode that traces no photons).
    pub emission: Option<crate::emission::choice::EmissionReport>,
    /// Photons stored over all maps.
    pub photons_stored: u64,
    /// Photon power channels stored as zero because they were more than 2⁴⁰ (about 10¹²)
    /// times smaller than their map's brightest channel ([`pm_trace::PhotonMaps::channels_below_range`]);
    /// zero in any ordinary scene.
    pub photon_channels_below_range: u64,
    /// The share of the emitted power whose first hit lay within 1 mm of its light
    /// ([`pm_trace::TraceStats::near_light_fraction`]): near 1 when a light faces into the
    /// wall or ceiling it sits on (an area light emits towards `edge_u × edge_v`), which
    /// otherwise shows only as a dark image; 0 when the mode traces no photons.
    pub near_light_fraction: f64,
    /// Number of photon maps.
    pub map_count: u32,
    /// How the photons fill the maps, against the estimate's k: maps with none or fewer than
    /// k, and the surface they cover (all zero when the mode traces no photons).
    pub occupancy: pm_trace::MapOccupancy,
    /// Worker threads used.
    pub threads: usize,
    /// Photon tracing.
    pub trace: Duration,
    /// Building the maps (kd-trees and polygon sets).
    pub build: Duration,
    /// Rendering the image.
    pub render: Duration,
    /// Precomputing the final gather's irradiance cache (zero in the other modes).
    pub precompute: Duration,
    /// Points in the final gather's irradiance cache.
    pub cache_points: u64,
    /// Bytes held by the final gather's irradiance cache.
    pub cache_bytes: u64,
    /// Gather rays cast by the final gather (first rays of each gather, not counting the
    /// specular bounces they follow).
    pub gather_rays: u64,
    /// What an automatic photon count did ([`crate::Renderer::build_photon_cache_auto`]),
    /// `None` for a fixed count.
    pub auto_photons: Option<crate::auto_photons::settings::AutoPhotonsReport>,
}

impl RenderStats {
    /// Sum of the phases (camera-driven emission's learning included).
    pub fn total(&self) -> Duration {
        self.emission.map_or(Duration::ZERO, |e| e.learn)
            + self.trace
            + self.build
            + self.precompute
            + self.render
    }

    /// Gather rays per second of the render phase (zero when none were cast).
    pub fn gather_rays_per_second(&self) -> f64 {
        let seconds = self.render.as_secs_f64();
        if self.gather_rays == 0 || seconds <= 0.0 {
            0.0
        } else {
            self.gather_rays as f64 / seconds
        }
    }
}
