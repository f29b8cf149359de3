//! ShadowRays: direct light by shadow rays at the first diffuse hit, everything else (photons
//! that are not direct) from the photon map.

use super::scatter::{MAX_SPECULAR_BOUNCES, specular_bounce};
use super::{Lighting, direct_irradiance};
use crate::{Estimator, EstimatorScratch};
use glam::Vec3;
use pm_trace::{Material, Ray, RayKind, Rng};
use std::f32::consts::FRAC_1_PI;

pub(super) fn radiance<E: Estimator>(
    lighting: &Lighting<'_, E>,
    mut ray: Ray,
    rng: &mut Rng,
    scratch: &mut EstimatorScratch,
) -> Vec3 {
    let scene = lighting.scene;
    let mut throughput = Vec3::ONE;
    for _ in 0..=MAX_SPECULAR_BOUNCES {
        let Some(hit) = scene.intersect(&ray, f32::INFINITY, RayKind::Camera) else {
            break;
        };
        if let Material::Lambertian { albedo } = *scene.material(&hit) {
            // The caller's options exclude direct photons (KindMask::NOT_DIRECT).
            let e = direct_irradiance(scene, &hit, rng) + lighting.photon_irradiance(&hit, scratch);
            return throughput * (scene.emission(&hit) + albedo * FRAC_1_PI * e);
        }
        let Some((next, factor)) = specular_bounce(scene, &hit, &ray, rng) else {
            break;
        };
        throughput *= factor;
        ray = next;
    }
    Vec3::ZERO
}
