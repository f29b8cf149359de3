//! Choosing an estimator at run time (command lines, comparisons) without `dyn` in the hot loop.

use super::Estimator;
use crate::estimator::disc::Disc;
use crate::estimator::geometry::GeometryBall;
use crate::estimator::geometry::GeometryCube;
use crate::estimator::options::EstimatorOptions;
use crate::estimator::point::MapView;
use crate::estimator::point::SurfacePoint;
use crate::estimator::scratch::EstimatorScratch;
use crate::estimator::weight::PhotonWeight;
use glam::Vec3;
use std::fmt;

/// One of the built-in estimators, chosen at run time ([`EstimatorKind::name`]: `disc`, `cube`, `ball`).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum EstimatorKind {
    /// [`Disc`] (Jensen).
    Disc,
    /// [`GeometryCube`] (Hey & Purgathofer).
    GeometryCube,
    /// [`GeometryBall`].
    GeometryBall,
}

impl EstimatorKind {
    /// All kinds, in command-line order.
    pub const ALL: [EstimatorKind; 3] = [
        EstimatorKind::Disc,
        EstimatorKind::GeometryCube,
        EstimatorKind::GeometryBall,
    ];

    /// The command-line name: `disc`, `cube` or `ball`.
    pub const fn name(self) -> &'static str {
        match self {
            EstimatorKind::Disc => "disc",
            EstimatorKind::GeometryCube => "cube",
            EstimatorKind::GeometryBall => "ball",
        }
    }
}

impl fmt::Display for EstimatorKind {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.name())
    }
}

impl Estimator for EstimatorKind {
    /// The kind's name, as the estimator it names gives ([`Disc`] and `EstimatorKind::Disc`
    /// render the same bits).
    fn identity(&self) -> String {
        self.name().to_owned()
    }

    #[inline]
    fn estimate(
        &self,
        at: SurfacePoint,
        map: MapView<'_>,
        options: &EstimatorOptions,
        weight: &dyn PhotonWeight,
        scratch: &mut EstimatorScratch,
    ) -> Vec3 {
        match self {
            EstimatorKind::Disc => Disc.estimate(at, map, options, weight, scratch),
            EstimatorKind::GeometryCube => GeometryCube.estimate(at, map, options, weight, scratch),
            EstimatorKind::GeometryBall => GeometryBall.estimate(at, map, options, weight, scratch),
        }
    }
}
