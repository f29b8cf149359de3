//! photon-maps: photon-mapped global illumination that does not leak light through thin walls
//! or around creases, and does not darken or brighten edges.
//!
//! This facade re-exports the four crates of the workspace:
//!
//! - [`geom`]: polygons, clipping to a cube and a ball, exact areas, the half-edge mesh, and
//!   the arrangement that cuts faces where they meet;
//! - [`kdtree`]: 20-byte compact photons and a kd-tree with k-nearest queries in a sphere or a
//!   cube;
//! - [`trace`]: scenes, lights, the watertight BVH, deterministic photon tracing, photon-map
//!   partitions (one map, crease angle, contact-aware), built-in scenes and glTF loading;
//! - [`render`]: the radiance estimators (disc, geometry cube, geometry ball), render modes, the
//!   tiled renderer, images and metrics.
//!
//! Conventions everywhere: metres, watts, `f32`, right-handed with +y up, linear Rec. 709 RGB.
//! A light's power is its total emitted flux in watts per channel; with N photons emitted each
//! starts with `Φ / N`.
//!
//! ```
//! use photon_maps::prelude::*;
//!
//! // The two rooms whose floor runs under the dividing wall: crease maps leak along the floor,
//! // contact maps do not.
//! // Partitioning takes the scene and gives it back split where faces meet, with its maps.
//! let partitioned = Contact::default().partition(scenes::build("touching-rooms")?)?;
//! let settings = RenderSettings { width: 48, height: 24, photons: 10_000, ..Default::default() };
//! let out = Renderer::new(EstimatorKind::GeometryCube, settings).render(&partitioned, &())?;
//! assert!(out.stats.map_count > 10, "the floor is split at the wall");
//! println!("mean radiance {:?}, {} maps", out.image.mean(), out.stats.map_count);
//! # Ok::<(), Box<dyn std::error::Error>>(())
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
//! - Ball and Stejko's project report, which combines the three and whose scenes (the Cornell
//!   box, the lit and unlit rooms, the coloured rooms, the accordion), four variants (basic,
//!   multiple maps, geometry area, both) and timing table this workspace reproduces; "the
//!   report" in these docs is that report. The reproduction is in the repository's
//!   `docs/results.md`.

pub use pm_geom as geom;
pub use pm_kdtree as kdtree;
pub use pm_render as render;
pub use pm_trace as trace;

/// The names a renderer author reaches for first: scenes and lights, map partitions
/// ([`trace::CreaseAngle`], [`trace::Contact`], [`trace::MapAssignment`]), photon tracing and
/// maps ([`trace::trace_photons`], [`trace::PhotonMaps`]), the estimators
/// ([`render::GeometryCube`], …) with the building blocks of new ones
/// ([`render::find_nearest`], [`render::gather_found`]), and the one-shot and progressive
/// renderers. The same set as [`render::prelude`].
pub mod prelude {
    pub use pm_render::prelude::*;
}
