//! A final gather read at the first diffuse hit x: direct light by shadow rays MIS-combined
//! with the gather rays, caustics from caustic photons, and indirect light by the gather rays
//! into a cache. What the gather reads (k-nearest or a pass's fixed volumes) is a
//! [`GatherReads`].
//!
//! # Glossy surfaces
//!
//! At a first hit x whose BSDF has a glossy lobe the gather goes through the BSDF: shadow rays
//! evaluate `f(wo, wi)` per light (power heuristic against the BSDF's density), the caustic
//! photons are read with the weight `f(wo, wi_p)`, and the gather rays are sampled from the
//! BSDF (stratified numbers, each carrying `f cos / pdf`), not from the cosine. The irradiance
//! cache is a diffuse quantity: it is read only where a gather ray lands on a surface without
//! a glossy lobe (as `ρ_d/π · E`). A gather ray that lands on a glossy surface y takes one
//! extra bounce there instead, through y's BSDF (the bounce Jensen's corner rule takes near
//! x); inside that bounce its rays read the cache wherever they land, so a glossy y seen
//! from a glossy y' reads only its diffuse lobe.

use super::direct::{
    Mis, bsdf_emission_weight, direct_irradiance_mis, direct_irradiance_shaded, direct_radiance_through,
    mis_enabled,
};
use super::photon_map::estimate_at;
use crate::cache::RadianceCache;
use crate::core::{PathVertex, RadianceSource, follow_delta_bounces_from};
use crate::error::RenderError;
use crate::estimator::Estimator;
use crate::estimator::options::EstimatorOptions;
use crate::estimator::point::MapView;
use crate::estimator::scratch::EstimatorScratch;
use crate::estimator::weight::{BsdfWeight, Irradiance, PhotonWeight};
use glam::{Vec2, Vec3};
use pm_kdtree::KindMask;
use pm_trace::sampling::cosine_hemisphere;
use pm_trace::{Bsdf, Hit, PhotonMaps, Ray, RayKind, Rng, Scene};
use std::f32::consts::FRAC_1_PI;

/// Parameters of [`crate::mode::Mode::FinalGather`].
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct FinalGatherOptions {
    /// Cosine-weighted gather rays per camera sample at its first diffuse hit (stratified over
    /// the hemisphere; default 64, for one camera sample per pixel). With several samples per
    /// pixel, fewer rays each do better at equal time: on the report's four scenes (125², 100k
    /// photons, one thread, 1–15 CPU-s) 16 samples × 4 rays had the lowest error in 19 of 20
    /// cells, 1.8–2.4× below 1 × 64 at 15 s; the render example's default is 16 × 4
    /// (the repository's `docs/final-gather-sweep.md`).
    pub gather_rays: u32,
    /// Irradiance is precomputed at one photon in `cache_every` of each map, from the others
    /// (at least 2; default 4, as in Christensen's paper).
    pub cache_every: u32,
    /// Jensen's extra bounce: a gather ray whose diffuse hit lies closer than this (metres) to
    /// its origin does not read the cache there but takes direct light, caustics and one more
    /// cosine-weighted ray into the cache; `Some(0.0)`: never. `None` (the default):
    /// [`Self::CORNER_FRACTION`] of the scene's bounding-box diagonal
    /// ([`Self::corner_distance_in`]).
    ///
    /// Near a corner, a fold or an object resting on a floor, a gather ray's hit lies within
    /// the cache's own gather volume of its origin, and the cache's estimate there is smoothed
    /// over the very neighbourhood whose light is changing fastest. Measured in the convergence
    /// study (125², 4 gather rays × 16 samples per pixel per pass, 30 s of CPU): the error of
    /// the mean of the passes falls from 0.0134 to 0.0058 on the accordion and from 0.0175 to
    /// 0.0134 on the Cornell box with the extra bounce within 5 cm, for about 5 % more time;
    /// on the rooms by 8–9 %. Twice or three times that distance measured the same. Each
    /// gather ray takes at most one extra bounce, so the cost is at most about twice the
    /// gather's; a scene whose bounds dwarf its detail (a vast ground plane) may want an
    /// explicit distance.
    pub corner_distance: Option<f32>,
}

impl Default for FinalGatherOptions {
    fn default() -> Self {
        FinalGatherOptions {
            gather_rays: 64,
            cache_every: 4,
            corner_distance: None,
        }
    }
}

