//! A path-traced bounce: from the camera path's first diffuse vertex, an unbiased path tracer
//! with next-event estimation combined with the diffuse bounces by multiple importance sampling
//! (power heuristic); Russian roulette ends long paths. With the render core's delta chain in
//! front of it, the path-trace mode: the reference every estimator is measured against.

use super::direct::{
    Mis, bsdf_emission_weight, direct_irradiance_mis, direct_irradiance_shaded, direct_radiance_through,
    mis_enabled,
};
use crate::core::delta::specular_bounce;
use crate::core::{PathVertex, RadianceSource};
use crate::estimator::scratch::EstimatorScratch;
use glam::Vec3;
use pm_trace::bsdf::ShadingPoint;
use pm_trace::{Bsdf, Hit, Material, RayKind, Rng, Scene};
use std::f32::consts::FRAC_1_PI;

/// Longest path (a safety net; Russian roulette ends paths long before).
const MAX_DEPTH: u32 = 256;
/// Bounces before Russian roulette starts.
const ROULETTE_AFTER: u32 = 3;

/// Radiance read at a path's first diffuse vertex by path tracing from there.
#[derive(Clone, Copy, Debug)]
pub struct PathTraced<'a> {
    /// The scene.
    pub scene: &'a Scene,
}

impl RadianceSource for PathTraced<'_> {
    fn scene(&self) -> &Scene {
        self.scene
    }

    /// The radiance a path traced onwards from `vertex` brings back (without its emission).
    fn reflected(&self, vertex: &PathVertex, rng: &mut Rng, _: &mut EstimatorScratch) -> Vec3 {
        let vertex = PathVertex {
            throughput: Vec3::ONE,
            ..*vertex
        };
        trace_from(self.scene, &vertex, VertexEmission::Left, rng)
    }

    /// Path tracing accumulates along its own path, each term times the throughput so far.
    fn carried(&self, vertex: &PathVertex, rng: &mut Rng, _: &mut EstimatorScratch) -> Vec3 {
        trace_from(self.scene, vertex, VertexEmission::Counted, rng)
    }
}

/// Whether the path's first vertex's own emission is in what [`trace_from`] returns.
#[derive(Clone, Copy, PartialEq, Eq)]
enum VertexEmission {
    Counted,
    Left,
}

/// The radiance a path brings back from `vertex` on, continuing with its throughput; its depth
/// counts the delta bounces before it.
fn trace_from(scene: &Scene, vertex: &PathVertex, first: VertexEmission, rng: &mut Rng) -> Vec3 {
    let mut ray = vertex.ray;
    let mut hit = vertex.hit;
    let mut radiance = Vec3::ZERO;
    let mut throughput = vertex.throughput;
    // Emission found by the ray is counted in full at the first vertex and after specular
    // bounces; after a diffuse bounce from `(x, pdf)` it is weighted against the shadow rays
    // there (by multiple importance sampling, when every light allows it; else not counted at
    // all, the shadow rays having carried it).
    let mut count_emission = first == VertexEmission::Counted;
    let mut diffuse_from: Option<(Vec3, f32)> = None;
    let mis = mis_enabled(scene);
    for depth in vertex.bounces..MAX_DEPTH {
        if depth > vertex.bounces {
            let Some(next) = scene.intersect_from(&hit, &ray, f32::INFINITY, RayKind::Other) else {
                break;
            };
            hit = next;
        }
        if count_emission {
            radiance += throughput * scene.emission(&hit);
        } else if let Some((from, pdf)) = diffuse_from {
            let le = scene.emission(&hit);
            if le != Vec3::ZERO {
                radiance +=
                    throughput * le * bsdf_emission_weight(scene, from, ray.direction, hit.t, 1.0, pdf);
            }
        }
        let material = scene.material(&hit);
        if material.lobes().has_non_delta() {
            let at = scene.shading_point(&hit);
            let vertex = Reflecting {
                hit: &hit,
                at: &at,
                material,
                wo: -ray.direction,
            };
            radiance += direct_light(scene, &vertex, throughput, mis, rng);
            // For a Lambertian surface, cosine sampling about the shading normal: weight
            // f · cos / pdf = (albedo / π) · cos / (cos / π) = albedo. A direction below the
            // geometric surface (possible where the shading normal leans away from it, near
            // the terminator) ends the path rather than leaking through the surface.
            let Some(sample) = material.sample_from(&at, -ray.direction, rng) else {
                break;
            };
            if sample.wi.dot(hit.normal) <= 0.0 {
                break;
            }
            throughput *= sample.weight;
            ray = scene.spawn_ray(&hit, sample.wi);
            if sample.lobe.has_delta() {
                count_emission = true;
                diffuse_from = None;
            } else {
                count_emission = false;
                diffuse_from = mis.then_some((hit.position, sample.pdf));
            }
        } else {
            let Some((next, factor)) = specular_bounce(scene, &hit, &ray, rng) else {
                break;
            };
            throughput *= factor;
            ray = next;
            count_emission = true;
            diffuse_from = None;
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

/// Radiance reflected at a non-delta `hit` towards `wo` straight from the lights, times the
/// path's `throughput` (multiplied in the order the images' bits were made with). A BSDF with a
/// glossy lobe is evaluated per light sample (`f · L · cos`, weighted against its own
/// density); one whose non-delta part is diffuse reflects `ρ_d/π` times the irradiance, read
/// with the cosine density's weights, which for a Lambertian lobe is the same sum.
fn direct_light(scene: &Scene, vertex: &Reflecting<'_>, throughput: Vec3, mis: bool, rng: &mut Rng) -> Vec3 {
    let Reflecting {
        hit,
        at,
        material,
        wo,
    } = *vertex;
    if material.lobes().has_glossy() {
        let weights = if mis { Mis::Weighted } else { Mis::ShadowRaysOnly };
        return throughput * direct_radiance_through(scene, hit, at, material, wo, weights, rng);
    }
    let direct = if mis {
        direct_irradiance_mis(scene, hit, at.shading, 1.0, rng)
    } else {
        direct_irradiance_shaded(scene, hit, at.shading, rng)
    };
    throughput * material.diffuse_albedo(at) * FRAC_1_PI * direct
}

/// A non-delta path vertex as its direct light is read: the hit, its shading point, its
/// material and the direction back along the path.
#[derive(Clone, Copy)]
struct Reflecting<'a> {
    hit: &'a Hit,
    at: &'a ShadingPoint,
    material: &'a Material,
    wo: Vec3,
}
