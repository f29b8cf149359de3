//! A photon decoded for an estimate: power in watts, direction, kind and squared distance.

use super::weight::PhotonWeight;
use glam::Vec3;
use pm_kdtree::{CompactPhoton, PhotonKind, PowerScale};

/// A photon decoded for an estimate: its power in watts, its travel direction, its kind and
/// its squared distance from the query point.
///
/// Everything a kernel needs: a distance-weighted estimator (cone, Epanechnikov, Silverman)
/// sums `kernel(distance_squared) · power` over the photons [`super::gather_found`] decodes, with no
/// scale or sign convention of its own.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct GatheredPhoton {
    /// Power per RGB channel in watts: the map's [`PowerScale`] is applied, and by
    /// [`super::gather_found`] the estimate's [`super::PhotonWeight`] (one for irradiance).
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

    /// The photon with its power times `weight` of its direction: `uniform` (the weight's
    /// [`PhotonWeight::uniform`], read once per estimate by the caller) when there is one, so
    /// that an irradiance read makes no call per photon.
    #[inline]
    pub fn weighted(self, weight: &dyn PhotonWeight, uniform: Option<Vec3>) -> Self {
        let w = match uniform {
            Some(w) => w,
            None => weight.weight(self.direction),
        };
        GatheredPhoton {
            power: self.power * w,
            ..self
        }
    }
}
