//! Precomputed irradiance (Christensen 1999): irradiance estimated once at one photon in n of
//! each map, then read by a final gather's rays as one nearest-point lookup in the hit's own map.

use crate::error::RenderError;
use crate::estimator::Estimator;
use crate::estimator::options::EstimatorOptions;
use crate::estimator::point::MapView;
use crate::estimator::scratch::EstimatorScratch;
use build::{cache_points, split_cache_points};
use caustics::caustic_trees;
use glam::Vec3;
use pm_kdtree::{KindMask, PhotonTree};
use pm_trace::{Hit, MapAssignment, PhotonMaps, Scene};

pub(crate) mod build;
mod caustics;
pub(crate) mod points;
pub(crate) mod query;

pub use build::CachePoint;
pub use points::{CANDIDATES, IrradiancePoint, IrradiancePoints, NORMAL_AGREEMENT};
pub use query::{CacheQuery, CachedRadiance, QueryMap};

/// Irradiance precomputed at photon positions, per photon map: the radiance cache of a final
/// gather.
///
/// [`RadianceCache::build`] sets about one photon in `n` of each map aside as a cache point
/// (each photon independently with probability 1/n, by a hash of its position and index),
/// finds the surface it landed on (its normal and side) and estimates the irradiance there
/// with the renderer's own [`Estimator`] — the same estimate, with the same partition and
/// area, that the photon maps give a camera ray — from the map's *other* photons, of all
/// kinds, scaled by n/(n − 1) ([`RadianceCache::set_aside`]), leaving out the k-nearest
/// search's boundary photon
/// ([`EstimatorOptions::leave_out_boundary`]). Both choices remove a bias of order 1/k:
/// - a photon's own estimate counts the photon itself and the boundary photon, k/(k − 2)
///   too bright;
/// - a lookup answers from the *nearest* cache point, which is the nearest because no other
///   cache point lies nearer the query: were the cache points among the photons estimated
///   from, that empty neighbourhood would make the chosen estimate about one photon too dark
///   (−0.9 % at k = 100 on the lit/unlit rooms, independent of the photon count). With
///   cache points and estimating photons disjoint (independent thinnings), where the cache
///   points lie says nothing about the photons counted.
///
/// The hash takes each photon's position, so every set of photons (every pass of a consistent
/// renderer) gets its own, independent choice, and each photon is kept with probability
/// (n − 1)/n whatever the others: the scale n/(n − 1) then makes an estimate from the others
/// exactly unbiased, in every map however few its photons. (By the index alone, the same tree
/// slots were set aside in every pass, a share off 1/n by a few tenths of a percent the same
/// way every time: a consistent renderer averaging passes kept a bias of +0.2 %. Scaling by
/// each map's own count ratio instead would be unbiased only given that some photon is kept,
/// and too dark by n⁻ᴺ in a map of N photons.)
///
/// The points are kept per map as [`IrradiancePoints`]: position, normal and irradiance in
/// full precision (48 bytes a point with the index), the caustic photons apart in a tree of
/// their own per map ([`RadianceCache::caustic_tree`]).
///
/// [`RadianceCache::irradiance`] answers a query at a surface point of map `m` with the nearest
/// cache point of map `m` whose normal agrees with the query's (cosine at least
/// [`NORMAL_AGREEMENT`]); the point's irradiance stands for the query's. Because a query only
/// reads its own map, and the maps do not cross walls, no cached light leaks through one.
/// [`RadianceCache::radiance`] turns that into the outgoing radiance `ρ/π · E` of a diffuse
/// hit, what a gather ray carries back.
///
/// ```
/// use pm_render::glam::Vec3;
/// use pm_render::{Disc, EstimatorOptions, EstimatorScratch, RadianceCache};
/// use pm_trace::{Camera, CreaseAngle, Partitioner, PhotonMaps, PointLight, Ray, RayKind, Scene, Surface, TraceOptions, trace_photons};
/// use std::f32::consts::PI;
///
/// // A point light of intensity π inside a closed diffuse sphere of albedo 0.5: radiance 1
/// // everywhere inside (irradiance 2π).
/// let scene = Scene::builder()
///     .sphere(Vec3::ZERO, 1.0, Surface::diffuse(Vec3::splat(0.5)))
///     .light(PointLight::new(Vec3::ZERO, Vec3::splat(4.0 * PI * PI)))
///     .camera(Camera::new(Vec3::new(0.0, 0.0, 0.5), Vec3::NEG_Z, Vec3::Y, 1.2))
///     .build()?;
/// let partitioned = CreaseAngle::default().partition(scene)?;
/// let (scene, assignment) = (partitioned.scene(), partitioned.assignment());
/// let traced = trace_photons(scene, assignment, &TraceOptions { photons: 20_000, ..TraceOptions::default() })?;
/// let maps = PhotonMaps::build(scene, assignment, traced)?;
/// let options = EstimatorOptions::for_scene(&scene.bounds());
/// let cache = RadianceCache::build(scene, &maps, &Disc, &options, 4)?;
/// let mut scratch = EstimatorScratch::new();
/// let hit = scene.intersect(&Ray { origin: Vec3::ZERO, direction: Vec3::X }, f32::INFINITY, RayKind::Other).unwrap();
/// let l = cache.radiance(scene, &hit, &mut scratch);
/// assert!((l.x - 1.0).abs() < 0.1, "{l}"); // one lookup: within the estimate's noise
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
#[derive(Clone, Debug)]
pub struct RadianceCache {
    /// Per photon map: its irradiance points.
    points: Vec<IrradiancePoints>,
    map_of_part: Vec<u32>,
    /// Per photon map: its photons of kind caustic alone (Jensen's caustic map, split as the
    /// photon maps are), so that a caustic estimate does not wade through the others.
    caustics: Vec<PhotonTree>,
    /// Per photon map: the photons that are not cache points (dropped by
    /// [`RadianceCache::without_photons`]).
    photons: Vec<PhotonTree>,
    /// `n/(n − 1)` for one cache point in `n` photons.
    set_aside: f32,
    max_distance: f32,
}

