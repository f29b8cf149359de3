//! Radiance estimators: the irradiance at a surface point from the photons of one map
//! (Jensen's disc, and Hey & Purgathofer's geometry-based area in a cube or a ball). The
//! trait is generic-friendly; [`EstimatorKind`] picks one at run time.
//!
//! # Writing an estimator: the Epanechnikov kernel
//!
//! An estimator of your own uses the building blocks of the built-in ones: [`find_nearest`]
//! runs the k-nearest query (the options' k, maximum distance and photon kinds) and returns
//! its radius r; [`gather_found`] decodes the neighbours into [`GatheredPhoton`]s with their
//! power in watts (the map's power scale applied) and squared distance, dropping photons from
//! behind when the options ask ([`EstimatorOptions::accepts`]). A distance-weighted kernel is
//! then a sum. Epanechnikov's kernel on the disc of radius r, `K(d) = 2/(π r²) · (1 − d²/r²)`,
//! integrates to one, so on a uniformly lit plane it estimates the irradiance without bias
//! (the k-th photon, at d = r, weighs nothing; the k − 1 inside average `1 − d²/r² = 1/2`):
//!
//! ```
//! use pm_render::prelude::*;
//! use std::f32::consts::PI;
//!
//! /// Epanechnikov's kernel over the k nearest photons.
//! struct Epanechnikov;
//!
//! impl Estimator for Epanechnikov {
//!     fn irradiance(
//!         &self,
//!         at: SurfacePoint,
//!         map: MapView<'_>,
//!         options: &EstimatorOptions,
//!         scratch: &mut EstimatorScratch,
//!     ) -> Vec3 {
//!         let Some(r) = find_nearest::<Euclidean>(at, map, options, scratch) else {
//!             return Vec3::ZERO;
//!         };
//!         gather_found(at, map.tree, options, scratch);
//!         let r2 = r * r;
//!         let weighted: Vec3 = scratch
//!             .photons()
//!             .iter()
//!             .map(|p| p.power * (1.0 - p.distance_squared / r2).max(0.0))
//!             .sum();
//!         weighted * (2.0 / (PI * r2))
//!     }
//! }
//!
//! // A plane lit by 1 W/m²: 10,000 photons of 0.04 mW on a jittered grid over 2 m × 2 m.
//! let photons: Vec<Photon> = (0..10_000u32)
//!     .map(|i| {
//!         let jitter = |n: u32| (n.wrapping_mul(2_654_435_761) >> 8) as f32 / (1 << 24) as f32;
//!         let (x, z) = ((i % 100) as f32 + jitter(i), (i / 100) as f32 + jitter(i ^ 0x5bd1));
//!         Photon {
//!             position: vec3(x / 50.0 - 1.0, 0.0, z / 50.0 - 1.0),
//!             power: Vec3::splat(4.0e-4),
//!             direction: Vec3::NEG_Y,
//!             kind: PhotonKind::Direct,
//!         }
//!     })
//!     .collect();
//! let tree = PhotonTree::build(photons)?;
//! let polygons = PolygonSet::new(); // a kernel estimator needs no geometry
//! let map = MapView { tree: &tree, polygons: &polygons };
//! let options = EstimatorOptions::with_max_distance(0.5);
//! let at = SurfacePoint::front(vec3(0.1, 0.0, -0.2), Vec3::Y);
//! let e = Epanechnikov.irradiance(at, map, &options, &mut EstimatorScratch::new());
//! assert!((e.x - 1.0).abs() < 0.1, "{e}");
//! # Ok::<(), Box<dyn std::error::Error>>(())
//! ```
//!
//! The repository's `crates/pm-render/tests/outside_kernels.rs` checks this kernel from
//! outside the crate against the closed form on a traced, uniformly lit plane, and
//! `tests/outside_estimator.rs` builds Jensen's cone filter the same way.

mod disc;
mod fixed;
mod gather;
mod geometry;
mod kind;
mod options;

pub use disc::Disc;
pub use fixed::FixedVolumeEstimator;
pub use gather::{GatheredPhoton, gather_found, gather_within};
pub use geometry::{GeometryBall, GeometryCube, VolumeMetric, irradiance_in_volume};
pub use kind::EstimatorKind;
pub use options::EstimatorOptions;

use glam::Vec3;
use pm_geom::{ClipScratch, PolygonSet};
use pm_kdtree::{Neighbour, Neighbours, PhotonTree};
use std::any::Any;

/// A point on a surface seen by the camera: where to estimate, and the side it is seen from.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SurfacePoint {
    /// Position (metres).
    pub position: Vec3,
    /// Unit geometric normal on the viewed side.
    pub normal: Vec3,
    /// True when the viewed side is the side the surface's own (polygon) normal points to.
    /// When false — a closed surface seen from inside its outward normals, such as a sphere —
    /// the geometry estimators flip the map's polygon normals so that they face its photons.
    pub front_face: bool,
}

impl SurfacePoint {
    /// A point seen from the side its polygons' normals point to.
    pub const fn front(position: Vec3, normal: Vec3) -> Self {
        SurfacePoint {
            position,
            normal,
            front_face: true,
        }
    }
}

/// One photon map as the estimators see it: its photons and the area geometry of its surfaces.
#[derive(Clone, Copy, Debug)]
pub struct MapView<'a> {
    /// The map's photons.
    pub tree: &'a PhotonTree,
    /// The map's polygons (with their overlap index built), used by the geometry estimators.
    pub polygons: &'a PolygonSet,
}