impl FinalGatherOptions {
    /// The most gather rays per camera sample (2¹⁴).
    pub const MAX_GATHER_RAYS: u32 = 1 << 14;

    /// The default corner distance's share of the scene's bounding-box diagonal (5 %: 5 cm in
    /// the Cornell box, 9 cm in the accordion).
    pub const CORNER_FRACTION: f32 = 0.05;

    /// The corner distance in a scene bounded by `bounds`: the one given, or
    /// [`Self::CORNER_FRACTION`] of the diagonal.
    pub fn corner_distance_in(&self, bounds: &pm_geom::Aabb) -> f32 {
        self.corner_distance
            .unwrap_or(Self::CORNER_FRACTION * bounds.diagonal())
    }

    /// Checks that there is at least one gather ray (at most [`Self::MAX_GATHER_RAYS`]), that
    /// `cache_every` is at least 2 and that a corner distance given is finite and not
    /// negative.
    pub fn validate(&self) -> Result<(), RenderError> {
        if self.gather_rays == 0 || self.gather_rays > Self::MAX_GATHER_RAYS {
            return Err(RenderError::BadFinalGather(format!(
                "{} gather rays: expected 1 to {}",
                self.gather_rays,
                Self::MAX_GATHER_RAYS
            )));
        }
        if self.cache_every < 2 {
            return Err(RenderError::BadFinalGather(format!(
                "cache points every {} photons: expected 2 or more (the others estimate their irradiance)",
                self.cache_every
            )));
        }
        if let Some(d) = self.corner_distance
            && !(d >= 0.0 && d.is_finite())
        {
            return Err(RenderError::BadFinalGather(format!(
                "corner distance {d} must be finite and not negative"
            )));
        }
        Ok(())
    }
}

/// What a final gather reads besides its rays: the caustics at a diffuse point and the cached
/// outgoing radiance at a gather ray's diffuse hit. The one-shot mode reads k-nearest
/// estimates ([`CacheReads`]); a progressive pass reads fixed-volume ones.
pub trait GatherReads: Sync {
    /// The scene.
    fn scene(&self) -> &Scene;
    /// The gather's parameters.
    fn options(&self) -> &FinalGatherOptions;
    /// The estimate with `weight` at `hit` from the photons of kind caustic of its map (with
    /// [`Irradiance`]: their irradiance).
    fn caustics(&self, hit: &Hit, weight: &dyn PhotonWeight, scratch: &mut EstimatorScratch) -> Vec3;
    /// Outgoing radiance (no emission) of the diffuse `hit` of a gather ray.
    fn cached_radiance(&self, hit: &Hit, scratch: &mut EstimatorScratch) -> Vec3;
}

/// The one-shot mode's reads: the estimator on the cache's caustic trees (split as the photon
/// maps are), and the cache's nearest point.
#[derive(Clone, Copy, Debug)]
pub struct CacheReads<'a, E> {
    /// The scene.
    pub scene: &'a Scene,
    /// Its photon maps (their polygons bound the caustic estimates' areas).
    pub maps: &'a PhotonMaps,
    /// The estimator of the caustics.
    pub estimator: &'a E,
    /// Its options (photons of every kind are read from the caustic trees).
    pub options: &'a EstimatorOptions,
    /// The irradiance cache, built from `maps`.
    pub cache: &'a RadianceCache,
    /// The gather's parameters.
    pub gather: FinalGatherOptions,
}

impl<E: Estimator> GatherReads for CacheReads<'_, E> {
    fn scene(&self) -> &Scene {
        self.scene
    }

    fn options(&self) -> &FinalGatherOptions {
        &self.gather
    }

    fn caustics(&self, hit: &Hit, weight: &dyn PhotonWeight, scratch: &mut EstimatorScratch) -> Vec3 {
        let map_id = self.maps.map_of(hit.part);
        let (Some(tree), Some(map)) = (self.cache.caustic_tree(map_id), self.maps.get(map_id)) else {
            return Vec3::ZERO;
        };
        let options = EstimatorOptions {
            kinds: KindMask::ALL,
            ..*self.options
        };
        let view = MapView {
            tree,
            polygons: map.geometry(),
        };
        estimate_at(self.scene, self.estimator, view, &options, weight, hit, scratch)
    }

    fn cached_radiance(&self, hit: &Hit, scratch: &mut EstimatorScratch) -> Vec3 {
        self.cache.radiance(self.scene, hit, scratch)
    }
}

