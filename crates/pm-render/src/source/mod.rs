//! Radiance sources: how each render mode reads radiance at a camera path's first diffuse
//! vertex ([`crate::core::RadianceSource`]). One per source of light information: the photon
//! maps by a k-nearest estimate ([`PhotonMapSource`]), a path-traced bounce ([`PathTraced`]), a
//! final gather into an irradiance cache ([`FinalGatherSource`]); a progressive pass's
//! fixed-volume reads live with the progressive renderer.

pub(crate) mod direct;
pub(crate) mod final_gather;
pub(crate) mod path_traced;
pub(crate) mod photon_map;
pub(crate) mod photon_read;

pub use direct::direct_irradiance;
pub use final_gather::{CacheReads, FinalGatherOptions, FinalGatherSource, GatherReads};
pub use path_traced::PathTraced;
pub use photon_map::{PhotonMapSource, map_irradiance};
pub use photon_read::DirectLight;
