//! Visualize: specular bounces from the eye, then the photon-map estimate at the first
//! diffuse hit.

use super::Lighting;
use super::scatter::{MAX_SPECULAR_BOUNCES, specular_bounce};
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
            let e = lighting.photon_irradiance(&hit, scratch);
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
