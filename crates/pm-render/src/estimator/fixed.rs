//! Fixed-volume estimates: every photon of a map inside a gather volume of a given size, over
//! that volume's area (the disc π r², or the geometric area of the map's polygons inside it).
//! Progressive rendering needs them: a volume chosen before the photons are seen makes each
//! estimate unbiased for the irradiance smoothed over that volume.

use super::gather::collect_within;
use super::geometry::{collect_faces, spread_power};
use super::{Estimator, find_nearest};
use crate::estimator::disc::Disc;
use crate::estimator::geometry::GeometryBall;
use crate::estimator::geometry::GeometryCube;
use crate::estimator::geometry::VolumeMetric;
use crate::estimator::kind::EstimatorKind;
use crate::estimator::options::EstimatorOptions;
use crate::estimator::point::MapView;
use crate::estimator::point::SurfacePoint;
use crate::estimator::scratch::EstimatorScratch;
use crate::estimator::weight::{Irradiance, PhotonWeight};
use glam::Vec3;
use pm_kdtree::{Chebyshev, Euclidean, Metric};
use std::f32::consts::PI;

/// An estimator that can also estimate in a volume of a given extent (a radius, or a cube's
/// half-size), and say which extent its k-nearest search would choose.
///
/// Implemented by [`Disc`], [`GeometryCube`], [`GeometryBall`] and [`EstimatorKind`]; the
/// progressive renderer is generic over it.
pub trait FixedVolumeEstimator: Estimator {
    /// The extent of this estimator's k-nearest search at `at` in `map` (the k-th distance
    /// under its metric, or `options.max_distance` when fewer than k photons lie within it).
    /// `None` when the k nearest all sit at `at` itself (a zero extent).
    fn nearest_extent(
        &self,
        at: SurfacePoint,
        map: MapView<'_>,
        options: &EstimatorOptions,
        scratch: &mut EstimatorScratch,
    ) -> Option<f32>;

    /// The sum of the power of *every* photon of `map` within `extent` of `at` under this
    /// estimator's metric, each times `weight` of its direction (options' kinds and back-face
    /// rejection applied; `k` and `max_distance` unused), divided by the volume's area:
    /// `π extent²` for the disc, the area of the map's polygons inside the cube or ball for
    /// the geometry estimators. With [`Irradiance`]: the irradiance.
    fn estimate_within(
        &self,
        at: SurfacePoint,
        map: MapView<'_>,
        extent: f32,
        options: &EstimatorOptions,
        weight: &dyn PhotonWeight,
        scratch: &mut EstimatorScratch,
    ) -> Vec3;

    /// Irradiance at `at` in the volume of `extent`: [`FixedVolumeEstimator::estimate_within`]
    /// with the weight [`Irradiance`].
    #[inline]
    fn irradiance_within(
        &self,
        at: SurfacePoint,
        map: MapView<'_>,
        extent: f32,
        options: &EstimatorOptions,
        scratch: &mut EstimatorScratch,
    ) -> Vec3 {
        self.estimate_within(at, map, extent, options, &Irradiance, scratch)
    }
}

/// The geometry estimate under metric `M` in the volume of `extent`, powers times `weight`.
fn geometry_within<M: VolumeMetric>(
    at: SurfacePoint,
    map: MapView<'_>,
    extent: f32,
    options: &EstimatorOptions,
    weight: &dyn PhotonWeight,
    scratch: &mut EstimatorScratch,
) -> Vec3 {
    if map.tree.is_empty() || extent.is_nan() || extent <= 0.0 {
        return Vec3::ZERO;
    }
    let EstimatorScratch {
        clip,
        photons,
        faces,
        candidates,
        ..
    } = scratch;
    collect_within::<M>(at, map.tree, extent, options, weight, photons);
    if photons.is_empty() {
        return Vec3::ZERO;
    }
    let volume = M::volume(at.position, extent);
    let orientation = if at.front_face { 1.0 } else { -1.0 };
    collect_faces(&volume, map.polygons, orientation, clip, candidates, faces);
    spread_power(at.normal, photons, faces)
}

impl FixedVolumeEstimator for Disc {
    fn nearest_extent(
        &self,
        at: SurfacePoint,
        map: MapView<'_>,
        options: &EstimatorOptions,
        scratch: &mut EstimatorScratch,
    ) -> Option<f32> {
        nearest_or_max::<Euclidean>(at, map, options, scratch)
    }

