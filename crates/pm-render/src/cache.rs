//! Precomputed irradiance (Christensen 1999): irradiance estimated once at every n-th photon of
//! each map, then read by a final gather's rays as one nearest-point lookup in the hit's own map.

use crate::{Estimator, EstimatorOptions, EstimatorScratch, MapView, RenderError, SurfacePoint};
use glam::Vec3;
use pm_kdtree::{Euclidean, KindMask, Photon, PhotonKind, PhotonTree};
use pm_trace::{Hit, MapAssignment, PhotonMaps, Ray, RayKind, Scene};
use rayon::prelude::*;
use std::f32::consts::FRAC_1_PI;

/// Candidates examined per lookup for one whose normal agrees with the query's.
const CANDIDATES: usize = 8;

/// The smallest cosine between a cache point's normal and the query's for the point to answer
/// (about 25°): the nearest point on the other side of a thin sheet, or across a sharp fold of
/// one map's surface, is passed over.
pub const NORMAL_AGREEMENT: f32 = 0.9;

/// Irradiance precomputed at photon positions, per photon map: the radiance cache of a final
/// gather.
///
/// [`RadianceCache::build`] takes every `n`-th photon of each map (in the map's tree order,
/// which is spatially stratified), finds the surface it landed on (its normal and side) and
/// estimates the irradiance there with the renderer's own [`Estimator`] from photons of all
/// kinds — the same estimate, with the same partition and area, that the photon maps give a
/// camera ray. The points are kept per map in a [`PhotonTree`] (20 bytes each: the position,
/// the irradiance as unbiased 12-bit log codes, the normal as an octahedral code).
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
/// use pm_trace::{Camera, CreaseAngle, MapAssignment, Partitioner, PhotonMaps, PointLight, Ray, RayKind, Scene, Surface, TraceOptions, trace_photons};
/// use std::f32::consts::PI;
///
/// // A point light of intensity π inside a closed diffuse sphere of albedo 0.5: radiance 1
/// // everywhere inside (irradiance 2π).
/// let scene = Scene::builder()
///     .sphere(Vec3::ZERO, 1.0, Surface::diffuse(Vec3::splat(0.5)))
///     .light(PointLight::new(Vec3::ZERO, Vec3::splat(4.0 * PI * PI)))
///     .camera(Camera::new(Vec3::new(0.0, 0.0, 0.5), Vec3::NEG_Z, Vec3::Y, 1.2))
///     .build()?;
/// let assignment = CreaseAngle::default().try_partition(&scene)?;
/// let traced = trace_photons(&scene, &assignment, &TraceOptions { photons: 20_000, ..TraceOptions::default() })?;
/// let maps = PhotonMaps::build(&scene, &assignment, traced)?;
/// let options = EstimatorOptions::for_scene(&scene.bounds());
/// let cache = RadianceCache::build(&scene, &maps, &Disc, &options, 4)?;
/// let mut scratch = EstimatorScratch::new();
/// let hit = scene.intersect(&Ray { origin: Vec3::ZERO, direction: Vec3::X }, f32::INFINITY, RayKind::Other).unwrap();
/// let l = cache.radiance(&scene, &hit, &mut scratch);
/// assert!((l.x - 1.0).abs() < 0.1, "{l}"); // one lookup: within the estimate's noise
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
#[derive(Clone, Debug)]
pub struct RadianceCache {
    /// One tree per photon map: "photons" whose power is the irradiance (W/m²) and whose
    /// direction is the surface normal on the side the photons arrived from.
    maps: Vec<PhotonTree>,
    map_of_part: Vec<u32>,
    /// Per photon map: its photons of kind caustic alone (Jensen's caustic map, split as the
    /// photon maps are), so that a caustic estimate does not wade through the others.
    caustics: Vec<PhotonTree>,
    max_distance: f32,
}

