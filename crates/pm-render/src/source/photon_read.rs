//! How the photons at a camera path's vertex become radiance: `ρ_d/π · E` where the BSDF's
//! non-delta part is diffuse only, `Σ Φ_p f(wo, wi_p) / A` where it has a glossy lobe.

use super::direct::{Mis, direct_irradiance, direct_radiance_through};
use crate::estimator::weight::{BsdfWeight, Irradiance, PhotonWeight};
use glam::Vec3;
use pm_trace::{Bsdf, Hit, Rng, Scene};
use std::f32::consts::FRAC_1_PI;

/// Where the direct light at a diffuse hit comes from.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum DirectLight {
    /// From the photons of kind direct, like all other light.
    Photons,
    /// From one shadow ray per light; the estimator's options must then leave photons of kind
    /// direct out ([`pm_kdtree::KindMask::NOT_DIRECT`]).
    ShadowRays,
}

/// Radiance reflected at `hit` towards `wo` from the photons `estimate` reads with the weight
/// it is given, plus direct light by shadow rays when `direct` says so.
///
/// A BSDF with a glossy lobe is read with the weight `f(wo, wi_p)` (its whole `f`, diffuse
/// lobe included) and its shadow rays evaluate `f` per light; any other (diffuse only) is read
/// as `albedo/π` times the irradiance (estimate with weight one, plus the shadow rays'
/// irradiance), with `albedo` the caller's (a texture may be filtered over a pixel's
/// footprint), exactly the arithmetic of the diffuse-only renderer.
#[inline]
pub(crate) fn photon_radiance(
    scene: &Scene,
    hit: &Hit,
    wo: Vec3,
    albedo: impl FnOnce() -> Vec3,
    direct: DirectLight,
    rng: &mut Rng,
    estimate: impl FnOnce(&dyn PhotonWeight) -> Vec3,
) -> Vec3 {
    let material = scene.material(hit);
    if material.lobes().has_glossy() {
        let at = scene.shading_point(hit);
        let mut l = estimate(&BsdfWeight::new(material, at, wo));
        if direct == DirectLight::ShadowRays {
            l += direct_radiance_through(scene, hit, &at, material, wo, Mis::ShadowRaysOnly, rng);
        }
        return l;
    }
    let albedo = albedo();
    let mut e = estimate(&Irradiance);
    if direct == DirectLight::ShadowRays {
        e += direct_irradiance(scene, hit, rng);
    }
    albedo * FRAC_1_PI * e
}
