//! Where photons are emitted: uniformly by the lights' own distributions (the default), or
//! driven by the camera ([`PhotonEmission::CameraDriven`]): a pilot of photon paths learns
//! which emission bins light what the camera sees ([`SeenSurfaces`]), and photons of the other
//! bins are mostly dropped at the light, the survivors carrying the dropped ones' power
//! ([`pm_trace::EmissionGuide`]). Unbiased in every mode that reads photons; worth it where the
//! camera sees a small part of what the lights light.
//!
//! ```
//! use pm_render::emission::PhotonEmission;
//! use pm_render::{Mode, RenderSettings};
//! use pm_trace::GuideOptions;
//!
//! let settings = RenderSettings {
//!     mode: Mode::FinalGather,
//!     emission: PhotonEmission::CameraDriven(GuideOptions::default()),
//!     ..RenderSettings::default()
//! };
//! assert!(settings.validate().is_ok());
//! ```

pub mod seen;

pub use seen::{ReadAt, SeenSurfaces};

use crate::error::RenderError;
use crate::mode::Mode;
use crate::settings::RenderSettings;
use pm_trace::{
    Camera, EmissionGuide, GuideOptions, MapAssignment, Scene, TraceOptions, TracedPhotons, trace_guided_photon_paths,
    trace_photons,
};
use std::time::{Duration, Instant};

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
            PhotonEmission::CameraDriven(g) => Some(format!("camera/pilot={}/floor={}", g.pilot_photons, g.floor)),
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

/// Traces a run's photons as its [`PhotonEmission`] says: the guide is learnt once (from the
/// scene's camera) and used for every pass.
#[derive(Clone, Debug)]
pub struct Emitter {
    guide: Option<EmissionGuide>,
    report: Option<EmissionReport>,
}

impl Emitter {
    /// Uniform emission: no guide.
    pub fn uniform() -> Self {
        Emitter {
            guide: None,
            report: None,
        }
    }

    /// The emitter of `settings.emission` for `scene` seen by `cameras` (learning the guide,
    /// for camera-driven emission, from a camera pass of `settings`' image size and a pilot
    /// of `settings.seed`).
    pub fn new(
        scene: &Scene,
        assignment: &MapAssignment,
        settings: &RenderSettings,
        cameras: &[Camera],
    ) -> Result<Self, RenderError> {
        let PhotonEmission::CameraDriven(options) = settings.emission else {
            return Ok(Self::uniform());
        };
        let start = Instant::now();
        let read_at = match settings.mode {
            Mode::FinalGather => ReadAt::GatherHits,
            _ => ReadAt::CameraHits,
        };
        let seen = SeenSurfaces::of_cameras(
            scene,
            assignment,
            cameras,
            (settings.width, settings.height),
            read_at,
            settings.seed,
        );
        let trace = TraceOptions {
            seed: settings.seed,
            ..TraceOptions::default()
        };
        let guide = EmissionGuide::learn(scene, assignment, &trace, &options, &|map, p| seen.sees(map, p))?;
        let report = EmissionReport {
            learn: start.elapsed(),
            seen_points: seen.points(),
            pilot_photons: options.pilot_photons,
            seen_fraction: guide.seen_fraction(),
            keep_rate: guide.keep_rate(),
            bins: guide.bin_count(),
        };
        Ok(Emitter {
            guide: Some(guide),
            report: Some(report),
        })
    }

    /// What the guide learnt (`None` for uniform emission).
    pub fn report(&self) -> Option<&EmissionReport> {
        self.report.as_ref()
    }

    /// The guide (`None` for uniform emission).
    pub fn guide(&self) -> Option<&EmissionGuide> {
        self.guide.as_ref()
    }

    /// Pass `pass` of `settings`' photons: `settings.photons` paths emitted uniformly, or, with
    /// a guide, as many emitted as trace on about `settings.photons`
    /// ([`EmissionGuide::photons_to_emit`]).
    pub fn trace(
        &self,
        scene: &Scene,
        assignment: &MapAssignment,
        settings: &RenderSettings,
        pass: u64,
    ) -> Result<TracedPhotons, RenderError> {
        let options = TraceOptions {
            photons: settings.photons,
            seed: settings.seed,
            pass,
            ..TraceOptions::default()
        };
        Ok(match &self.guide {
            None => trace_photons(scene, assignment, &options)?,
            Some(guide) => {
                let photons = guide.photons_to_emit(settings.photons)?;
                let options = TraceOptions { photons, ..options };
                trace_guided_photon_paths(scene, assignment, &options, 0..photons, guide)?
            }
        })
    }
}