impl RadianceCache {
    /// Precomputes irradiance at one photon in `every` of each of `maps` (at least 2), from
    /// the others, with `estimator` and `options` (whose photon kinds are replaced by all
    /// kinds, since light leaving a surface is the sum of everything arriving there, and
    /// which leave out the boundary photon). Runs on the current rayon pool; the result does
    /// not depend on the number of threads.
    pub fn build<E: Estimator>(
        scene: &Scene,
        maps: &PhotonMaps,
        estimator: &E,
        options: &EstimatorOptions,
        every: u32,
    ) -> Result<Self, RenderError> {
        options.validate()?;
        let options = EstimatorOptions {
            kinds: KindMask::ALL,
            leave_out_boundary: true,
            ..*options
        };
        let trees: Vec<&PhotonTree> = maps.trees().iter().collect();
        Self::build_with(
            scene,
            &trees,
            maps.assignment(),
            every,
            options.max_distance,
            |point, scratch| {
                let map = maps.map(point.map as u32);
                let view = MapView {
                    tree: point.photons,
                    polygons: map.geometry(),
                };
                estimator.irradiance(point.at, view, &options, scratch)
            },
        )
    }

    /// The cache of photon trees `trees` (one per map of `assignment`, indexed by map id) with
    /// your own irradiance estimate. About one photon in `every` of each tree (each with
    /// probability 1/`every`, by a hash of its position and index) becomes a cache point; the
    /// others form the tree [`CachePoint::photons`] that `irradiance(point, scratch)`
    /// estimates from, and the result is scaled by `every/(every − 1)` for the photons set
    /// aside. Lookups search
    /// within `max_distance`. Runs on the current rayon pool; the result does not depend on
    /// the number of threads. `every` below 2 is refused (there would be no photons left to
    /// estimate from). `every` above the photons stored is allowed here (the cache is then
    /// most likely empty, and a lookup finds no point); the renderers refuse it as an option
    /// ([`crate::RenderSettings::validate`], [`crate::Renderer::build_cache`]).
    pub fn build_with<F>(
        scene: &Scene,
        trees: &[&PhotonTree],
        assignment: &MapAssignment,
        every: u32,
        max_distance: f32,
        irradiance: F,
    ) -> Result<Self, RenderError>
    where
        F: Fn(CachePoint<'_>, &mut EstimatorScratch) -> Vec3 + Sync,
    {
        if every < 2 {
            return Err(RenderError::BadFinalGather(format!(
                "cache points every {every} photons: expected 2 or more (the others estimate their irradiance)"
            )));
        }
        if !(max_distance > 0.0 && max_distance.is_finite()) {
            return Err(RenderError::BadMaxDistance(max_distance));
        }
        let map_of_part = map_of_parts(assignment);
        let set_aside = f64::from(every) / f64::from(every - 1);
        let splits = trees
            .iter()
            .map(|tree| split_cache_points(tree, every))
            .collect::<Result<Vec<_>, _>>()?;
        let cache = trees
            .iter()
            .zip(&splits)
            .enumerate()
            .map(|(m, (tree, (indices, others)))| {
                let points = cache_points(
                    scene,
                    &map_of_part,
                    m,
                    tree,
                    indices,
                    others,
                    set_aside,
                    &irradiance,
                );
                IrradiancePoints::new(points)
            })
            .collect::<Result<Vec<_>, _>>()?;
        let photons = splits.into_iter().map(|(_, others)| others).collect();
        let caustics = caustic_trees(trees)?;
        Ok(RadianceCache {
            points: cache,
            map_of_part,
            caustics,
            photons,
            set_aside: set_aside as f32,
            max_distance,
        })
    }

    /// The cache of `points` (one per map of `maps`, as a cache of `maps` built with one
    /// cache point in `every` and a lookup distance of `max_distance` held them, e.g. read
    /// back from a cache file), without [`RadianceCache::photons`]: its caustic trees are
    /// made from `maps` as [`RadianceCache::build_with`] makes them, so the cache is the one
    /// built, bit for bit. Refused: a point count per map that differs from the maps', an
    /// `every` below 2, a distance not positive and finite.
    pub fn from_points(
        points: Vec<IrradiancePoints>,
        maps: &PhotonMaps,
        every: u32,
        max_distance: f32,
    ) -> Result<Self, RenderError> {
        if every < 2 {
            return Err(RenderError::BadFinalGather(format!(
                "cache points every {every} photons: expected 2 or more"
            )));
        }
        if !(max_distance > 0.0 && max_distance.is_finite()) {
            return Err(RenderError::BadMaxDistance(max_distance));
        }
        if points.len() != maps.len() {
            return Err(RenderError::BadFinalGather(format!(
                "cache points for {} maps, but there are {} maps",
                points.len(),
                maps.len()
            )));
        }
        let trees: Vec<&PhotonTree> = maps.trees().iter().collect();
        Ok(RadianceCache {
            points,
            map_of_part: map_of_parts(maps.assignment()),
            caustics: caustic_trees(&trees)?,
            photons: Vec::new(),
            set_aside: (f64::from(every) / f64::from(every - 1)) as f32,
            max_distance,
        })
    }

    /// Irradiance (W/m²) at `position` on a surface of photon map `map` whose normal on the
    /// side of interest is `normal`: that of the nearest cache point of the same map whose
    /// normal agrees ([`NORMAL_AGREEMENT`]) within the estimator's maximum distance, or `None`
    /// when there is none (no photons reached that part of the map). Allocation-free once
    /// `scratch` is warm.
    pub fn irradiance(
        &self,
        position: Vec3,
        normal: Vec3,
        map: u32,
        scratch: &mut EstimatorScratch,
    ) -> Option<Vec3> {
        self.irradiance_within(position, normal, map, self.max_distance, scratch)
    }

    /// [`RadianceCache::irradiance`] from a cache point within `radius` of `position` only
    /// (a consistent renderer shrinks it with its gather volumes, and estimates afresh where
    /// no cache point is that close: from [`RadianceCache::photons`], not from all photons,
    /// which near a point with no cache point close by are fewer than average).
    pub fn irradiance_within(
        &self,
        position: Vec3,
        normal: Vec3,
        map: u32,
        radius: f32,
        scratch: &mut EstimatorScratch,
    ) -> Option<Vec3> {
        self.points.get(map as usize)?.nearest_agreeing(
            position,
            normal,
            radius.min(self.max_distance),
            &mut scratch.neighbours,
        )
    }

    /// The photons of map `map` that are not cache points, which the cache estimated from
    /// (`None` after [`RadianceCache::without_photons`]). An estimate from them, times
    /// [`RadianceCache::set_aside`], does not depend on where the cache points are: the one
    /// to take where no cache point is near enough.
    pub fn photons(&self, map: u32) -> Option<&PhotonTree> {
        self.photons.get(map as usize)
    }

    /// `n/(n − 1)` for one cache point in `n` photons: what an estimate from
    /// [`RadianceCache::photons`] is scaled by for the photons set aside.
    pub fn set_aside(&self) -> f32 {
        self.set_aside
    }

    /// The cache without [`RadianceCache::photons`] (memory for a renderer that only looks
    /// up cache points).
    pub fn without_photons(mut self) -> Self {
        self.photons = Vec::new();
        self
    }

    /// The photon map of part `part` (as the assignment the cache was built with says).
    pub fn map_of(&self, part: pm_trace::PartId) -> Option<u32> {
        self.map_of_part.get(part.0 as usize).copied()
    }

    /// Outgoing radiance `ρ/π · E` (W/(m²·sr)) of a diffuse `hit`: the answer of
    /// [`RadianceCache::radiance_at`] to [`CacheQuery::at_hit`] (the hit part's own map, the
    /// albedo at the hit); zero where the cache has no point. Emission is not included.
    pub fn radiance(&self, scene: &Scene, hit: &Hit, scratch: &mut EstimatorScratch) -> Vec3 {
        self.radiance_at(&CacheQuery::at_hit(scene, hit), scratch)
            .map_or(Vec3::ZERO, |answer| answer.radiance)
    }

    /// The cache read at a surface point a renderer with its own ray tracer found: the
    /// nearest cache point of the query's map within the lookup distance whose normal agrees
    /// with the query's (cosine at least [`NORMAL_AGREEMENT`]; when the nearest does not
    /// agree, the nearest that does among the [`CANDIDATES`] nearest), its irradiance `E`
    /// and `ρ/π · E` with the query's albedo — exactly what the built-in final gather reads
    /// at a gather ray's diffuse hit ([`RadianceCache::radiance`] is this call).
    ///
    /// `None` where no cache point agrees (no photon reached that part of the map, or the
    /// query is on the other side of a sheet), and for a map or part the cache does not
    /// have, a position that is not finite, or a normal that is zero or not finite. Never
    /// panics; allocation-free once `scratch` is warm (one scratch per thread).
    ///
    /// ```
    /// # use pm_render::{CacheQuery, QueryMap, RadianceCache, EstimatorScratch};
    /// # use pm_render::glam::Vec3;
    /// # fn f(cache: &RadianceCache) {
    /// let mut scratch = EstimatorScratch::new();
    /// let query = CacheQuery { position: Vec3::new(0.1, 0.0, 0.2), normal: Vec3::Y, map: QueryMap::Map(0), albedo: Vec3::splat(0.5) };
    /// if let Some(answer) = cache.radiance_at(&query, &mut scratch) {
    ///     println!("L = {} from the point at {}", answer.radiance, answer.point.position);
    /// }
    /// # }
    /// ```
    pub fn radiance_at(&self, query: &CacheQuery, scratch: &mut EstimatorScratch) -> Option<CachedRadiance> {
        let map = query.map.resolve(&self.map_of_part)?;
        let normal = query.unit_normal()?;
        if !query.position.is_finite() {
            return None;
        }
        let point = self.points.get(map as usize)?.nearest_agreeing_point(
            query.position,
            normal,
            self.max_distance,
            &mut scratch.neighbours,
        )?;
        Some(CachedRadiance::new(query.albedo, map, point))
    }

    /// The distance within which [`RadianceCache::radiance_at`] looks for a cache point
    /// (metres): the estimator's maximum distance the cache was built with.
    pub fn max_distance(&self) -> f32 {
        self.max_distance
    }

    /// The photons of kind caustic of photon map `map` alone, as a tree of their own (Jensen's
    /// caustic map, one per photon map); `None` for a map without any. Their powers are
    /// re-encoded relative to the tree's own scale (unbiased, like every photon's).
    pub fn caustic_tree(&self, map: u32) -> Option<&PhotonTree> {
        self.caustics.get(map as usize).filter(|t| !t.is_empty())
    }

    /// The irradiance points of photon map `map`.
    pub fn points(&self, map: u32) -> Option<&IrradiancePoints> {
        self.points.get(map as usize)
    }

    /// Photon maps the cache covers.
    pub fn map_count(&self) -> usize {
        self.points.len()
    }

    /// Cache points over all maps.
    pub fn len(&self) -> usize {
        self.points.iter().map(IrradiancePoints::len).sum()
    }

    /// True when no map has a cache point.
    pub fn is_empty(&self) -> bool {
        self.len() == 0
    }

    /// Bytes held by the cache (its trees and the part-to-map table).
    pub fn memory_bytes(&self) -> usize {
        self.points
            .iter()
            .map(IrradiancePoints::memory_bytes)
            .sum::<usize>()
            + self.map_of_part.len() * size_of::<u32>()
            + self.caustics.iter().map(PhotonTree::memory_bytes).sum::<usize>()
            + self.photons.iter().map(PhotonTree::memory_bytes).sum::<usize>()
            + size_of::<Self>()
    }
}

/// The map of each part of `assignment`, indexed by part.
pub(crate) fn map_of_parts(assignment: &MapAssignment) -> Vec<u32> {
    (0..assignment.part_count() as u32)
        .map(|p| assignment.map_of(pm_trace::PartId(p)))
        .collect()
}
