//! Smooth colourless glass: Fresnel reflection and refraction, two delta lobes chosen by the
//! Fresnel reflectance, about the shading normal with the geometric normal as the fallback.

use super::lobes::Lobes;
use super::scatter::{GlassBounce, glass_bounce};
use super::shading_point::ShadingPoint;
use super::{Bsdf, BsdfSample};
use crate::rng::Rng;
use glam::{Vec2, Vec3};

/// A smooth dielectric of index of refraction `ior` (inside over outside); it absorbs nothing
/// and ignores the tint.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Glass {
    /// Index of refraction (inside / outside), e.g. 1.5.
    pub ior: f32,
}

impl Glass {
    /// `n_incident / n_transmitted` for a ray arriving at `at`'s side.
    #[inline]
    fn eta(&self, at: &ShadingPoint) -> f32 {
        if at.front_face { 1.0 / self.ior } else { self.ior }
    }

    fn to_sample(bounce: GlassBounce) -> BsdfSample {
        BsdfSample {
            wi: bounce.direction,
            // Each lobe is chosen with the probability of its share (F or 1 − F), so the
            // weight, share over probability, is one.
            weight: Vec3::ONE,
            pdf: bounce.probability,
            lobe: if bounce.reflected {
                Lobes::DELTA_REFLECTION
            } else {
                Lobes::DELTA_TRANSMISSION
            },
        }
    }
}

impl Bsdf for Glass {
    #[inline]
    fn lobes(&self) -> Lobes {
        Lobes::DELTA_REFLECTION | Lobes::DELTA_TRANSMISSION
    }

    /// Zero: delta lobes have no density.
    #[inline]
    fn eval(&self, _at: &ShadingPoint, _wo: Vec3, _wi: Vec3) -> Vec3 {
        Vec3::ZERO
    }

    /// Zero: delta lobes have no density.
    #[inline]
    fn pdf(&self, _at: &ShadingPoint, _wo: Vec3, _wi: Vec3) -> f32 {
        0.0
    }

    /// Reflection when `u_lobe` is below the Fresnel reflectance (or refraction is
    /// impossible), else refraction; `u` unused.
    #[inline]
    fn sample(&self, at: &ShadingPoint, wo: Vec3, _u: Vec2, u_lobe: f32) -> Option<BsdfSample> {
        let bounce = glass_bounce(-wo, at.geometric, at.shading, self.eta(at), &mut || u_lobe);
        Some(Self::to_sample(bounce))
    }

    /// Draws one number, and only when refraction is possible.
    #[inline]
    fn sample_from(&self, at: &ShadingPoint, wo: Vec3, rng: &mut Rng) -> Option<BsdfSample> {
        let bounce = glass_bounce(-wo, at.geometric, at.shading, self.eta(at), &mut || {
            rng.next_f32()
        });
        Some(Self::to_sample(bounce))
    }

    #[inline]
    fn albedo(&self, _at: &ShadingPoint, _wo: Vec3) -> Vec3 {
        Vec3::ONE
    }
}
