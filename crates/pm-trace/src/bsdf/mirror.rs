//! The perfect specular reflector: one delta lobe about the shading normal (the geometric one
//! where that would reflect into the surface).

use super::lobes::Lobes;
use super::scatter::mirror_direction;
use super::shading_point::ShadingPoint;
use super::{Bsdf, BsdfSample};
use crate::rng::Rng;
use glam::{Vec2, Vec3};

/// A mirror of reflectance `reflectance` (times the point's tint).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Mirror {
    /// Reflectance per RGB channel, in `[0, 1]`.
    pub reflectance: Vec3,
}

impl Bsdf for Mirror {
    #[inline]
    fn lobes(&self) -> Lobes {
        Lobes::DELTA_REFLECTION
    }

    /// Zero: a delta lobe has no density.
    #[inline]
    fn eval(&self, _at: &ShadingPoint, _wo: Vec3, _wi: Vec3) -> Vec3 {
        Vec3::ZERO
    }

    /// Zero: a delta lobe has no density.
    #[inline]
    fn pdf(&self, _at: &ShadingPoint, _wo: Vec3, _wi: Vec3) -> f32 {
        0.0
    }

    /// The reflection of `wo` (no random number used), weight the reflectance, probability 1.
    #[inline]
    fn sample(&self, at: &ShadingPoint, wo: Vec3, _u: Vec2, _u_lobe: f32) -> Option<BsdfSample> {
        Some(BsdfSample {
            wi: mirror_direction(-wo, at.geometric, at.shading),
            weight: self.reflectance * at.tint,
            pdf: 1.0,
            lobe: Lobes::DELTA_REFLECTION,
        })
    }

    /// Draws nothing.
    #[inline]
    fn sample_from(&self, at: &ShadingPoint, wo: Vec3, _rng: &mut Rng) -> Option<BsdfSample> {
        self.sample(at, wo, Vec2::ZERO, 0.0)
    }

    #[inline]
    fn albedo(&self, at: &ShadingPoint, _wo: Vec3) -> Vec3 {
        self.reflectance * at.tint
    }
}
