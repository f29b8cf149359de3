//! Compact 20-byte photons and an implicit kd-tree with k-nearest queries in a sphere
//! (Euclidean) or a cube (Chebyshev, L∞), for photon-mapping renderers.
//!
//! - [`CompactPhoton`] packs a [`Photon`] (position, RGB power, travel direction, kind) into
//!   20 bytes: power within 0.7 % per channel and unbiased (stochastic rounding), relative to
//!   a [`PowerScale`] that the tree keeps (its brightest channel, so any absolute power
//!   works), direction within 0.05°.
//! - [`PhotonTree`] stores photons in tree order with no per-node pointers (20 bytes per
//!   photon plus about 0.2 bytes of split nodes), built in parallel by median selection.
//! - [`PhotonTree::nearest_k`] finds the k nearest photons within a maximum distance under a
//!   [`Metric`] ([`Euclidean`] or [`Chebyshev`], or your own), filtered by [`KindMask`],
//!   into a reusable [`Neighbours`] buffer that also reports the search extent.
//! - [`PhotonTree::for_each_within`] visits every photon within a radius.
//!
//! Limits: photon coordinates within ±[`MAX_COORDINATE`] (10¹⁸ m), so squared distances
//! stay finite; [`PhotonTree::build`] refuses others with [`BuildError::PositionOutOfRange`].
//!
//! # Conventions
//!
//! f32 throughout; positions in metres (right-handed, +y up, as in the rest of the
//! workspace); power in watts per linear-RGB channel; `direction` is the unit direction of
//! *travel* (pointing into the surface the photon landed on). Distances returned by queries
//! are true distances under the query's metric, never squared. Queries allocate nothing once
//! their [`Neighbours`] buffer is warm and may run from many threads at once.
//!
//! # Example
//!
//! ```
//! use pm_kdtree::glam::Vec3;
//! use pm_kdtree::{Chebyshev, Euclidean, KindMask, Neighbours, Photon, PhotonKind, PhotonTree};
//!
//! // 1000 photons of 1 mW each on the floor y = 0, in a 1 m × 1 m grid-like pattern.
//! let photons: Vec<Photon> = (0..1000)
//!     .map(|i| Photon {
//!         position: Vec3::new((i % 32) as f32 / 32.0, 0.0, (i / 32) as f32 / 32.0),
//!         power: Vec3::splat(1e-3),
//!         direction: Vec3::NEG_Y,
//!         kind: if i % 2 == 0 { PhotonKind::Direct } else { PhotonKind::Indirect },
//!     })
//!     .collect();
//! let tree = PhotonTree::from_photons(&photons)?;
//! tree.validate().expect("a freshly built tree is valid");
//!
//! let mut near = Neighbours::new();
//! tree.nearest_k::<Euclidean>(Vec3::new(0.5, 0.0, 0.5), 50, 0.2, KindMask::ALL, &mut near);
//! assert_eq!(near.len(), 50);
//! assert!(!near.is_partial());
//! // Jensen's estimate: irradiance = total power / (π r²), r = the 50th distance.
//! // Powers are stored relative to the tree's scale: sum them, then multiply once.
//! let relative: Vec3 = near.as_slice().iter().map(|n| tree.get(n.index).relative_power()).sum();
//! let power = relative * tree.power_scale().watts();
//! assert_eq!(tree.power(near.as_slice()[0].index), Vec3::splat(1e-3), "the scale itself is exact");
//! let irradiance = power / (std::f32::consts::PI * near.extent().powi(2));
//! assert!((irradiance.x - 1.0).abs() < 0.25, "1000 mW on about 1 m² is about 1 W/m²");
//!
//! // A cube query that only wants indirect photons and runs out of photons: partial.
//! tree.nearest_k::<Chebyshev>(Vec3::new(5.0, 0.0, 5.0), 10, 0.1, KindMask::NOT_DIRECT, &mut near);
//! assert!(near.is_partial() && near.is_empty() && near.extent() == 0.1);
//! # Ok::<(), pm_kdtree::BuildError>(())
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

pub mod error;
pub mod metric;
pub mod photon;
mod power_code;
pub mod query;
pub mod tree;
pub mod tree_arrays;

pub use error::BuildError;
/// The glam version this crate's API uses (`Vec3`), so users need not pin it by hand.
pub use glam;
pub use metric::{Chebyshev, Euclidean, Metric};
pub use photon::{CompactPhoton, KindMask, Photon, PhotonKind, PowerScale};
pub use query::{Neighbour, Neighbours};
pub use tree::{InvariantError, LEAF_CAPACITY, MAX_COORDINATE, PhotonTree};
pub use tree_arrays::{OwnedTreeArrays, TreeArrays};
