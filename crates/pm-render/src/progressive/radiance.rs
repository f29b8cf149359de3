//! The radiance one camera ray carries in one progressive pass: specular bounces from the
//! eye, then at the first diffuse hit a fixed-volume estimate in the hit's map, its extent the
//! pilot's extent there times the pass's shrink factor.

use super::pilot::Pilot;
use crate::mode::direct_irradiance;
use crate::mode::final_gather::{self, GatherSource};
use crate::mode::scatter::{MAX_SPECULAR_BOUNCES, specular_bounce};
use crate::{
    EstimatorOptions, EstimatorScratch, FinalGatherOptions, FixedVolumeEstimator, MapView, RadianceCache,
    SurfacePoint,
};
use glam::Vec3;
use pm_kdtree::PhotonTree;
use pm_trace::{Hit, Material, Ray, RayKind, Rng, Scene};
use std::f32::consts::FRAC_1_PI;

/// Everything a pass reads.
pub(super) struct PassLighting<'a, E> {
    pub scene: &'a Scene,
    /// This pass's photons, one tree per map.
    pub trees: &'a [PhotonTree],
    /// The pilot, which fixes the gather volume at each point, and every map's polygons (the
    /// same in every pass).
    pub pilot: &'a Pilot,
    pub estimator: &'a E,
    pub options: &'a EstimatorOptions,
    /// This pass's shrink factor `s_i`.
    pub scale: f32,
    /// Direct light by shadow rays (photons of kind direct excluded by `options`).
    pub shadow_rays: bool,
    /// The final gather instead: this pass's cache, and the gather's parameters.
    pub gather: Option<(&'a RadianceCache, FinalGatherOptions)>,
}

impl<E: FixedVolumeEstimator> PassLighting<'_, E> {
    fn irradiance(&self, hit: &Hit, scratch: &mut EstimatorScratch) -> Vec3 {
        let map_id = self.pilot.maps.map_of(hit.part) as usize;
        let (Some(tree), Some(pilot)) = (self.trees.get(map_id), self.pilot.maps.maps().get(map_id)) else {
            return Vec3::ZERO;
        };
        let at = SurfacePoint {
            position: hit.position,
            normal: self.scene.shading_normal_at(hit),
            front_face: hit.front_face,
        };
        let Some(extent) = self.pilot.extent(map_id, hit.position, self.options, scratch) else {
            return Vec3::ZERO;
        };
        let view = MapView {
            tree,
            polygons: pilot.geometry(),
        };
        self.estimator
            .irradiance_within(at, view, extent * self.scale, self.options, scratch)
    }

    pub fn radiance(&self, mut ray: Ray, rng: &mut Rng, scratch: &mut EstimatorScratch) -> Vec3 {
        if let Some((cache, options)) = self.gather {
            let source = PassGather {
                lighting: self,
                cache,
                options,
            };
            return final_gather::radiance(&source, ray, rng, scratch);
        }
        let scene = self.scene;
        let mut throughput = Vec3::ONE;
        for _ in 0..=MAX_SPECULAR_BOUNCES {
            let Some(hit) = scene.intersect(&ray, f32::INFINITY, RayKind::Camera) else {
                break;
            };
            if let Material::Lambertian { .. } = *scene.material(&hit) {
                let albedo = scene.albedo_at(&hit);
                let mut e = self.irradiance(&hit, scratch);
                if self.shadow_rays {
                    e += direct_irradiance(scene, &hit, rng);
                }
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
}

/// A progressive pass's final gather: fixed-volume estimates throughout. The caustics at x
/// come from the pass's caustic photons in the pass's volume there; a gather hit y reads the
/// pass's cache only from a point within the pass's gather extent at y, and estimates afresh
/// at y otherwise, so as the volumes shrink every reading converges to the irradiance at y.
struct PassGather<'a, E> {
    lighting: &'a PassLighting<'a, E>,
    cache: &'a RadianceCache,
    options: FinalGatherOptions,
}

impl<E: FixedVolumeEstimator> PassGather<'_, E> {
    /// Irradiance at `hit` from `tree` (photons of `hit`'s map `map_id`) in the fixed volume
    /// of `extent` there, on the map's pilot geometry.
    fn within(
        &self,
        tree: Option<&PhotonTree>,
        hit: &Hit,
        map_id: u32,
        extent: f32,
        scratch: &mut EstimatorScratch,
    ) -> Vec3 {
        let l = self.lighting;
        let (Some(tree), Some(pilot)) = (tree, l.pilot.maps.maps().get(map_id as usize)) else {
            return Vec3::ZERO;
        };
        let at = SurfacePoint {
            position: hit.position,
            normal: l.scene.shading_normal_at(hit),
            front_face: hit.front_face,
        };
        let view = MapView {
            tree,
            polygons: pilot.geometry(),
        };
        l.estimator
            .irradiance_within(at, view, extent, l.options, scratch)
    }

    /// Irradiance at `hit` estimated afresh, in the pass's volume there (`extent`), from the
    /// pass's photons that are not cache points, scaled for those set aside. Not from all
    /// photons: this estimate is taken because no cache point lies near `hit`, and the
    /// photons there are then fewer than average (by the cache points that are not there),
    /// while the others are as many as ever.
    fn fresh_irradiance(&self, hit: &Hit, map_id: u32, extent: f32, scratch: &mut EstimatorScratch) -> Vec3 {
        self.within(self.cache.photons(map_id), hit, map_id, extent, scratch) * self.cache.set_aside()
    }
}

impl<E: FixedVolumeEstimator> GatherSource for PassGather<'_, E> {
    fn scene(&self) -> &Scene {
        self.lighting.scene
    }

    fn options(&self) -> &FinalGatherOptions {
        &self.options
    }

    fn caustic_irradiance(&self, hit: &Hit, scratch: &mut EstimatorScratch) -> Vec3 {
        let l = self.lighting;
        let map_id = l.pilot.maps.map_of(hit.part);
        // Most maps hold no caustic photons: no extent to look up then.
        let tree @ Some(_) = self.cache.caustic_tree(map_id) else {
            return Vec3::ZERO;
        };
        let Some(extent) = l.pilot.extent(map_id as usize, hit.position, l.options, scratch) else {
            return Vec3::ZERO;
        };
        self.within(tree, hit, map_id, extent * l.scale, scratch)
    }

    fn cached_radiance(&self, hit: &Hit, scratch: &mut EstimatorScratch) -> Vec3 {
        let l = self.lighting;
        let map_id = l.pilot.maps.map_of(hit.part);
        let Some(extent) = l.pilot.extent(map_id as usize, hit.position, l.options, scratch) else {
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