/// The `i`-th of `n` stratified points of the unit square: cells of a grid of ⌈√n⌉ columns
/// and enough rows, shifted by `offset` (uniform over the cells) so that each point alone is
/// uniform over the square even when `n` does not fill the grid, and jittered within its cell.
fn stratified(i: u32, n: u32, offset: u32, rng: &mut Rng) -> Vec2 {
    let columns = (n as f32).sqrt().ceil().max(1.0) as u32;
    let rows = n.div_ceil(columns);
    let cell = (i + offset) % (columns * rows);
    Vec2::new(
        ((cell % columns) as f32 + rng.next_f32()) / columns as f32,
        ((cell / columns) as f32 + rng.next_f32()) / rows as f32,
    )
    .min(Vec2::splat(1.0 - f32::EPSILON))
}

/// The sample count the gather rays enter the power heuristic with, against one shadow ray
/// per light. Any weights that sum to one keep the estimate unbiased; with the true count N
/// (say 64) the gather rays would take half the direct light of a small light that few of them
/// hit, which measured twice the error of shadow rays alone on the Cornell box; with 1 each
/// strategy keeps the light where its density is the larger.
const MIS_GATHER_COUNT: f32 = 1.0;

/// How a gather ray weighs emission at its first hit: `None` (shadow rays carry all direct
/// light), or the multiple-importance weight against them, from the origin x, the ray's
/// density and the number of gather rays.
#[derive(Clone, Copy)]
struct EmissionWeight {
    from: Vec3,
    pdf: f32,
    rays: f32,
}

/// Radiance a gather ray carries back: through specular bounces to a diffuse hit y, then the
/// cache at y (or, when y lies within `corner` metres of the ray's origin, one more bounce).
/// Emission met straight away counts with its multiple-importance weight `mis` (and not at
/// all without one); emission after specular bounces does not count: the caustic photons at
/// the gather's origin carry it.
fn gather<G: GatherReads>(
    source: &G,
    from: &Hit,
    ray: Ray,
    corner: f32,
    mis: Option<EmissionWeight>,
    rng: &mut Rng,
    scratch: &mut EstimatorScratch,
) -> Vec3 {
    let scene = source.scene();
    let mut emitted = Vec3::ZERO;
    let vertex = follow_delta_bounces_from(
        scene,
        Some(from),
        ray,
        RayKind::Other,
        rng,
        |hit, ray, _, bounce| {
            if bounce == 0
                && let Some(w) = mis
            {
                let le = scene.emission(hit);
                if le != Vec3::ZERO {
                    emitted = le * bsdf_emission_weight(scene, w.from, ray.direction, hit.t, w.rays, w.pdf);
                }
            }
        },
    );
    let Some(vertex) = vertex else {
        return emitted;
    };
    // The cache is a diffuse quantity: a glossy y takes the extra bounce too (through its
    // BSDF), as a y close to x does; within that bounce (`corner` 0) y reads the cache.
    let glossy = corner > 0.0 && scene.material(&vertex.hit).lobes().has_glossy();
    if vertex.distance < corner || glossy {
        let wo = -vertex.ray.direction;
        return emitted + vertex.throughput * bounce(source, &vertex.hit, wo, 1, 0.0, rng, scratch);
    }
    emitted + vertex.throughput * source.cached_radiance(&vertex.hit, scratch)
}

/// Reflected radiance at a non-delta `hit` towards `wo` (without its emission): a surface
/// with a glossy lobe by [`glossy_bounce`], any other by [`diffuse_bounce`].
fn bounce<G: GatherReads>(
    source: &G,
    hit: &Hit,
    wo: Vec3,
    rays: u32,
    corner: f32,
    rng: &mut Rng,
    scratch: &mut EstimatorScratch,
) -> Vec3 {
    if source.scene().material(hit).lobes().has_glossy() {
        glossy_bounce(source, hit, wo, rays, corner, rng, scratch)
    } else {
        diffuse_bounce(source, hit, rays, corner, rng, scratch)
    }
}

