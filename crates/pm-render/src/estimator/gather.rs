//! Gathered photons: the neighbours of a k-nearest query decoded for an estimate (power in
//! watts, direction, kind, squared distance), with the photon filters every estimator shares.

use super::{EstimatorOptions, EstimatorScratch, SurfacePoint};
use glam::Vec3;
use pm_kdtree::{CompactPhoton, PhotonKind, PhotonTree, PowerScale};

/// A photon decoded for an estimate: its power in watts, its travel direction, its kind and
/// its squared distance from the query point.
///
/// Everything a kernel needs: a distance-weighted estimator (cone, Epanechnikov, Silverman)
/// sums `kernel(distance_squared) · power` over the photons [`gather_found`] decodes, with no
/// scale or sign convention of its own.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct GatheredPhoton {
    /// Power per RGB channel in watts: the map's [`PowerScale`] is applied.
    pub power: Vec3,
    /// Direction of travel, of any positive length: the estimators use it only in signs of
    /// dot products and in ratios of them, which do not depend on its length. Photons
    /// decoded from a map have unit L1 norm ([`CompactPhoton::direction_l1`]).
    pub direction: Vec3,
    /// Direct, indirect or caustic.
    pub kind: PhotonKind,
    /// Squared Euclidean distance from the query point (m²), whatever the query's metric.
    pub distance_squared: f32,
}

impl GatheredPhoton {
    /// Decodes `photon` of a tree whose power scale is `scale`, seen from `at`.
    #[inline]
    pub fn decode(photon: &CompactPhoton, scale: PowerScale, at: Vec3) -> Self {
        GatheredPhoton {
            power: photon.power(scale),
            direction: photon.direction_l1(),
            kind: photon.kind(),
            distance_squared: photon.position().distance_squared(at),
        }
    }
}

impl SurfacePoint {
    /// True when a photon travelling along `direction` arrives from behind the viewed side
    /// (`direction · normal ≥ 0`): it lit the other side of the surface. `direction` may have
    /// any positive length.
    #[inline]
    pub fn arrives_from_behind(&self, direction: Vec3) -> bool {
        direction.dot(self.normal) >= 0.0
    }
}

impl EstimatorOptions {
    /// The filter every estimator applies to a photon of `kind` travelling along `direction`
    /// at `at`: its kind is one of [`EstimatorOptions::kinds`], and, when
    /// [`EstimatorOptions::reject_behind`] is set, it does not arrive from behind
    /// ([`SurfacePoint::arrives_from_behind`]).
    #[inline]
    pub fn accepts(&self, at: SurfacePoint, kind: PhotonKind, direction: Vec3) -> bool {
        self.kinds.accepts(kind) && !(self.reject_behind && at.arrives_from_behind(direction))
    }
}

/// Decodes the neighbours found by the last [`super::find_nearest`] into
/// [`EstimatorScratch::photons`] ([`GatheredPhoton::decode`]: powers in watts, squared
/// distances), keeping those [`EstimatorOptions::accepts`] (the k-nearest query has already
/// applied the kind filter; this adds back-face rejection when it is on). With
/// [`EstimatorOptions::leave_out_boundary`] the boundary photon is left out.
pub fn gather_found(
    at: SurfacePoint,
    tree: &PhotonTree,
    options: &EstimatorOptions,
    scratch: &mut EstimatorScratch,
) {
    let scale = tree.power_scale();
    scratch.photons.clear();
    let counted = counted_neighbours(&scratch.neighbours, options.leave_out_boundary);
    for n in scratch.neighbours.as_slice().iter().filter(|n| counted(n)) {
        let photon = GatheredPhoton::decode(&tree.get(n.index), scale, at.position);
        // The query has applied the kind filter already.
        if !(options.reject_behind && at.arrives_from_behind(photon.direction)) {
            scratch.photons.push(photon);
        }
    }
}

/// Decodes every photon within `extent` of `at` (under metric `M`: a ball for
/// [`pm_kdtree::Euclidean`], a cube of half-size `extent` for [`pm_kdtree::Chebyshev`]) that
/// `options` accepts into the scratch's photons ([`EstimatorScratch::photons`]): the
/// fixed-volume counterpart of [`gather_found`], for a [`super::FixedVolumeEstimator`] of
/// your own. Allocation-free once the scratch is warm.
pub fn gather_within<M: pm_kdtree::Metric>(
    at: SurfacePoint,
    tree: &PhotonTree,
    extent: f32,
    options: &EstimatorOptions,
    scratch: &mut EstimatorScratch,
) {
    collect_within::<M>(at, tree, extent, options, &mut scratch.photons);
}

/// [`gather_within`] into `photons` (for callers that hold other parts of the scratch).
pub(super) fn collect_within<M: pm_kdtree::Metric>(
    at: SurfacePoint,
    tree: &PhotonTree,
    extent: f32,
    options: &EstimatorOptions,
    photons: &mut Vec<GatheredPhoton>,
) {
    let scale = tree.power_scale();
    photons.clear();
    tree.for_each_within::<M>(at.position, extent, |index, _| {
        let photon = GatheredPhoton::decode(&tree.get(index), scale, at.position);
        if options.accepts(at, photon.kind, photon.direction) {
            photons.push(photon);
        }
    });
}

/// Which of the `neighbours` of a k-nearest search an estimate counts: all of them, or, with
/// `leave_out_boundary`, all but the boundary photon (the farthest, when the search found its
/// k and the extent is its distance).
pub(super) fn counted_neighbours(
    neighbours: &pm_kdtree::Neighbours,
    leave_out_boundary: bool,
) -> impl Fn(&pm_kdtree::Neighbour) -> bool {
    let boundary = (leave_out_boundary && !neighbours.is_partial())
        .then(|| {
            neighbours
                .as_slice()
                .iter()
                .max_by(|a, b| a.distance.total_cmp(&b.distance))
                .map(|n| n.index)
        })
        .flatten();
    move |n| Some(n.index) != boundary
}
