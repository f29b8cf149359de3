//! PathTrace: an unbiased path tracer with next-event estimation. Emission is counted only on
//! camera rays and after specular bounces (diffuse bounces get it from the shadow rays), so
//! nothing is counted twice; Russian roulette ends long paths without bias.

use super::direct::direct_irradiance_shaded;
use super::scatter::specular_bounce;
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
    let mut count_emission = true;
    let mut kind = RayKind::Camera;
    for depth in 0..MAX_DEPTH {
        let Some(hit) = scene.intersect(&ray, f32::INFINITY, kind) else {
            break;
        };
        if count_emission {
            radiance += throughput * scene.emission(&hit);
        }
        match *scene.material(&hit) {
            Material::Lambertian { .. } => {
                let albedo = scene.albedo_at(&hit);
                let shading = scene.shading_normal_at(&hit);
                radiance +=
                    throughput * albedo * FRAC_1_PI * direct_irradiance_shaded(scene, &hit, shading, rng);
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
                kind = RayKind::Other;
            }
            _ => {
                let Some((next, factor)) = specular_bounce(scene, &hit, &ray, rng) else {
                    break;
                };
                throughput *= factor;
                ray = next;
                count_emission = true;
            }
        }
        if depth >= ROULETTE_AFTER {
            let survive = throughput.max_element().min(0.95);
            if survive <= 0.0 || rng.next_f32() >= survive {
                break;
            }
            throughput /= survive;
        }
    }
    radiance
}