    fn estimate_within(
        &self,
        at: SurfacePoint,
        map: MapView<'_>,
        extent: f32,
        options: &EstimatorOptions,
        weight: &dyn PhotonWeight,
        scratch: &mut EstimatorScratch,
    ) -> Vec3 {
        if map.tree.is_empty() || extent.is_nan() || extent <= 0.0 {
            return Vec3::ZERO;
        }
        collect_within::<Euclidean>(at, map.tree, extent, options, weight, &mut scratch.photons);
        let power: Vec3 = scratch.photons.iter().map(|p| p.power).sum();
        power / (PI * extent * extent)
    }
}

/// The two geometry-based estimators differ only in their metric (the cube's Chebyshev, the
/// ball's Euclidean), which also picks the gather volume whose polygon area divides.
macro_rules! geometry_fixed_volume {
    ($estimator:ty, $metric:ty) => {
        impl FixedVolumeEstimator for $estimator {
            fn nearest_extent(
                &self,
                at: SurfacePoint,
                map: MapView<'_>,
                options: &EstimatorOptions,
                scratch: &mut EstimatorScratch,
            ) -> Option<f32> {
                nearest_or_max::<$metric>(at, map, options, scratch)
            }

            fn estimate_within(
                &self,
                at: SurfacePoint,
                map: MapView<'_>,
                extent: f32,
                options: &EstimatorOptions,
                weight: &dyn PhotonWeight,
                scratch: &mut EstimatorScratch,
            ) -> Vec3 {
                geometry_within::<$metric>(at, map, extent, options, weight, scratch)
            }
        }
    };
}

geometry_fixed_volume!(GeometryCube, Chebyshev);
geometry_fixed_volume!(GeometryBall, Euclidean);

impl FixedVolumeEstimator for EstimatorKind {
    #[inline]
    fn nearest_extent(
        &self,
        at: SurfacePoint,
        map: MapView<'_>,
        options: &EstimatorOptions,
        scratch: &mut EstimatorScratch,
    ) -> Option<f32> {
        match self {
            EstimatorKind::Disc => Disc.nearest_extent(at, map, options, scratch),
            EstimatorKind::GeometryCube => GeometryCube.nearest_extent(at, map, options, scratch),
            EstimatorKind::GeometryBall => GeometryBall.nearest_extent(at, map, options, scratch),
        }
    }

    #[inline]
    fn estimate_within(
        &self,
        at: SurfacePoint,
        map: MapView<'_>,
        extent: f32,
        options: &EstimatorOptions,
        weight: &dyn PhotonWeight,
        scratch: &mut EstimatorScratch,
    ) -> Vec3 {
        match self {
            EstimatorKind::Disc => Disc.estimate_within(at, map, extent, options, weight, scratch),
            EstimatorKind::GeometryCube => {
                GeometryCube.estimate_within(at, map, extent, options, weight, scratch)
            }
            EstimatorKind::GeometryBall => {
                GeometryBall.estimate_within(at, map, extent, options, weight, scratch)
            }
        }
    }
}

impl<E: FixedVolumeEstimator + ?Sized> FixedVolumeEstimator for &E {
    fn nearest_extent(
        &self,
        at: SurfacePoint,
        map: MapView<'_>,
        options: &EstimatorOptions,
        scratch: &mut EstimatorScratch,
    ) -> Option<f32> {
        (**self).nearest_extent(at, map, options, scratch)
    }

    fn estimate_within(
        &self,
        at: SurfacePoint,
        map: MapView<'_>,
        extent: f32,
        options: &EstimatorOptions,
        weight: &dyn PhotonWeight,
        scratch: &mut EstimatorScratch,
    ) -> Vec3 {
        (**self).estimate_within(at, map, extent, options, weight, scratch)
    }
}

/// The k-nearest extent, or the maximum distance in an empty map (a map the pilot missed
/// still gets a volume to gather in).
fn nearest_or_max<M: Metric>(
    at: SurfacePoint,
    map: MapView<'_>,
    options: &EstimatorOptions,
    scratch: &mut EstimatorScratch,
) -> Option<f32> {
    if map.tree.is_empty() {
        return Some(options.max_distance);
    }
    find_nearest::<M>(at, map, options, scratch)
}
