//! Delta scattering: the bounces the render core follows at surfaces whose BSDF has only delta
//! lobes (mirror reflection, Fresnel glass, or a renderer author's own), sampled through
//! [`Bsdf`].

use glam::Vec3;
use pm_trace::bsdf::near_specular::passes_through;
use pm_trace::{Bsdf, Hit, Ray, Rng, Scene};

/// The next ray and throughput factor (the sample's weight) after a delta (mirror or glass)
/// bounce at `hit` (or a near-specular glossy one, sampled from its BSDF), or `None` when the
/// material is not passed through ([`passes_through`]) or absorbs.
///
/// Mirrors and glass bend light about the interpolated shading normal
/// ([`Scene::shading_normal_at`]), so a smooth (`NORMAL`-attributed) mesh reflects and
/// refracts like the surface it approximates. The geometric normal still decides sides: where
/// the shading normal faces away from the incoming ray, or the direction it gives would reflect
/// into the surface or refract back out of it (near the silhouette of a coarse mesh), the
/// bounce uses the geometric normal instead, so no path crosses a surface it should not.
#[inline]
pub fn specular_bounce(scene: &Scene, hit: &Hit, ray: &Ray, rng: &mut Rng) -> Option<(Ray, Vec3)> {
    let material = scene.material(hit);
    if !passes_through(material) {
        return None;
    }
    let sample = material.sample_from(&scene.shading_point(hit), -ray.direction, rng)?;
    Some((scene.spawn_ray(hit, sample.wi), sample.weight))
}
