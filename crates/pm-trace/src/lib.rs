//! Scenes, lights, a watertight BVH, deterministic parallel photon tracing and the partition
//! of surfaces into photon maps.
//!
//! (Crate docs to be completed by the pm-trace issue.)

#[cfg(feature = "gltf")]
pub mod gltf;
