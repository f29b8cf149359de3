//! Gathering photons: the neighbours of a k-nearest query, or every photon in a fixed volume,
//! decoded for an estimate, with the photon filters every estimator shares.

use super::options::EstimatorOptions;
use super::photon::GatheredPhoton;
use super::point::SurfacePoint;
use super::scratch::EstimatorScratch;
use super::weight::PhotonWeight;
use glam::Vec3;
use pm_kdtree::{PhotonKind, PhotonTree};

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
/// [`EstimatorScratch::photons`] ([`GatheredPhoton::decode`]: powers in watts times `weight`
/// of their direction, squared distances), keeping those [`EstimatorOptions::accepts`] (the k-nearest query has already
/// applied the kind filter; this adds back-face rejection when it is on). With
/// [`EstimatorOptions::leave_out_boundary`] the boundary photon is left out.
pub fn gather_found(
    at: SurfacePoint,
    tree: &PhotonTree,
    options: &EstimatorOptions,
    weight: &dyn PhotonWeight,
    scratch: &mut EstimatorScratch,
) {
    let scale = tree.power_scale();
    let uniform = weight.uniform();
    scratch.photons.clear();
    let counted = counted_neighbours(&scratch.neighbours, options.leave_out_boundary);
    for n in scratch.neighbours.as_slice().iter().filter(|n| counted(n)) {
        let photon = GatheredPhoton::decode(&tree.get(n.index), scale, at.position);
        // The query has applied the kind filter already.
        if !(options.reject_behind && at.arrives_from_behind(photon.direction)) {
            scratch.photons.push(photon.weighted(weight, uniform));
        }
    }
}

/// Decodes every photon within `extent` of `at` (under metric `M`: a ball for
/// [`pm_kdtree::Euclidean`], a cube of half-size `extent` for [`pm_kdtree::Chebyshev`]) that
/// `options` accepts into the scratch's photons ([`EstimatorScratch::photons`]): the
/// fixed-volume counterpart of [`gather_found`] (powers times `weight` likewise), for a
/// [`super::FixedVolumeEstimator`] of your own. Allocation-free once the scratch is warm.
pub fn gather_within<M: pm_kdtree::Metric>(
    at: SurfacePoint,
    tree: &PhotonTree,
    extent: f32,
    options: &EstimatorOptions,
    weight: &dyn PhotonWeight,
    scratch: &mut EstimatorScratch,
) {
    collect_within::<M>(at, tree, extent, options, weight, &mut scratch.photons);
}

/// [`gather_within`] into `photons` (for callers that hold other parts of the scratch).
pub(super) fn collect_within<M: pm_kdtree::Metric>(
    at: SurfacePoint,
    tree: &PhotonTree,
    extent: f32,
    options: &EstimatorOptions,
    weight: &dyn PhotonWeight,
    photons: &mut Vec<GatheredPhoton>,
) {
    let scale = tree.power_scale();
    let uniform = weight.uniform();
    photons.clear();
    tree.for_each_within::<M>(at.position, extent, |index, _| {
        let photon = GatheredPhoton::decode(&tree.get(index), scale, at.position);
        if options.accepts(at, photon.kind, photon.direction) {
            photons.push(photon.weighted(weight, uniform));
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
