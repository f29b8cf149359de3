//! photon-maps: photon-mapped global illumination that does not leak light through thin walls
//! or around creases, and does not darken or brighten edges.
//!
//! This facade re-exports the four crates of the workspace:
//! [`geom`] (polygons, clipping, half-edge mesh), [`kdtree`] (compact photons, kd-tree),
//! [`trace`] (scenes, lights, photon tracing, map partitions) and [`render`] (estimators,
//! renderer, images).

pub use pm_geom as geom;
pub use pm_kdtree as kdtree;
pub use pm_render as render;
pub use pm_trace as trace;

/// The types most programs need.
pub mod prelude {
    pub use glam::{Vec3, vec3};
    pub use pm_geom::{Aabb, Ball, HalfEdgeMesh};
    pub use pm_kdtree::{Photon, PhotonKind, PhotonTree};
}
