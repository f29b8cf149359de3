//! What one progressive pass reads at a camera path's first diffuse hit: a fixed-volume
//! estimate in the hit's map, its extent the pilot's extent there times the pass's shrink
//! factor ([`PassPhotonSource`]), or a final gather whose every read is such an estimate
//! ([`PassGather`]).

use super::pilot::Pilot;
use crate::cache::RadianceCache;
use crate::core::{PathVertex, RadianceSource};
use crate::estimator::fixed::FixedVolumeEstimator;
use crate::estimator::options::EstimatorOptions;
use crate::estimator::point::MapView;
use crate::estimator::point::SurfacePoint;
use crate::estimator::scratch::EstimatorScratch;
use crate::estimator::weight::{Irradiance, PhotonWeight};
use crate::source::final_gather::FinalGatherOptions;
use crate::source::final_gather::GatherReads;
use crate::source::photon_read::DirectLight;
use crate::source::photon_read::photon_radiance;
use glam::Vec3;
use pm_kdtree::PhotonTree;
use pm_trace::{Hit, Rng, Scene};
use std::f32::consts::FRAC_1_PI;

/// Everything a pass's fixed-volume estimates read.
pub(super) struct PassVolumes<'a, E> {
    pub scene: &'a Scene,
    /// This pass's photons, one tree per map.
    pub trees: &'a [PhotonTree],
    /// The pilot, which fixes the gather volume at each point, and every map's polygons (the
    /// same in every pass).
    pub pilot: &'a Pilot<'a, E>,
    pub estimator: &'a E,
    pub options: &'a EstimatorOptions,
    /// This pass's shrink factor `s_i`.
    pub scale: f32,
}

impl<E: FixedVolumeEstimator> PassVolumes<'_, E> {
    /// The estimate with `weight` at `hit` from the pass's photons of its map, in the pass's
    /// volume there.
    fn estimate(&self, hit: &Hit, weight: &dyn PhotonWeight, scratch: &mut EstimatorScratch) -> Vec3 {
        let map_id = self.pilot.map_of(hit.part);
        let Some(extent) = self.pilot.extent(map_id as usize, hit.position, scratch) else {
            return Vec3::ZERO;
        };
        self.within(
            self.trees.get(map_id as usize),
            hit,
            map_id,
            extent * self.scale,
            weight,
            scratch,
        )
    }

    /// The estimate with `weight` at `hit` from `tree` (photons of `hit`'s map `map_id`) in
    /// the fixed volume of `extent` there, on the map's pilot geometry.
    fn within(
        &self,
        tree: Option<&PhotonTree>,
        hit: &Hit,
        map_id: u32,
        extent: f32,
        weight: &dyn PhotonWeight,
        scratch: &mut EstimatorScratch,
    ) -> Vec3 {
        let (Some(tree), Some(polygons)) = (tree, self.pilot.polygons(map_id)) else {
            return Vec3::ZERO;
        };
        let at = SurfacePoint {
            position: hit.position,
            normal: self.scene.shading_normal_at(hit),
            front_face: hit.front_face,
        };
        let view = MapView { tree, polygons };
        self.estimator
            .estimate_within(at, view, extent, self.options, weight, scratch)
    }
}

/// A pass's photon-map read: `ρ/π · E` with `E` the fixed-volume estimate on a diffuse
/// surface, the estimate with the BSDF's weight on a glossy one (plus shadow rays, by
/// [`DirectLight`]).
pub(super) struct PassPhotonSource<'a, E> {
    pub volumes: &'a PassVolumes<'a, E>,
    pub direct: DirectLight,
}

impl<E: FixedVolumeEstimator> RadianceSource for PassPhotonSource<'_, E> {
    fn scene(&self) -> &Scene {
        self.volumes.scene
    }

    fn reflected(&self, vertex: &PathVertex, rng: &mut Rng, scratch: &mut EstimatorScratch) -> Vec3 {
        let (scene, hit) = (self.volumes.scene, &vertex.hit);
        let albedo = || scene.albedo_at(hit);
        let wo = -vertex.ray.direction;
        photon_radiance(scene, hit, wo, albedo, self.direct, rng, |weight| {
            self.volumes.estimate(hit, weight, scratch)
        })
    }
}

/// A progressive pass's final gather: fixed-volume estimates throughout. The caustics at x
/// come from the pass's caustic photons in the pass's volume there; a gather hit y reads the
/// pass's cache only from a point within the pass's gather extent at y, and estimates afresh
/// at y otherwise, so as the volumes shrink every reading converges to the irradiance at y.
pub(super) struct PassGather<'a, E> {
    pub volumes: &'a PassVolumes<'a, E>,
    pub cache: &'a RadianceCache,
    pub options: FinalGatherOptions,
}

impl<E: FixedVolumeEstimator> PassGather<'_, E> {
    /// Irradiance at `hit` estimated afresh, in the pass's volume there (`extent`), from the
    /// pass's photons that are not cache points, scaled for those set aside. Not from all
    /// photons: this estimate is taken because no cache point lies near `hit`, and the
    /// photons there are then fewer than average (by the cache points that are not there),
    /// while the others are as many as ever.
    fn fresh_irradiance(&self, hit: &Hit, map_id: u32, extent: f32, scratch: &mut EstimatorScratch) -> Vec3 {
        self.volumes.within(
            self.cache.photons(map_id),
            hit,
            map_id,
            extent,
            &Irradiance,
            scratch,
        ) * self.cache.set_aside()
    }
}

impl<E: FixedVolumeEstimator> GatherReads for PassGather<'_, E> {
    fn scene(&self) -> &Scene {
        self.volumes.scene
    }

    fn options(&self) -> &FinalGatherOptions {
        &self.options
    }

    fn caustics(&self, hit: &Hit, weight: &dyn PhotonWeight, scratch: &mut EstimatorScratch) -> Vec3 {
        let l = self.volumes;
        let map_id = l.pilot.map_of(hit.part);
        // Most maps hold no caustic photons: no extent to look up then.
        let tree @ Some(_) = self.cache.caustic_tree(map_id) else {
            return Vec3::ZERO;
        };
        let Some(extent) = l.pilot.extent(map_id as usize, hit.position, scratch) else {
            return Vec3::ZERO;
        };
        l.within(tree, hit, map_id, extent * l.scale, weight, scratch)
    }

    fn cached_radiance(&self, hit: &Hit, scratch: &mut EstimatorScratch) -> Vec3 {
        let l = self.volumes;
        let map_id = l.pilot.map_of(hit.part);
        let Some(extent) = l.pilot.extent(map_id as usize, hit.position, scratch) else {
            return Vec3::ZERO;
        };
        let e =
            match self
                .cache
                .irradiance_within(hit.position, hit.normal, map_id, extent * l.scale, scratch)
            {
                Some(e) => e,
                None => self.fresh_irradiance(hit, map_id, extent * l.scale, scratch),
            };
        l.scene.albedo_at(hit) * FRAC_1_PI * e
    }
}
