//! Geometry for photon mapping: convex polygons, their clipping to a cube and a ball, exact
//! areas, polygon sets with an overlap index, and a half-edge mesh with crease angles.
//!
//! (Crate docs to be completed by the pm-geom issue: conventions, example.)

pub mod aabb;
pub mod ball;
pub mod clip;
pub mod error;
pub mod mesh;
pub mod plane;
pub mod polygon;
pub mod polygon_set;
pub mod volume;

pub use aabb::Aabb;
pub use ball::Ball;
pub use clip::{ClipScratch, clip_polygon_to_aabb};
pub use error::MeshError;
pub use glam;
pub use mesh::{FaceId, HalfEdgeId, HalfEdgeMesh, MeshOptions, VertexId};
pub use plane::Plane;
pub use polygon::{polygon_area, polygon_normal, polygon_vector_area};
pub use polygon_set::PolygonSet;
pub use volume::GatherVolume;
