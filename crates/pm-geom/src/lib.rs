//! Geometry for photon mapping: convex polygons, their clipping to a cube and a ball, exact
//! areas, polygon sets with an overlap index, and a half-edge mesh with crease angles.
//!
//! The geometry-based radiance estimate spreads each photon's power over the surface area
//! enclosed by a gather volume. This crate answers "how much of this polygon lies inside the
//! volume" for a cube ([`Aabb`], Sutherland–Hodgman clipping) and a ball ([`Ball`], exact
//! polygon ∩ disc area) through one trait, [`GatherVolume`]; finds the candidate polygons
//! fast ([`PolygonSet`], with a bounding-volume hierarchy, its coplanar polygons merged by
//! [`CoplanarMerger`]); tells which faces may share a photon map ([`HalfEdgeMesh`]: twins,
//! non-manifold edges, crease angles); and cuts faces where they pierce, stand on, overlap or
//! nearly touch each other ([`split_polygons_at_intersections`], a mesh arrangement), so that no
//! map spans both sides of a wall built as a solid box through a floor slab.
//!
//! # Conventions
//!
//! - `f32` and [`glam`] types throughout; units are metres, angles radians.
//! - Right-handed coordinates, +y up. Polygons are `&[Vec3]` with vertices in order; a
//!   polygon's normal points to where its vertices appear counter-clockwise.
//! - Polygons handed to the clipping and area functions are convex and planar.
//! - Hot paths (clipping, areas, overlap queries) allocate nothing once the caller-owned
//!   [`ClipScratch`] has grown; they never panic on geometric input and return 0 rather
//!   than NaN. Mesh construction returns a typed [`MeshError`].
//!
//! # Example
//!
//! ```
//! use pm_geom::{Aabb, Ball, ClipScratch, GatherVolume, clip_polygon_to_aabb, polygon_area};
//! use pm_geom::glam::{Vec3, vec3};
//!
//! // A 2 m × 2 m floor quad, facing up, and a cube of half-size 0.5 m centred on a corner.
//! let quad = [vec3(0., 0., 0.), vec3(0., 0., 2.), vec3(2., 0., 2.), vec3(2., 0., 0.)];
//! let cube = Aabb::cube(vec3(0., 0., 0.), 0.5);
//! let mut scratch = ClipScratch::new();
//!
//! let clipped = clip_polygon_to_aabb(&quad, &cube, &mut scratch);
//! println!("clipped to {} vertices, area {} m²", clipped.len(), polygon_area(clipped));
//! assert!((polygon_area(clipped) - 0.25).abs() < 1e-6);
//!
//! // The same through the gather-volume trait, for the cube and for a ball.
//! let area = cube.polygon_area_inside(&quad, Vec3::Y, &mut scratch);
//! assert!((area - 0.25).abs() < 1e-6);
//! let ball = Ball::new(vec3(1., 0.3, 1.), 0.5); // cuts the floor in a disc of radius 0.4
//! let disc = ball.polygon_area_inside(&quad, Vec3::Y, &mut scratch);
//! assert!((disc - std::f32::consts::PI * 0.16).abs() < 1e-5);
//! ```
//!
//! # References
//!
//! - H. W. Jensen, *Global Illumination using Photon Maps*, Rendering Techniques '96
//!   (Eurographics Workshop on Rendering), 1996: photon maps and the disc estimate
//!   `E = Σ Φ / (π r²)` over the k nearest photons.
//! - R. D. Larsen and N. J. Christensen, *Optimizing Photon Mapping Using Multiple Photon Maps
//!   for Irradiance Estimates*, WSCG 2003: one photon map per group of faces joined across
//!   edges with a small crease angle, so that no estimate gathers through a wall.
//! - H. Hey and W. Purgathofer, *Advanced Radiance Estimation for Photon Map Global
//!   Illumination*, Computer Graphics Forum 21(3), 2002: gather in a cube and divide by the
//!   surface area actually inside it, so that edges are not darkened.
//! - Q. Zhou, E. Grinspun, D. Zorin and A. Jacobson, *Mesh Arrangements for Solid Geometry*,
//!   ACM Transactions on Graphics 35(4), 2016, and libigl's `remesh_self_intersections`: every
//!   intersection of a mesh's faces made an edge of the faces on all its sides; here with one
//!   scene-relative tolerance instead of exact constructions.
//! - Ball and Stejko's project report, which combines the three and whose scenes (the Cornell
//!   box, the lit and unlit rooms, the coloured rooms, the accordion), four variants (basic,
//!   multiple maps, geometry area, both) and timing table this workspace reproduces; "the
//!   report" in these docs is that report. The reproduction is in the repository's
//!   `docs/results.md`.

pub mod aabb;
pub mod arrangement;
pub mod ball;
mod bounds_bvh;
pub mod clip;
pub mod error;
mod fast_hash;
pub mod merge;
pub mod mesh;
pub mod plane;
pub mod polygon;
pub mod polygon_set;
pub mod volume;

pub use aabb::Aabb;
pub use arrangement::{
    Arrangement, ArrangementError, ArrangementOptions, ArrangementSeconds, BarrierSet, IntersectionCounts,
    StepTimer, split_polygons_at_intersections,
};
pub use ball::{Ball, polygon_area_in_ball};
pub use clip::{
    ClipScratch, clip_convex_polygon_by_distance, clip_polygon_to_aabb, split_convex_polygon_by_distance,
    split_convex_polygon_by_plane,
};
pub use error::MeshError;
pub use glam;
pub use merge::{CoplanarMerger, MergeOptions, merge_coplanar_polygons};
pub use mesh::{FaceId, HalfEdgeId, HalfEdgeMesh, MeshOptions, VertexId};
pub use plane::Plane;
pub use polygon::{polygon_area, polygon_normal, polygon_vector_area};
pub use polygon_set::PolygonSet;
pub use volume::GatherVolume;
