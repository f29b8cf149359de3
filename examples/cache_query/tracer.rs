//! A renderer author's own final gather, written outside the crates with public items only:
//! its own camera loop, shadow rays and gather rays, reading the library's photon cache through
//! `RadianceCache::radiance_at` at each gather ray's diffuse hit.
//!
//! Shared by `examples/cache_query.rs` and `tests/cache_query.rs` (included by `#[path]`).
//!
//! What it computes at a camera ray's first diffuse hit x, as the built-in final gather does:
//! emission seen on the way, `ρ/π · (E_direct + E_caustic)` with one shadow ray per light and
//! the caustic photons of x's map read by the renderer's estimator, plus `ρ` times the mean of
//! cosine-sampled gather rays, each carrying the cache's `ρ/π · E` at its diffuse hit y (through
//! mirrors and glass), or, when y lies within the corner distance of x, one more bounce there
//! (Jensen's extra bounce, as the built-in takes it).
//!
//! Where it differs from the built-in, on purpose (each difference is unbiased, so the two agree
//! in expectation, not bit for bit): gather directions are independent uniform numbers, not
//! stratified; direct light is carried by shadow rays alone (the built-in weighs them against
//! gather rays that hit a light by multiple importance sampling; here a gather ray's emission
//! is not counted); random streams are its own. Not covered: glossy surfaces (the built-in
//! gathers through a glossy BSDF and takes an extra bounce at a glossy y; this tracer reads
//! every non-delta surface as Lambertian with `Scene::albedo_at`).

use photon_maps::kdtree::KindMask;
use photon_maps::render::core::{follow_delta_bounces, follow_delta_bounces_from, passes_through};
use photon_maps::render::glam::{Vec2, Vec3};
use photon_maps::render::source::direct_irradiance;
use photon_maps::render::{
    CacheQuery, Estimator, EstimatorOptions, EstimatorScratch, Image, MapView, QueryMap, RadianceCache,
    RenderError, SurfacePoint,
};
use photon_maps::trace::sampling::cosine_hemisphere;
use photon_maps::trace::{Hit, PhotonMaps, Ray, RayKind, Rng, Scene};
use rayon::prelude::*;
use std::f32::consts::FRAC_1_PI;

/// What the tracer reads: the scene, its photon maps and the cache built from them, and the
/// estimator of the caustics with its options.
pub struct CacheTracer<'a, E> {
    /// The scene.
    pub scene: &'a Scene,
    /// The photon maps the cache was built from (their polygons bound the caustic estimate).
    pub maps: &'a PhotonMaps,
    /// The irradiance cache.
    pub cache: &'a RadianceCache,
    /// The estimator of the caustics at x.
    pub estimator: &'a E,
    /// Its options (the caustic trees are read with every photon kind).
    pub options: EstimatorOptions,
    /// Gather rays per camera sample.
    pub gather_rays: u32,
    /// A gather ray's diffuse hit closer than this (metres) takes one more bounce.
    pub corner: f32,
}

/// Image size, samples and seed of a render.
#[derive(Clone, Copy, Debug)]
pub struct Shot {
    /// Pixels across.
    pub width: u32,
    /// Pixels down.
    pub height: u32,
    /// Jittered camera samples per pixel.
    pub samples: u32,
    /// The seed of every random stream (one per pixel sample).
    pub seed: u64,
}

