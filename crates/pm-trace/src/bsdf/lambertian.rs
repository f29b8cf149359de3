//! The ideal diffuse reflector: `f = ρ/π` above the shading normal, sampled by the cosine.

use super::lobes::Lobes;
use super::shading_point::ShadingPoint;
use super::{Bsdf, BsdfSample};
use crate::rng::Rng;
use crate::sampling::cosine_hemisphere;
use glam::{Vec2, Vec3};
use std::f32::consts::FRAC_1_PI;

/// A Lambertian surface of reflectance `albedo` (times the point's tint).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Lambertian {
    /// Reflectance per RGB channel, in `[0, 1]`.
    pub albedo: Vec3,
}

impl Bsdf for Lambertian {
    #[inline]
    fn lobes(&self) -> Lobes {
        Lobes::DIFFUSE_REFLECTION
    }

    #[inline]
    fn eval(&self, at: &ShadingPoint, _wo: Vec3, wi: Vec3) -> Vec3 {
        if at.shading.dot(wi) > 0.0 {
            self.albedo * at.tint * FRAC_1_PI
        } else {
            Vec3::ZERO
        }
    }

    #[inline]
    fn pdf(&self, at: &ShadingPoint, _wo: Vec3, wi: Vec3) -> f32 {
        at.shading.dot(wi).max(0.0) * FRAC_1_PI
    }

    /// Cosine-distributed about the shading normal from `u` (`u_lobe` unused). The weight is
    /// the reflectance exactly (`(ρ/π) cos / (cos/π)`); the direction may lie below the
    /// geometric surface where the shading normal leans (the renderer drops it there).
    #[inline]
    fn sample(&self, at: &ShadingPoint, _wo: Vec3, u: Vec2, _u_lobe: f32) -> Option<BsdfSample> {
        let wi = cosine_hemisphere(at.shading, u);
        Some(BsdfSample {
            wi,
            weight: self.albedo * at.tint,
            pdf: at.shading.dot(wi).max(0.0) * FRAC_1_PI,
            lobe: Lobes::DIFFUSE_REFLECTION,
        })
    }

    /// Draws `u.x` and `u.y` only.
    #[inline]
    fn sample_from(&self, at: &ShadingPoint, wo: Vec3, rng: &mut Rng) -> Option<BsdfSample> {
        let u = Vec2::new(rng.next_f32(), rng.next_f32());
        self.sample(at, wo, u, 0.0)
    }

    #[inline]
    fn albedo(&self, at: &ShadingPoint, _wo: Vec3) -> Vec3 {
        self.albedo * at.tint
    }

    #[inline]
    fn diffuse_albedo(&self, at: &ShadingPoint) -> Vec3 {
        self.albedo * at.tint
    }
}
