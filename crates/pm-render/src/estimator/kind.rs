//! Choosing an estimator at run time (command lines, comparisons) without `dyn` in the hot loop.

use super::{
    Disc, Estimator, EstimatorOptions, EstimatorScratch, GeometryBall, GeometryCube, MapView, SurfacePoint,
};
use crate::RenderError;
use glam::Vec3;
use std::fmt;
use std::str::FromStr;

/// One of the built-in estimators, chosen at run time. Parses from `disc`, `cube`, `ball`.
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

impl FromStr for EstimatorKind {
    type Err = RenderError;
    fn from_str(s: &str) -> Result<Self, RenderError> {
        Self::ALL
            .into_iter()
            .find(|k| k.name() == s)
            .ok_or_else(|| RenderError::UnknownName {
                what: "estimator",
                name: s.to_owned(),
                expected: "disc|cube|ball",
            })
    }
}

impl Estimator for EstimatorKind {
    #[inline]
    fn irradiance(
        &self,
        at: SurfacePoint,
        map: MapView<'_>,
        options: &EstimatorOptions,
        scratch: &mut EstimatorScratch,
    ) -> Vec3 {
        match self {
            EstimatorKind::Disc => Disc.irradiance(at, map, options, scratch),
            EstimatorKind::GeometryCube => GeometryCube.irradiance(at, map, options, scratch),
            EstimatorKind::GeometryBall => GeometryBall.irradiance(at, map, options, scratch),
        }
    }
}
