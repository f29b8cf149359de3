//! The radiance one camera ray carries in one progressive pass: specular bounces from the
//! eye, then at the first diffuse hit a fixed-volume estimate in the hit's map, its extent the
//! pilot's extent there times the pass's shrink factor.

use super::pilot::Pilot;
use crate::mode::direct_irradiance;
use crate::mode::scatter::{MAX_SPECULAR_BOUNCES, specular_bounce};
use crate::{EstimatorOptions, EstimatorScratch, FixedVolumeEstimator, MapView, SurfacePoint};
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
