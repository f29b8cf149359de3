//! The photon maps read at the first diffuse hit by a k-nearest estimate: the photon-map
//! mode (Ball & Stejko's main results) and, with direct light by shadow rays, their Image 1.

use super::photon_read::{DirectLight, photon_radiance};
use crate::core::{PathVertex, RadianceSource};
use crate::estimator::Estimator;
use crate::estimator::options::EstimatorOptions;
use crate::estimator::point::MapView;
use crate::estimator::point::SurfacePoint;
use crate::estimator::scratch::EstimatorScratch;
use crate::estimator::weight::{Irradiance, PhotonWeight};
use glam::Vec3;
use pm_trace::{Hit, PhotonMaps, Rng, Scene};

/// Irradiance at `hit` from the photon map of its part with `estimator` (zero when that map
/// is missing): the read that every photon-map source shares.
#[inline]
pub fn map_irradiance<E: Estimator + ?Sized>(
    scene: &Scene,
    maps: &PhotonMaps,
    estimator: &E,
    options: &EstimatorOptions,
    hit: &Hit,
    scratch: &mut EstimatorScratch,
) -> Vec3 {
    map_estimate(scene, maps, estimator, options, &Irradiance, hit, scratch)
}

/// `estimator`'s estimate with `weight` at `hit` (its shading normal, its side) from the
/// photons and polygons of the hit's own map (zero when that map is missing).
#[inline]
pub(crate) fn map_estimate<E: Estimator + ?Sized>(
    scene: &Scene,
    maps: &PhotonMaps,
    estimator: &E,
    options: &EstimatorOptions,
    weight: &dyn PhotonWeight,
    hit: &Hit,
    scratch: &mut EstimatorScratch,
) -> Vec3 {
    let Some(map) = maps.get(maps.map_of(hit.part)) else {
        return Vec3::ZERO;
    };
    let view = MapView {
        tree: map.tree(),
        polygons: map.geometry(),
    };
    estimate_at(scene, estimator, view, options, weight, hit, scratch)
}

/// `estimator`'s estimate with `weight` at `hit` (its shading normal, its side) from the
/// photons and polygons of `view`.
#[inline]
pub(crate) fn estimate_at<E: Estimator + ?Sized>(
    scene: &Scene,
    estimator: &E,
    view: MapView<'_>,
    options: &EstimatorOptions,
    weight: &dyn PhotonWeight,
    hit: &Hit,
    scratch: &mut EstimatorScratch,
) -> Vec3 {
    let at = SurfacePoint {
        position: hit.position,
        normal: scene.shading_normal_at(hit),
        front_face: hit.front_face,
    };
    estimator.estimate(at, view, options, weight, scratch)
}

/// Radiance at the first non-delta hit from a k-nearest estimate in the hit's own map (plus
/// shadow rays, by [`DirectLight`]): `ρ/π · E` on a diffuse surface, `Σ Φ_p f(wo, wi_p) / A`
/// on one with a glossy lobe (see [`crate::estimator`]). Textures are averaged over the pixel's footprint
/// there: its width at the distance travelled, stretched on a tilted surface.
#[derive(Clone, Copy, Debug)]
pub struct PhotonMapSource<'a, E> {
    /// The scene.
    pub scene: &'a Scene,
    /// Its photon maps.
    pub maps: &'a PhotonMaps,
    /// The estimator.
    pub estimator: &'a E,
    /// Its options.
    pub options: &'a EstimatorOptions,
    /// The angle a pixel spans ([`pm_trace::Camera::pixel_angle`]); zero point-samples
    /// textures.
    pub pixel_angle: f32,
    /// Where direct light comes from.
    pub direct: DirectLight,
}

impl<E: Estimator> RadianceSource for PhotonMapSource<'_, E> {
    fn scene(&self) -> &Scene {
        self.scene
    }

    #[inline]
    fn reflected(&self, vertex: &PathVertex, rng: &mut Rng, scratch: &mut EstimatorScratch) -> Vec3 {
        let (scene, hit) = (self.scene, &vertex.hit);
        // The pixel's footprint: its width at this distance, stretched on a tilted surface
        // (by the square root of 1/cos, between the ellipse's two axes).
        let albedo = || {
            let cos = (-vertex.ray.direction.dot(hit.normal)).max(1e-3);
            scene.albedo_over(hit, vertex.distance * self.pixel_angle / cos.sqrt())
        };
        let wo = -vertex.ray.direction;
        photon_radiance(scene, hit, wo, albedo, self.direct, rng, |weight| {
            map_estimate(
                scene,
                self.maps,
                self.estimator,
                self.options,
                weight,
                hit,
                scratch,
            )
        })
    }
}
