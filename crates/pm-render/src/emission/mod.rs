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

pub mod choice;
pub mod emitter;
pub mod seen;

pub use choice::{EmissionReport, PhotonEmission};
pub use emitter::Emitter;
pub use seen::{ReadAt, SeenSurfaces};
