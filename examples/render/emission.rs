//! `--emission camera`: photons concentrated on what the camera sees
//! (`pm_render::emission`), with the guide's pilot size and floor.

use super::report::json_number;
use photon_maps::render::emission::{EmissionReport, PhotonEmission};
use photon_maps::trace::GuideOptions;

/// How photons leave the lights.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, clap::ValueEnum)]
pub enum EmissionChoice {
    /// By each light's own distribution (the default).
    #[default]
    Uniform,
    /// Concentrated on what the camera sees: a pilot of photon paths learns which directions
    /// of which lights reach it, and the rest are mostly dropped at the light (unbiased: the
    /// survivors carry their power).
    Camera,
}

/// The options of camera-driven emission.
#[derive(clap::Args, Debug)]
pub struct EmissionArgs {
    /// Modes that read photons: how photons leave the lights. `camera` concentrates them on
    /// what the camera sees (worth it when it sees a small part of what the lights light).
    #[arg(long, value_enum, default_value_t = EmissionChoice::Uniform)]
    pub emission: EmissionChoice,
    /// With --emission camera: pilot photon paths that learn the guide [default: 65536].
    #[arg(long)]
    pub guide_pilot: Option<u32>,
    /// With --emission camera: the least share of photons kept in directions the camera
    /// never sees, 0 < f ≤ 1 [default: 0.125].
    #[arg(long)]
    pub guide_floor: Option<f32>,
}

impl EmissionArgs {
    /// The typed emission, checked.
    pub fn emission(&self) -> Result<PhotonEmission, String> {
        match self.emission {
            EmissionChoice::Uniform => Ok(PhotonEmission::Uniform),
            EmissionChoice::Camera => {
                let defaults = GuideOptions::default();
                let guide = GuideOptions {
                    pilot_photons: self.guide_pilot.unwrap_or(defaults.pilot_photons),
                    floor: self.guide_floor.unwrap_or(defaults.floor),
                };
                guide.validate().map_err(|e| format!("--emission camera: {e}"))?;
                Ok(PhotonEmission::CameraDriven(guide))
            }
        }
    }
}

/// The summary's words on camera-driven emission (empty for uniform emission).
pub fn summary(report: Option<&EmissionReport>, emitted: u64, traced: u64) -> String {
    match report {
        None => String::new(),
        Some(e) => format!(
            ", camera-driven: {traced} of {emitted} paths traced on (keep rate {:.3}; {:.1} % of {} pilot paths seen from {} camera points; learnt in {:.3} s)",
            e.keep_rate,
            100.0 * e.seen_fraction,
            e.pilot_photons,
            e.seen_points,
            e.learn.as_secs_f64()
        ),
    }
}

/// The JSON fields of camera-driven emission, each followed by ", " (the emission alone
/// for uniform emission).
pub fn json(report: Option<&EmissionReport>, traced: u64) -> String {
    match report {
        None => format!("\"emission\": \"uniform\", \"photons_traced\": {traced}, "),
        Some(e) => format!(
            "\"emission\": \"camera\", \"photons_traced\": {traced}, \"guide\": {{\"pilot_photons\": {}, \"seen_points\": {}, \"seen_fraction\": {}, \"keep_rate\": {}, \"bins\": {}, \"seconds\": {}}}, ",
            e.pilot_photons,
            e.seen_points,
            json_number(e.seen_fraction),
            json_number(e.keep_rate),
            e.bins,
            json_number(e.learn.as_secs_f64())
        ),
    }
}