/// Per-thread buffers of the estimators; reuse one per worker so queries allocate nothing once
/// warm.
///
/// Estimators written outside this crate use the same building blocks as the built-in ones:
/// [`find_nearest`] fills [`EstimatorScratch::neighbours`], [`gather_found`] decodes them into
/// [`EstimatorScratch::photons`], and [`EstimatorScratch::slot`] keeps buffers of the
/// estimator's own type alive from one query to the next.
#[derive(Default)]
pub struct EstimatorScratch {
    pub(crate) neighbours: Neighbours,
    pub(crate) clip: ClipScratch,
    pub(crate) photons: Vec<GatheredPhoton>,
    /// Candidate faces that overlap the volume: (area inside, unit normal).
    pub(crate) faces: Vec<(f32, Vec3)>,
    pub(crate) candidates: Vec<u32>,
    /// Gather rays cast by the final gather on this worker since the renderer last read it.
    pub(crate) gather_rays: u64,
    /// An outside estimator's own buffers (see [`EstimatorScratch::slot`]).
    slot: Option<Box<dyn Any + Send>>,
}

impl Clone for EstimatorScratch {
    /// A copy of the built-in buffers; the estimator's own slot starts empty again (it is
    /// scratch, and its type need not be `Clone`).
    fn clone(&self) -> Self {
        EstimatorScratch {
            neighbours: self.neighbours.clone(),
            clip: self.clip.clone(),
            photons: self.photons.clone(),
            faces: self.faces.clone(),
            candidates: self.candidates.clone(),
            gather_rays: 0,
            slot: None,
        }
    }
}

impl std::fmt::Debug for EstimatorScratch {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("EstimatorScratch")
            .field("neighbours", &self.neighbours.len())
            .field("photons", &self.photons.len())
            .field("faces", &self.faces.len())
            .field("slot", &self.slot.is_some())
            .finish()
    }
}

impl EstimatorScratch {
    /// Empty scratch; grows on first use.
    pub fn new() -> Self {
        Self::default()
    }

    /// The neighbours found by the last [`find_nearest`], in no particular order (their
    /// indices are into the map's [`PhotonTree`], their distances under the query's metric).
    pub fn neighbours(&self) -> &[Neighbour] {
        self.neighbours.as_slice()
    }

    /// The photons decoded by the last [`gather_found`].
    pub fn photons(&self) -> &[GatheredPhoton] {
        &self.photons
    }

    /// The estimator's own scratch of type `T`, made with `T::default()` on first use and
    /// kept (with its capacity) for later queries on the same worker. Asking for another type
    /// replaces it, so an estimator should keep all its buffers in one type.
    pub fn slot<T: Any + Send + Default>(&mut self) -> &mut T {
        if !self.slot.as_ref().is_some_and(|s| s.is::<T>()) {
            self.slot = Some(Box::new(T::default()));
        }
        // Just made sure the slot holds a `T`.
        self.slot
            .as_mut()
            .and_then(|s| s.downcast_mut::<T>())
            .expect("slot holds a T")
    }

    /// The neighbours, the decoded photons and the estimator's own slot at once, for
    /// estimators that read the first two while writing the third.
    pub fn split<T: Any + Send + Default>(&mut self) -> (&[Neighbour], &[GatheredPhoton], &mut T) {
        self.slot::<T>();
        let slot = self
            .slot
            .as_mut()
            .and_then(|s| s.downcast_mut::<T>())
            .expect("slot holds a T");
        (self.neighbours.as_slice(), &self.photons, slot)
    }
}

/// Estimates irradiance (W/m²) at a surface point from one photon map.
///
/// Outgoing radiance on a Lambertian surface of albedo ρ is `ρ/π · E`.
pub trait Estimator: Send + Sync {
    /// Irradiance at `at` from `map`, with `options`, using `scratch` for all buffers.
    fn irradiance(
        &self,
        at: SurfacePoint,
        map: MapView<'_>,
        options: &EstimatorOptions,
        scratch: &mut EstimatorScratch,
    ) -> Vec3;

    /// A name that tells this estimator, with its parameters, from every other: part of a
    /// progressive render's shard identity, so shards made with different estimators never
    /// merge. The default is the type's name; give an estimator with parameters (a kernel
    /// width) a name that includes them.
    fn identity(&self) -> String {
        std::any::type_name::<Self>().to_owned()
    }
}

impl<E: Estimator + ?Sized> Estimator for &E {
    fn identity(&self) -> String {
        (**self).identity()
    }

    fn irradiance(
        &self,
        at: SurfacePoint,
        map: MapView<'_>,
        options: &EstimatorOptions,
        scratch: &mut EstimatorScratch,
    ) -> Vec3 {
        (**self).irradiance(at, map, options, scratch)
    }
}

/// Runs the k-nearest query of an estimator under metric `M` (`options.k` photons within
/// `options.max_distance`, of `options.kinds`) into [`EstimatorScratch::neighbours`] and
/// returns the search extent (the k-th distance, or the maximum distance when fewer were
/// found), or `None` when the map is empty or the extent is zero (nothing to estimate from).
/// The preamble of every built-in estimator.
pub fn find_nearest<M: pm_kdtree::Metric>(
    at: SurfacePoint,
    map: MapView<'_>,
    options: &EstimatorOptions,
    scratch: &mut EstimatorScratch,
) -> Option<f32> {
    if map.tree.is_empty() {
        return None;
    }
    map.tree.nearest_k::<M>(
        at.position,
        options.k,
        options.max_distance,
        options.kinds,
        &mut scratch.neighbours,
    );
    let extent = scratch.neighbours.extent();
    (extent > 0.0).then_some(extent)
}