impl RadianceCache {
    /// Precomputes irradiance at every `every`-th photon of each of `maps` (1 = every photon)
    /// with `estimator` and `options` (whose photon kinds are replaced by all kinds: light
    /// leaving a surface is the sum of everything arriving there). Runs on the current rayon
    /// pool; the result does not depend on the number of threads. `every = 0` is refused.
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
            ..*options
        };
        let trees: Vec<&PhotonTree> = maps.maps().iter().map(|m| m.tree()).collect();
        Self::build_with(
            scene,
            &trees,
            maps.assignment(),
            every,
            options.max_distance,
            |map, at, scratch| {
                let map = maps.map(map as u32);
                let view = MapView {
                    tree: map.tree(),
                    polygons: map.geometry(),
                };
                estimator.irradiance(at, view, &options, scratch)
            },
        )
    }

    /// The cache of photon trees `trees` (one per map of `assignment`, indexed by map id) with
    /// your own irradiance estimate: `irradiance(map, at, scratch)` is called at every
    /// `every`-th photon of each tree, `at` being the photon's position with the normal and
    /// side of the surface it landed on. Lookups search within `max_distance`. Runs on the
    /// current rayon pool; the result does not depend on the number of threads.
    pub fn build_with<F>(
        scene: &Scene,
        trees: &[&PhotonTree],
        assignment: &MapAssignment,
        every: u32,
        max_distance: f32,
        irradiance: F,
    ) -> Result<Self, RenderError>
    where
        F: Fn(usize, SurfacePoint, &mut EstimatorScratch) -> Vec3 + Sync,
    {
        if every == 0 {
            return Err(RenderError::BadFinalGather(
                "the cache needs every n-th photon with n ≥ 1".into(),
            ));
        }
        if !(max_distance > 0.0 && max_distance.is_finite()) {
            return Err(RenderError::BadMaxDistance(max_distance));
        }
        let map_of_part: Vec<u32> = (0..assignment.part_count() as u32)
            .map(|p| assignment.map_of(pm_trace::PartId(p)))
            .collect();
        // The cast that finds a photon's surface starts this far before it.
        let back = 4.0 * scene.epsilon();
        let cache = trees
            .iter()
            .enumerate()
            .map(|(m, tree)| {
                let indices: Vec<u32> = (0..tree.len() as u32).step_by(every as usize).collect();
                let points: Vec<Photon> = indices
                    .par_iter()
                    .map_init(EstimatorScratch::new, |scratch, &i| {
                        let photon = tree.get(i);
                        let position = photon.position();
                        let direction = photon.direction();
                        let ray = Ray {
                            origin: position - direction * back,
                            direction,
                        };
                        let hit = scene.intersect(&ray, 2.0 * back, RayKind::Other)?;
                        if map_of_part.get(hit.part.0 as usize) != Some(&(m as u32)) {
                            return None;
                        }
                        let at = SurfacePoint {
                            position,
                            normal: scene.shading_normal_at(&hit),
                            front_face: hit.front_face,
                        };
                        Some(Photon {
                            position,
                            power: irradiance(m, at, scratch),
                            direction: hit.normal,
                            kind: PhotonKind::Direct,
                        })
                    })
                    .flatten()
                    .collect();
                PhotonTree::build(points).map_err(|e| RenderError::BadFinalGather(e.to_string()))
            })
            .collect::<Result<Vec<_>, _>>()?;
        let caustics = trees
            .iter()
            .map(|tree| {
                let scale = tree.power_scale();
                let photons: Vec<Photon> = tree
                    .iter()
                    .filter(|p| p.kind() == PhotonKind::Caustic)
                    .map(|p| p.decode(scale))
                    .collect();
                PhotonTree::build(photons).map_err(|e| RenderError::BadFinalGather(e.to_string()))
            })
            .collect::<Result<Vec<_>, _>>()?;
        Ok(RadianceCache {
            maps: cache,
            map_of_part,
            caustics,
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
    /// no cache point is that close).
    pub fn irradiance_within(
        &self,
        position: Vec3,
        normal: Vec3,
        map: u32,
        radius: f32,
        scratch: &mut EstimatorScratch,
    ) -> Option<Vec3> {
        let tree = self.maps.get(map as usize)?;
        let max_distance = radius.min(self.max_distance);
        if tree.is_empty() {
            return None;
        }
        let neighbours = &mut scratch.neighbours;
        // The nearest point first (almost always the answer), then more candidates.
        tree.nearest_k::<Euclidean>(position, 1, max_distance, KindMask::ALL, neighbours);
        let agrees = |p: &pm_kdtree::CompactPhoton| p.direction().dot(normal) >= NORMAL_AGREEMENT;
        match neighbours.as_slice().first().map(|n| tree.get(n.index)) {
            None => return None,
            Some(p) if agrees(&p) => return Some(p.power(tree.power_scale())),
            Some(_) => {}
        }
        tree.nearest_k::<Euclidean>(position, CANDIDATES, max_distance, KindMask::ALL, neighbours);
        neighbours.sort_by_distance();
        neighbours
            .as_slice()
            .iter()
            .map(|n| tree.get(n.index))
            .find(agrees)
            .map(|p| p.power(tree.power_scale()))
    }

    /// The photon map of part `part` (as the assignment the cache was built with says).
    pub fn map_of(&self, part: pm_trace::PartId) -> Option<u32> {
        self.map_of_part.get(part.0 as usize).copied()
    }

    /// Outgoing radiance `ρ/π · E` (W/(m²·sr)) of a diffuse `hit`, with `E` from
    /// [`RadianceCache::irradiance`] in the hit part's own map and `ρ` the albedo at the hit;
    /// zero where the cache has no point. Emission is not included.
    pub fn radiance(&self, scene: &Scene, hit: &Hit, scratch: &mut EstimatorScratch) -> Vec3 {
        let Some(&map) = self.map_of_part.get(hit.part.0 as usize) else {
            return Vec3::ZERO;
        };
        match self.irradiance(hit.position, hit.normal, map, scratch) {
            Some(e) => scene.albedo_at(hit) * FRAC_1_PI * e,
            None => Vec3::ZERO,
        }
    }

    /// The photons of kind caustic of photon map `map` alone, as a tree of their own (Jensen's
    /// caustic map, one per photon map); `None` for a map without any. Their powers are
    /// re-encoded relative to the tree's own scale (unbiased, like every photon's).
    pub fn caustic_tree(&self, map: u32) -> Option<&PhotonTree> {
        self.caustics.get(map as usize).filter(|t| !t.is_empty())
    }

    /// Cache points over all maps.
    pub fn len(&self) -> usize {
        self.maps.iter().map(PhotonTree::len).sum()
    }

    /// True when no map has a cache point.
    pub fn is_empty(&self) -> bool {
        self.len() == 0
    }

    /// Bytes held by the cache (its trees and the part-to-map table).
    pub fn memory_bytes(&self) -> usize {
        self.maps.iter().map(PhotonTree::memory_bytes).sum::<usize>()
            + self.map_of_part.len() * size_of::<u32>()
            + self.caustics.iter().map(PhotonTree::memory_bytes).sum::<usize>()
            + size_of::<Self>()
    }
}
