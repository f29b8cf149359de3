//! PathTrace: an unbiased path tracer with next-event estimation combined with the diffuse
//! bounces by multiple importance sampling (power heuristic); Russian roulette ends long paths.

use super::direct::{bsdf_emission_weight, direct_irradiance_mis, direct_irradiance_shaded, mis_enabled};
use super::scatter::{MAX_SPECULAR_BOUNCES, specular_bounce};
use glam::{Vec2, Vec3};
use pm_trace::sampling::cosine_hemisphere;
use pm_trace::{Material, Ray, RayKind, Rng, Scene};
use std::f32::consts::FRAC_1_PI;

/// Longest path (a safety net; Russian roulette ends paths long before).
const MAX_DEPTH: u32 = 256;
/// Bounces before Russian roulette starts.
const ROULETTE_AFTER: u32 = 3;

pub(super) fn radiance(scene: &Scene, mut ray: Ray, rng: &mut Rng) -> Vec3 {
    let mut radiance = Vec3::ZERO;
    let mut throughput = Vec3::ONE;
    // Emission found by the ray is counted in full on camera rays and after specular bounces;
    // after a diffuse bounce from `(x, pdf)` it is weighted against the shadow rays there (by
    // multiple importance sampling, when every light allows it; else not counted at all, the
    // shadow rays having carried it).
    let mut count_emission = true;
    let mut diffuse_from: Option<(Vec3, f32)> = None;
    let mis = mis_enabled(scene);
    let mut kind = RayKind::Camera;
    // Until the first diffuse vertex the path is the camera's delta chain, which every mode
    // follows alike: at most MAX_SPECULAR_BOUNCES bounces, and no Russian roulette.
    let mut past_first_diffuse = false;
    for depth in 0..MAX_DEPTH {
        let Some(hit) = scene.intersect(&ray, f32::INFINITY, kind) else {
            break;
        };
        if count_emission {
            radiance += throughput * scene.emission(&hit);
        } else if let Some((from, pdf)) = diffuse_from {
            let le = scene.emission(&hit);
            if le != Vec3::ZERO {
                radiance +=
                    throughput * le * bsdf_emission_weight(scene, from, ray.direction, hit.t, 1.0, pdf);
            }
        }
        match *scene.material(&hit) {
            Material::Lambertian { .. } => {
                let albedo = scene.albedo_at(&hit);
                let shading = scene.shading_normal_at(&hit);
                let direct = if mis {
                    direct_irradiance_mis(scene, &hit, shading, 1.0, rng)
                } else {
                    direct_irradiance_shaded(scene, &hit, shading, rng)
                };
                radiance += throughput * albedo * FRAC_1_PI * direct;
                // Cosine sampling about the shading normal: f · cos / pdf = (albedo / π) · cos /
                // (cos / π) = albedo. A direction below the geometric surface (possible where
                // the shading normal leans away from it, near the terminator) ends the path
                // rather than leaking through the surface.
                let direction = cosine_hemisphere(shading, Vec2::new(rng.next_f32(), rng.next_f32()));
                if direction.dot(hit.normal) <= 0.0 {
                    break;
                }
                throughput *= albedo;
                ray = scene.spawn_ray(&hit, direction);
                count_emission = false;
                diffuse_from = mis.then(|| (hit.position, shading.dot(direction).max(0.0) * FRAC_1_PI));
                kind = RayKind::Other;
                past_first_diffuse = true;
            }
            _ => {
                if !past_first_diffuse && depth >= MAX_SPECULAR_BOUNCES {
                    break;
                }
                let Some((next, factor)) = specular_bounce(scene, &hit, &ray, rng) else {
                    break;
                };
                throughput *= factor;
                ray = next;
                count_emission = true;
                diffuse_from = None;
            }
        }
        if past_first_diffuse && depth >= ROULETTE_AFTER {
            let survive = throughput.max_element().min(0.95);
            if survive <= 0.0 || rng.next_f32() >= survive {
                break;
            }
            throughput /= survive;
        }
    }
    radiance
}
