//! Photon tracing from the lights into per-map photon lists, and building the photon maps
//! (kd-tree plus area geometry) from them.

mod maps;
mod path;
mod scatter;
mod trace;

pub use maps::{MapGeometry, PhotonMap, PhotonMaps};
pub use scatter::{fresnel_dielectric, glass_direction, mirror_direction, reflect, refract};
pub use trace::{
    MAX_PHOTON_PATHS, MAX_STORED_PHOTONS, NEAR_LIGHT_DISTANCE, TraceOptions, TraceStats, TracedPhotons,
    trace_photons,
};
