//! The [`Emitter`]: a run's photons traced as its [`PhotonEmission`] says, with the guide
//! learnt once for every pass.

use super::choice::{EmissionReport, PhotonEmission};
use super::seen::{ReadAt, SeenSurfaces};
use crate::error::RenderError;
use crate::mode::Mode;
use crate::settings::RenderSettings;
use pm_trace::{
    Camera, EmissionGuide, MapAssignment, Scene, TraceOptions, TracedPhotons, trace_guided_photon_paths,
    trace_photons,
};
use std::time::Instant;

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
