//! What an estimate sums per photon: a weight on each photon's power, from the direction it
//! arrived from. Weight one gives irradiance; a BSDF's `f(wo, wi_p)` gives reflected radiance.

use glam::Vec3;
use pm_trace::bsdf::{Bsdf, ShadingPoint};

/// The factor an estimate puts on each gathered photon's power, a function of the photon's
/// travel direction. Every estimator sums `Φ_p · weight(ω_p)` times its own kernel or area
/// term, so one estimator reads irradiance ([`Irradiance`], weight one) and reflected
/// radiance ([`BsdfWeight`], `f(wo, wi_p)`) alike.
pub trait PhotonWeight {
    /// The weight of a photon travelling along `direction` (towards the surface; any positive
    /// length), per RGB channel.
    fn weight(&self, direction: Vec3) -> Vec3;

    /// `Some(w)` when every photon gets the same weight `w` whatever its direction, so that an
    /// estimator may sum powers without decoding directions and multiply once. `None` (the
    /// default) otherwise.
    #[inline]
    fn uniform(&self) -> Option<Vec3> {
        None
    }
}

/// Weight one for every photon: the estimate is the irradiance `E` (W/m²).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct Irradiance;

impl PhotonWeight for Irradiance {
    #[inline]
    fn weight(&self, _direction: Vec3) -> Vec3 {
        Vec3::ONE
    }

    #[inline]
    fn uniform(&self) -> Option<Vec3> {
        Some(Vec3::ONE)
    }
}

/// Weight `f(wo, wi_p)` with `wi_p = −ω_p` (the direction the photon came from): the estimate
/// is the radiance `Σ Φ_p f(wo, wi_p) / A` reflected towards `wo` (W/(m²·sr)).
///
/// No shading-normal correction: the photons' power is flux through the geometric surface,
/// and the estimate reads it as that (as the diffuse `ρ_d/π · E` does). Veach's adjoint
/// correction `|wi·n_s| / |wi·n_g|` (Mitsuba's) would make the glossy and diffuse reads
/// differ on smooth-shaded meshes and blows up for photons grazing the geometric surface;
/// on flat faces, where the two normals agree, both forms are the same.
#[derive(Clone, Copy, Debug)]
pub struct BsdfWeight<'a, B: ?Sized> {
    bsdf: &'a B,
    at: ShadingPoint,
    wo: Vec3,
}

impl<'a, B: Bsdf + ?Sized> BsdfWeight<'a, B> {
    /// The weight of `bsdf` at `at` for light leaving towards `wo` (unit, away from the
    /// surface).
    pub fn new(bsdf: &'a B, at: ShadingPoint, wo: Vec3) -> Self {
        BsdfWeight { bsdf, at, wo }
    }
}

impl<B: Bsdf + ?Sized> PhotonWeight for BsdfWeight<'_, B> {
    #[inline]
    fn weight(&self, direction: Vec3) -> Vec3 {
        match (-direction).try_normalize() {
            Some(wi) => self.bsdf.eval(&self.at, self.wo, wi),
            None => Vec3::ZERO,
        }
    }
}
