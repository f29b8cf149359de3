//! Photon tracing from the lights into per-map photon lists, and building the photon maps
//! (kd-tree plus area geometry) from them.

mod guide;
mod light_picker;
mod map_geometry;
mod maps;
mod occupancy;
mod options;
mod path;
mod pilot;
mod trace;
mod traced;

pub use crate::bsdf::scatter::{fresnel_dielectric, glass_direction, mirror_direction, reflect, refract};
pub use guide::{EmissionGuide, GuideOptions};
pub use map_geometry::MapGeometry;
pub use maps::{PhotonMap, PhotonMaps};
pub use occupancy::MapOccupancy;
pub use options::{MAX_PHOTON_PATHS, MAX_STORED_PHOTONS, NEAR_LIGHT_DISTANCE, TraceOptions};
pub use trace::{trace_guided_photon_paths, trace_photon_paths, trace_photons};
pub use traced::{TraceStats, TracedPhotons};
