//! Geometry-based area estimation (Hey & Purgathofer): spread each gathered photon's power over
//! the area of the same map's surfaces inside the gather volume that faces it.

use super::{Estimator, find_nearest};
use crate::estimator::gather::gather_found;
use crate::estimator::options::EstimatorOptions;
use crate::estimator::photon::GatheredPhoton;
use crate::estimator::point::MapView;
use crate::estimator::point::SurfacePoint;
use crate::estimator::scratch::EstimatorScratch;
use crate::estimator::weight::PhotonWeight;
use glam::Vec3;
use pm_geom::{Aabb, Ball, ClipScratch, GatherVolume, PolygonSet};
use pm_kdtree::{Chebyshev, Euclidean, Metric};

/// A metric whose k-nearest region is a gather volume: Chebyshev → cube, Euclidean → ball.
pub trait VolumeMetric: Metric {
    /// The region of this metric's k-nearest search.
    type Volume: GatherVolume;
    /// The volume of all points within `extent` of `center` under this metric.
    fn volume(center: Vec3, extent: f32) -> Self::Volume;
}

impl VolumeMetric for Chebyshev {
    type Volume = Aabb;
    fn volume(center: Vec3, extent: f32) -> Aabb {
        Aabb::cube(center, extent)
    }
}

impl VolumeMetric for Euclidean {
    type Volume = Ball;
    fn volume(center: Vec3, extent: f32) -> Ball {
        Ball::new(center, extent)
    }
}

/// Hey & Purgathofer's estimator in a cube (the k nearest under L∞), with the cosine at the
/// query point so that it conserves energy.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct GeometryCube;

/// The geometry estimator in a ball (the k nearest under L2) with the exact polygon–ball area
/// of each polygon inside the ball.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct GeometryBall;

impl Estimator for GeometryCube {
    /// `cube`.
    fn identity(&self) -> String {
        "cube".to_owned()
    }

    fn estimate(
        &self,
        at: SurfacePoint,
        map: MapView<'_>,
        options: &EstimatorOptions,
        weight: &dyn PhotonWeight,
        scratch: &mut EstimatorScratch,
    ) -> Vec3 {
        geometry_estimate::<Chebyshev>(at, map, options, weight, scratch)
    }
}

impl Estimator for GeometryBall {
    /// `ball`.
    fn identity(&self) -> String {
        "ball".to_owned()
    }

    fn estimate(
        &self,
        at: SurfacePoint,
        map: MapView<'_>,
        options: &EstimatorOptions,
        weight: &dyn PhotonWeight,
        scratch: &mut EstimatorScratch,
    ) -> Vec3 {
        geometry_estimate::<Euclidean>(at, map, options, weight, scratch)
    }
}

/// The geometry estimate under metric `M` from the k nearest photons, each power times `weight`.
fn geometry_estimate<M: VolumeMetric>(
    at: SurfacePoint,
    map: MapView<'_>,
    options: &EstimatorOptions,
    weight: &dyn PhotonWeight,
    scratch: &mut EstimatorScratch,
) -> Vec3 {
    let Some(extent) = find_nearest::<M>(at, map, options, scratch) else {
        return Vec3::ZERO;
    };
    gather_found(at, map.tree, options, weight, scratch);
    let volume = M::volume(at.position, extent);
    let EstimatorScratch {
        clip,
        photons,
        faces,
        candidates,
        ..
    } = scratch;
    let orientation = if at.front_face { 1.0 } else { -1.0 };
    collect_faces(&volume, map.polygons, orientation, clip, candidates, faces);
    spread_power(at.normal, photons, faces)
}

/// The geometry estimate for a given gather `volume` and `photons` (already gathered), over
/// the polygons of `polygons` that overlap it, seen from a surface with unit normal `normal`:
/// `E = Σ_p Φ_p · max(0, −n·ω_p) / S_p` (`Φ_p` already weighted, [`super::gather_found`]) with `S_p = Σ_f A_f · max(0, −n_f·ω_p)` (the length
/// of `ω_p` cancels, so photon directions need not be normalised).
/// The cosine at x uses the enclosed face most aligned with `normal` (x's own face on a
/// polygon mesh), which keeps curved surfaces seen through polygonal proxies consistent.
///
/// This is the core of [`GeometryCube`] and [`GeometryBall`], public so that new gather volumes
/// (anything implementing [`GatherVolume`]) can be used and tested directly.
pub fn irradiance_in_volume<V: GatherVolume>(
    volume: &V,
    normal: Vec3,
    photons: &[GatheredPhoton],
    polygons: &PolygonSet,
    scratch: &mut EstimatorScratch,
) -> Vec3 {
    let EstimatorScratch {
        clip,
        faces,
        candidates,
        ..
    } = scratch;
    collect_faces(volume, polygons, 1.0, clip, candidates, faces);
    spread_power(normal, photons, faces)
}

/// Fills `faces` with (area inside `volume`, normal × `orientation`) of every polygon that has
/// area inside it.
pub(super) fn collect_faces<V: GatherVolume>(
    volume: &V,
    polygons: &PolygonSet,
    orientation: f32,
    clip: &mut ClipScratch,
    candidates: &mut Vec<u32>,
    faces: &mut Vec<(f32, Vec3)>,
) {
    candidates.clear();
    faces.clear();
    if polygons.is_empty() {
        return;
    }
    polygons.for_each_overlapping(&volume.bounds(), |i| candidates.push(i));
    for &i in candidates.iter() {
        let normal = polygons.normal(i);
        let area = volume.polygon_area_inside(polygons.polygon(i), normal, clip);
        if area > 0.0 {
            faces.push((area, normal * orientation));
        }
    }
}

pub(super) fn spread_power(normal: Vec3, photons: &[GatheredPhoton], faces: &[(f32, Vec3)]) -> Vec3 {
    let normal = snap_normal(normal, faces);
    if faces.iter().all(|&(_, n)| n == normal) {
        // One plane (the common case: a flat map, or a merged wall, away from its edges):
        // `S_p = A · cos_x` for every photon facing x, so `E = Σ Φ_p / A` without the
        // per-photon sum over faces.
        let area: f32 = faces.iter().map(|&(a, _)| a).sum();
        if area <= 0.0 {
            return Vec3::ZERO;
        }
        let facing: Vec3 = photons
            .iter()
            .filter(|p| normal.dot(p.direction) < 0.0)
            .map(|p| p.power)
            .sum();
        return facing / area;
    }
    let mut e = Vec3::ZERO;
    for p in photons {
        let cos_x = -normal.dot(p.direction);
        if cos_x <= 0.0 {
            continue;
        }
        let s: f32 = faces
            .iter()
            .map(|&(area, n)| area * (-n.dot(p.direction)).max(0.0))
            .sum();
        if s > 0.0 {
            e += p.power * (cos_x / s);
        }
    }
    e
}

/// The normal of the enclosed face most aligned with `normal` (the query point's own face on
/// a polygon mesh, so nothing changes there), or `normal` itself when no face is within 60°.
///
/// On curved surfaces (a sphere seen through its polygonal proxy) the true normal at x and
/// the proxy faces disagree by a few degrees. A grazing photon can then face x but none of
/// the proxy faces except a sliver that barely touches the volume, making `S_p` vanish and
/// the estimate explode. With the cosine taken on a proxy face, `cos_x ≤ S_p / A_face`.
fn snap_normal(normal: Vec3, faces: &[(f32, Vec3)]) -> Vec3 {
    let mut best = (0.5, normal);
    for &(_, n) in faces {
        let alignment = n.dot(normal);
        if alignment > best.0 {
            best = (alignment, n);
        }
    }
    best.1
}
