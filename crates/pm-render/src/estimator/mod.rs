//! Radiance estimators: the irradiance at a surface point from the photons of one map
//! (Jensen's disc, and Hey & Purgathofer's geometry-based area in a cube or a ball), or the
//! radiance reflected there. The trait is generic-friendly; [`EstimatorKind`] picks one at
//! run time.
//!
//! # What is read where
//!
//! Every estimator sums each gathered photon's power times a [`PhotonWeight`] of its
//! direction, over its own area or kernel: `Σ Φ_p w(ω_p) / A`. With [`Irradiance`] (weight
//! one) that is the irradiance `E`; with [`BsdfWeight`] (`f(wo, wi_p)`, `wi_p = −ω_p`) it is
//! the radiance reflected towards `wo`. The renderer reads a surface whose BSDF has a glossy
//! lobe with the BSDF weight (the whole `f`, its diffuse lobe included); a surface whose
//! non-delta part is diffuse only as `ρ_d/π · E` with the irradiance weight, which is the same
//! sum for a Lambertian lobe and keeps its images bit for bit. The radiance cache stays an
//! irradiance (a diffuse quantity) read at diffuse hits.
//!
//! # Writing an estimator: the Epanechnikov kernel
//!
//! An estimator of your own uses the building blocks of the built-in ones: [`find_nearest`]
//! runs the k-nearest query (the options' k, maximum distance and photon kinds) and returns
//! its radius r; [`gather_found`] decodes the neighbours into [`GatheredPhoton`]s with their
//! power in watts (the map's power scale applied) times the caller's [`PhotonWeight`] and
//! their squared distance, dropping photons from behind when the options ask
//! ([`EstimatorOptions::accepts`]). A distance-weighted kernel is
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
//!     fn estimate(
//!         &self,
//!         at: SurfacePoint,
//!         map: MapView<'_>,
//!         options: &EstimatorOptions,
//!         weight: &dyn PhotonWeight,
//!         scratch: &mut EstimatorScratch,
//!     ) -> Vec3 {
//!         let Some(r) = find_nearest::<Euclidean>(at, map, options, scratch) else {
//!             return Vec3::ZERO;
//!         };
//!         gather_found(at, map.tree, options, weight, scratch);
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

pub(crate) mod disc;
pub(crate) mod fixed;
pub(crate) mod gather;
pub(crate) mod geometry;
pub(crate) mod kind;
pub(crate) mod options;
pub(crate) mod photon;
pub(crate) mod point;
pub(crate) mod scratch;
pub(crate) mod weight;

pub use disc::Disc;
pub use fixed::FixedVolumeEstimator;
pub use gather::{gather_found, gather_within};
pub use geometry::{GeometryBall, GeometryCube, VolumeMetric, irradiance_in_volume};
pub use kind::EstimatorKind;
pub use options::EstimatorOptions;
pub use photon::GatheredPhoton;
pub use point::{MapView, SurfacePoint};
pub use scratch::EstimatorScratch;
pub use weight::{BsdfWeight, Irradiance, PhotonWeight};

use glam::Vec3;

/// Estimates irradiance (W/m²), or reflected radiance, at a surface point from one photon map.
///
/// Outgoing radiance on a Lambertian surface of albedo ρ is `ρ/π · E`; on any other it is the
/// estimate with the weight [`BsdfWeight`].
pub trait Estimator: Send + Sync {
    /// The sum over the photons of `map` this estimator gathers at `at` of their power times
    /// `weight` of their direction, over its area or kernel (with [`Irradiance`]: the
    /// irradiance), with `options`, using `scratch` for all buffers.
    fn estimate(
        &self,
        at: SurfacePoint,
        map: MapView<'_>,
        options: &EstimatorOptions,
        weight: &dyn PhotonWeight,
        scratch: &mut EstimatorScratch,
    ) -> Vec3;

    /// Irradiance at `at` from `map`: [`Estimator::estimate`] with the weight [`Irradiance`].
    #[inline]
    fn irradiance(
        &self,
        at: SurfacePoint,
        map: MapView<'_>,
        options: &EstimatorOptions,
        scratch: &mut EstimatorScratch,
    ) -> Vec3 {
        self.estimate(at, map, options, &Irradiance, scratch)
    }

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

    fn estimate(
        &self,
        at: SurfacePoint,
        map: MapView<'_>,
        options: &EstimatorOptions,
        weight: &dyn PhotonWeight,
        scratch: &mut EstimatorScratch,
    ) -> Vec3 {
        (**self).estimate(at, map, options, weight, scratch)
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