/// Reflected radiance at `hit` towards `wo` through a BSDF with a glossy lobe: direct light
/// by shadow rays evaluating `f` (MIS-weighted against the BSDF's density), caustics read
/// with the weight `f(wo, wi_p)`, and `rays` gather rays sampled from the BSDF (stratified
/// numbers, weight `f cos / pdf`) for the rest.
fn glossy_bounce<G: GatherReads>(
    source: &G,
    hit: &Hit,
    wo: Vec3,
    rays: u32,
    corner: f32,
    rng: &mut Rng,
    scratch: &mut EstimatorScratch,
) -> Vec3 {
    let scene = source.scene();
    let material = scene.material(hit);
    let at = scene.shading_point(hit);
    let mis = mis_enabled(scene);
    let weights = if mis { Mis::Weighted } else { Mis::ShadowRaysOnly };
    let direct = direct_radiance_through(scene, hit, &at, material, wo, weights, rng);
    let caustics = source.caustics(hit, &BsdfWeight::new(material, at, wo), scratch);
    let mut indirect = Vec3::ZERO;
    let columns = (rays as f32).sqrt().ceil().max(1.0) as u32;
    let cells = columns * rays.div_ceil(columns);
    let offset = ((rng.next_f32() * cells as f32) as u32).min(cells - 1);
    for i in 0..rays {
        let u = stratified(i, rays, offset, rng);
        let Some(sample) = material.sample(&at, wo, u, rng.next_f32()) else {
            continue;
        };
        if sample.wi.dot(hit.normal) <= 0.0 {
            continue;
        }
        scratch.gather_rays += 1;
        let weight = (mis && !sample.lobe.has_delta()).then_some(EmissionWeight {
            from: hit.position,
            pdf: sample.pdf,
            rays: MIS_GATHER_COUNT,
        });
        let ray = scene.spawn_ray(hit, sample.wi);
        indirect += sample.weight * gather(source, hit, ray, corner, weight, rng, scratch);
    }
    direct + caustics + indirect / rays as f32
}

/// Reflected radiance at a diffuse `hit` (without its emission): direct light by shadow rays,
/// caustics from the caustic photons, and `rays` gather rays for the rest (those that land
/// within `corner` metres taking one more bounce).
fn diffuse_bounce<G: GatherReads>(
    source: &G,
    hit: &Hit,
    rays: u32,
    corner: f32,
    rng: &mut Rng,
    scratch: &mut EstimatorScratch,
) -> Vec3 {
    let scene = source.scene();
    let albedo = scene.albedo_at(hit);
    let shading = scene.shading_normal_at(hit);
    let mis = mis_enabled(scene);
    let direct = if mis {
        direct_irradiance_mis(scene, hit, shading, MIS_GATHER_COUNT, rng)
    } else {
        direct_irradiance_shaded(scene, hit, shading, rng)
    };
    let e = direct + source.caustics(hit, &Irradiance, scratch);
    let mut indirect = Vec3::ZERO;
    let columns = (rays as f32).sqrt().ceil().max(1.0) as u32;
    let cells = columns * rays.div_ceil(columns);
    let offset = ((rng.next_f32() * cells as f32) as u32).min(cells - 1);
    for i in 0..rays {
        // Cosine sampling: f · cos / pdf = ρ; a direction below the geometric surface carries
        // nothing (as in the path tracer), so no gather ray leaves through the surface.
        let direction = cosine_hemisphere(shading, stratified(i, rays, offset, rng));
        if direction.dot(hit.normal) <= 0.0 {
            continue;
        }
        scratch.gather_rays += 1;
        let weight = mis.then(|| EmissionWeight {
            from: hit.position,
            pdf: shading.dot(direction).max(0.0) * FRAC_1_PI,
            rays: MIS_GATHER_COUNT,
        });
        indirect += gather(
            source,
            hit,
            scene.spawn_ray(hit, direction),
            corner,
            weight,
            rng,
            scratch,
        );
    }
    albedo * (FRAC_1_PI * e + indirect / rays as f32)
}

/// A final gather at the first diffuse vertex, reading through `G`.
#[derive(Clone, Copy, Debug)]
pub struct FinalGatherSource<G> {
    /// What the gather reads.
    pub reads: G,
}

impl<G: GatherReads> RadianceSource for FinalGatherSource<G> {
    fn scene(&self) -> &Scene {
        self.reads.scene()
    }

    fn reflected(&self, vertex: &PathVertex, rng: &mut Rng, scratch: &mut EstimatorScratch) -> Vec3 {
        let scene = self.reads.scene();
        let options = self.reads.options();
        let corner = options.corner_distance_in(&scene.bounds());
        bounce(
            &self.reads,
            &vertex.hit,
            -vertex.ray.direction,
            options.gather_rays,
            corner,
            rng,
            scratch,
        )
    }
}
