//! PhotonMap and ShadowRays: specular bounces from the eye, then at the first diffuse hit the
//! photon-map estimate, plus (for ShadowRays) direct light by shadow rays.

use super::scatter::{MAX_SPECULAR_BOUNCES, specular_bounce};
use super::{Lighting, direct_irradiance};
use crate::{Estimator, EstimatorScratch};
use glam::Vec3;
use pm_trace::{Material, Ray, RayKind, Rng};
use std::f32::consts::FRAC_1_PI;

/// Radiance along a camera ray. With `shadow_rays` the direct light comes from shadow rays to
/// the lights, and the caller's options must exclude direct photons (`KindMask::NOT_DIRECT`).
pub(super) fn radiance<E: Estimator>(
    lighting: &Lighting<'_, E>,
    mut ray: Ray,
    rng: &mut Rng,
    scratch: &mut EstimatorScratch,
    shadow_rays: bool,
) -> Vec3 {
    let scene = lighting.scene;
    let mut throughput = Vec3::ONE;
    let mut distance = 0.0f32;
    for _ in 0..=MAX_SPECULAR_BOUNCES {
        let Some(hit) = scene.intersect(&ray, f32::INFINITY, RayKind::Camera) else {
            break;
        };
        distance += hit.t;
        if let Material::Lambertian { .. } = *scene.material(&hit) {
            // The pixel's footprint: its width at this distance, stretched on a tilted surface
            // (by the square root of 1/cos, between the ellipse's two axes).
            let cos = (-ray.direction.dot(hit.normal)).max(1e-3);
            let albedo = scene.albedo_over(&hit, distance * lighting.pixel_angle / cos.sqrt());
            let mut e = lighting.photon_irradiance(&hit, scratch);
            if shadow_rays {
                e += direct_irradiance(scene, &hit, rng);
            }
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
