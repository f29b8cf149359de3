//! The radiance cache as another renderer asks it: a surface point given by position, normal,
//! map (or part) and albedo, with no [`pm_trace::Hit`] needed, and the cached answer there.

use super::points::IrradiancePoint;
use glam::Vec3;
use pm_trace::{Hit, PartId, Scene};
use std::f32::consts::FRAC_1_PI;

/// A normal whose squared length is within this of one is used as given (bit for bit, as the
/// scene's unit normals are); any other finite, non-zero normal is normalised first.
const UNIT_TOLERANCE: f32 = 1e-4;

/// Which photon map a [`CacheQuery`] reads: one by its id, or the one the cache's partition
/// assigned to a part (what a renderer that traced our scene's parts knows).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum QueryMap {
    /// Photon map `id` (as in [`pm_trace::PhotonMaps::map`]).
    Map(u32),
    /// The map of this part ([`crate::RadianceCache::map_of`]).
    Part(PartId),
}

impl QueryMap {
    /// The map id, looking a part up in `map_of_part`; `None` for a part out of range.
    pub(crate) fn resolve(self, map_of_part: &[u32]) -> Option<u32> {
        match self {
            QueryMap::Map(id) => Some(id),
            QueryMap::Part(part) => map_of_part.get(part.0 as usize).copied(),
        }
    }
}

/// A surface point at which [`crate::RadianceCache::radiance_at`] reads the cache: what a
/// renderer with its own ray tracer knows at its hit.
///
/// The fields are plain inputs, like a ray's, so a query is built with a struct literal;
/// [`CacheQuery::at_hit`] builds the one the built-in final gather asks at one of our hits.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct CacheQuery {
    /// The point (metres, scene space).
    pub position: Vec3,
    /// The unit geometric normal on the side being looked at (the side the query's ray
    /// arrived from): a cache point answers only where its own normal agrees
    /// ([`super::NORMAL_AGREEMENT`]). A normal that is not unit is normalised; a zero or
    /// non-finite one gets no answer.
    pub normal: Vec3,
    /// The photon map to read.
    pub map: QueryMap,
    /// The diffuse reflectance `ρ` at the point, the albedo the outgoing radiance `ρ/π · E`
    /// is taken with: the built-in gather takes [`Scene::albedo_at`] (material factor times
    /// texture and vertex colours); a renderer with its own materials gives its own.
    pub albedo: Vec3,
}

impl CacheQuery {
    /// The query the built-in final gather asks at `hit` of `scene`: its position, geometric
    /// normal, part, and [`Scene::albedo_at`] there.
    pub fn at_hit(scene: &Scene, hit: &Hit) -> Self {
        CacheQuery {
            position: hit.position,
            normal: hit.normal,
            map: QueryMap::Part(hit.part),
            albedo: scene.albedo_at(hit),
        }
    }

    /// The normal to compare cache points' with: as given when it is unit (within
    /// [`UNIT_TOLERANCE`]), normalised otherwise, `None` when zero or not finite.
    pub(crate) fn unit_normal(&self) -> Option<Vec3> {
        if !self.normal.is_finite() {
            return None;
        }
        if (self.normal.length_squared() - 1.0).abs() <= UNIT_TOLERANCE {
            return Some(self.normal);
        }
        self.normal.try_normalize()
    }
}

/// The cache's answer to a [`CacheQuery`].
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct CachedRadiance {
    /// Outgoing radiance `ρ/π · E` (W/(m²·sr)) with the query's albedo: what a diffuse
    /// surface there sends back along a gather ray (emission not included).
    pub radiance: Vec3,
    /// Irradiance `E` (W/m²): the answering cache point's.
    pub irradiance: Vec3,
    /// The photon map read.
    pub map: u32,
    /// The cache point that answered: the nearest of the map's within the lookup distance
    /// whose normal agrees with the query's.
    pub point: IrradiancePoint,
}

impl CachedRadiance {
    /// The answer of `point` (of map `map`) to a query with `albedo`.
    pub(crate) fn new(albedo: Vec3, map: u32, point: IrradiancePoint) -> Self {
        CachedRadiance {
            radiance: albedo * FRAC_1_PI * point.irradiance,
            irradiance: point.irradiance,
            map,
            point,
        }
    }

    /// Distance (metres) from `position` (the query's) to the answering cache point.
    pub fn distance_from(&self, position: Vec3) -> f32 {
        self.point.position.distance(position)
    }
}
