//! Radiance estimators: the irradiance at a surface point from the photons of one map
//! (Jensen's disc, and Hey & Purgathofer's geometry-based area in a cube or a ball). The
//! trait is generic-friendly; [`EstimatorKind`] picks one at run time.

mod disc;
mod fixed;
mod geometry;
mod kind;
mod options;

pub use disc::Disc;
pub use fixed::FixedVolumeEstimator;
pub use geometry::{GeometryBall, GeometryCube, VolumeMetric, irradiance_in_volume};
pub use kind::EstimatorKind;
pub use options::EstimatorOptions;

use glam::Vec3;
use pm_geom::{ClipScratch, PolygonSet};
use pm_kdtree::{Neighbours, PhotonTree};

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

/// A photon decoded for the estimate: power and travel direction.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct GatheredPhoton {
    /// Power per RGB channel, in the unit the estimate should come out in: watts when passed
    /// to [`irradiance_in_volume`]. The estimators gather a map's photons relative to its
    /// [`pm_kdtree::PowerScale`] ([`pm_kdtree::CompactPhoton::relative_power`]) and multiply
    /// the estimate by the scale once.
    pub power: Vec3,
    /// Direction of travel, of any positive length: the estimators use it only in signs of
    /// dot products and in ratios of them, which do not depend on its length. Photons
    /// gathered from a map have unit L1 norm ([`pm_kdtree::CompactPhoton::direction_l1`]).
    pub direction: Vec3,
}

/// Per-thread buffers of the estimators; reuse one per worker so queries allocate nothing once
/// warm.
#[derive(Clone, Debug, Default)]
pub struct EstimatorScratch {
    pub(crate) neighbours: Neighbours,
    pub(crate) clip: ClipScratch,
    pub(crate) photons: Vec<GatheredPhoton>,
    /// Candidate faces that overlap the volume: (area inside, unit normal).
    pub(crate) faces: Vec<(f32, Vec3)>,
    pub(crate) candidates: Vec<u32>,
}

impl EstimatorScratch {
    /// Empty scratch; grows on first use.
    pub fn new() -> Self {
        Self::default()
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
}

impl<E: Estimator + ?Sized> Estimator for &E {
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

/// Runs the k-nearest query of an estimator under metric `M` into `scratch.neighbours` and
/// returns the search extent, or `None` when the map is empty or the extent is zero (nothing
/// to estimate from).
pub(crate) fn find_nearest<M: pm_kdtree::Metric>(
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

/// Decodes the neighbours found by the last query into `scratch.photons`, dropping photons
/// that arrive from behind the surface when `options.reject_behind` is set. Their powers are
/// relative to the tree's power scale: multiply the estimate by
/// [`PhotonTree::power_scale`]'s watts.
pub(crate) fn gather_found(
    at: SurfacePoint,
    tree: &PhotonTree,
    options: &EstimatorOptions,
    scratch: &mut EstimatorScratch,
) {
    scratch.photons.clear();
    for n in scratch.neighbours.as_slice() {
        let p = tree.get(n.index);
        // Unnormalised: only signs and ratios of dot products with it are used.
        let direction = p.direction_l1();
        if options.reject_behind && direction.dot(at.normal) >= 0.0 {
            continue;
        }
        scratch.photons.push(GatheredPhoton {
            power: p.relative_power(),
            direction,
        });
    }
}