impl<E: Estimator> CacheTracer<'_, E> {
    /// The image of `shot`, rows in parallel (one scratch per worker); the same for any
    /// number of threads.
    pub fn render(&self, shot: Shot) -> Result<Image, RenderError> {
        let (w, h) = (shot.width as usize, shot.height as usize);
        let mut pixels = vec![Vec3::ZERO; w * h];
        let aspect = shot.width as f32 / shot.height as f32;
        let camera = self.scene.camera();
        pixels
            .par_chunks_mut(w)
            .enumerate()
            .for_each_init(EstimatorScratch::new, |scratch, (y, row)| {
                for (x, pixel) in row.iter_mut().enumerate() {
                    let index = (y * w + x) as u64;
                    let mut sum = Vec3::ZERO;
                    for s in 0..shot.samples {
                        let mut rng = Rng::new(shot.seed, index * u64::from(shot.samples) + u64::from(s));
                        let u = (x as f32 + rng.next_f32()) / w as f32;
                        let v = (y as f32 + rng.next_f32()) / h as f32;
                        sum += self.camera_sample(camera.ray(u, v, aspect), &mut rng, scratch);
                    }
                    *pixel = sum / shot.samples as f32;
                }
            });
        Image::from_pixels(shot.width, shot.height, pixels)
    }

    /// Radiance along a camera ray: emission seen through mirrors and glass, and at the first
    /// diffuse hit its emission plus the gathered reflection.
    fn camera_sample(&self, ray: Ray, rng: &mut Rng, scratch: &mut EstimatorScratch) -> Vec3 {
        let scene = self.scene;
        let mut seen = Vec3::ZERO;
        let vertex = follow_delta_bounces(scene, ray, RayKind::Camera, rng, |hit, _, throughput, _| {
            if passes_through(scene.material(hit)) {
                seen += throughput * scene.emission(hit);
            }
        });
        let Some(vertex) = vertex else {
            return seen;
        };
        let reflected = self.reflected(&vertex.hit, self.gather_rays, self.corner, rng, scratch);
        seen + vertex.throughput * (scene.emission(&vertex.hit) + reflected)
    }

    /// Radiance reflected at the diffuse `hit`: direct light by shadow rays, caustics from the
    /// caustic photons, and `rays` cosine-sampled gather rays for the rest.
    fn reflected(
        &self,
        hit: &Hit,
        rays: u32,
        corner: f32,
        rng: &mut Rng,
        scratch: &mut EstimatorScratch,
    ) -> Vec3 {
        let scene = self.scene;
        let shading = scene.shading_normal_at(hit);
        let e = direct_irradiance(scene, hit, rng) + self.caustics(hit, shading, scratch);
        let mut indirect = Vec3::ZERO;
        for _ in 0..rays {
            let u = Vec2::new(rng.next_f32(), rng.next_f32()).min(Vec2::splat(1.0 - f32::EPSILON));
            let direction = cosine_hemisphere(shading, u);
            // A direction below the geometric surface carries nothing (no ray leaves through it).
            if direction.dot(hit.normal) <= 0.0 {
                continue;
            }
            indirect += self.gather(hit, scene.spawn_ray(hit, direction), corner, rng, scratch);
        }
        scene.albedo_at(hit) * (FRAC_1_PI * e + indirect / rays as f32)
    }

    /// Radiance a gather ray leaving `from` carries back: through mirrors and glass to a
    /// diffuse hit y, then the cache's answer at y (or one more bounce when y is within
    /// `corner` of the origin).
    fn gather(
        &self,
        from: &Hit,
        ray: Ray,
        corner: f32,
        rng: &mut Rng,
        scratch: &mut EstimatorScratch,
    ) -> Vec3 {
        let vertex =
            follow_delta_bounces_from(self.scene, Some(from), ray, RayKind::Other, rng, |_, _, _, _| {});
        let Some(vertex) = vertex else {
            return Vec3::ZERO;
        };
        if vertex.distance < corner {
            return vertex.throughput * self.reflected(&vertex.hit, 1, 0.0, rng, scratch);
        }
        let hit = &vertex.hit;
        let query = CacheQuery {
            position: hit.position,
            normal: hit.normal,
            map: QueryMap::Part(hit.part),
            albedo: self.scene.albedo_at(hit),
        };
        match self.cache.radiance_at(&query, scratch) {
            Some(answer) => vertex.throughput * answer.radiance,
            None => Vec3::ZERO,
        }
    }

    /// Caustic irradiance at `hit`: the estimator on the cache's caustic tree of the hit's
    /// map, bounded by that map's polygons.
    fn caustics(&self, hit: &Hit, shading: Vec3, scratch: &mut EstimatorScratch) -> Vec3 {
        let Some(map) = self.cache.map_of(hit.part) else {
            return Vec3::ZERO;
        };
        let (Some(tree), Some(photon_map)) = (self.cache.caustic_tree(map), self.maps.get(map)) else {
            return Vec3::ZERO;
        };
        let at = SurfacePoint {
            position: hit.position,
            normal: shading,
            front_face: hit.front_face,
        };
        let view = MapView {
            tree,
            polygons: photon_map.geometry(),
        };
        let options = EstimatorOptions {
            kinds: KindMask::ALL,
            ..self.options
        };
        self.estimator.irradiance(at, view, &options, scratch)
    }
}
