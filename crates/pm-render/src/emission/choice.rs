//! The choice of emission a run makes ([`PhotonEmission`]) and what camera-driven emission
//! reports ([`EmissionReport`]).

use pm_trace::GuideOptions;
use std::time::Duration;

/// How photons leave the lights.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub enum PhotonEmission {
    /// By each light's own emission distribution, lights in proportion to power.
    #[default]
    Uniform,
    /// Concentrated on what the camera sees, learnt by a pilot of photon paths.
    CameraDriven(GuideOptions),
}

impl PhotonEmission {
    /// The command-line name: `uniform` or `camera`.
    pub const fn name(&self) -> &'static str {
        match self {
            PhotonEmission::Uniform => "uniform",
            PhotonEmission::CameraDriven(_) => "camera",
        }
    }

    /// A text naming the emission and its options, for cache and shard identities (`None`
    /// for uniform emission, which older files did not name).
    pub fn identity(&self) -> Option<String> {
        match self {
            PhotonEmission::Uniform => None,
            PhotonEmission::CameraDriven(g) => {
                Some(format!("camera/pilot={}/floor={}", g.pilot_photons, g.floor))
            }
        }
    }
}

/// What camera-driven emission learnt, and what it cost.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct EmissionReport {
    /// Camera pass and pilot.
    pub learn: Duration,
    /// Points where the camera's rays (and a final gather's) read the maps.
    pub seen_points: usize,
    /// Pilot paths traced.
    pub pilot_photons: u32,
    /// Share of pilot paths that stored a photon the camera sees.
    pub seen_fraction: f64,
    /// Expected share of emitted photons traced on.
    pub keep_rate: f64,
    /// Emission bins the pilot reached.
    pub bins: usize,
}
