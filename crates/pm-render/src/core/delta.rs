//! Delta scattering: mirror reflection and Fresnel glass, the bounces the render core follows.

use glam::Vec3;
use pm_trace::photons::{glass_direction, mirror_direction};
use pm_trace::{Hit, Material, Ray, Rng, Scene};

/// The next ray and throughput factor after a delta (mirror or glass) bounce at `hit`, or
/// `None` when the material is diffuse.
///
/// Mirrors and glass bend light about the interpolated shading normal
/// ([`Scene::shading_normal_at`]), so a smooth (`NORMAL`-attributed) mesh reflects and
/// refracts like the surface it approximates. The geometric normal still decides sides: where
/// the shading normal faces away from the incoming ray, or the direction it gives would reflect
/// into the surface or refract back out of it (near the silhouette of a coarse mesh), the
/// bounce uses the geometric normal instead, so no path crosses a surface it should not.
#[inline]
pub fn specular_bounce(scene: &Scene, hit: &Hit, ray: &Ray, rng: &mut Rng) -> Option<(Ray, Vec3)> {
    let d = ray.direction;
    match *scene.material(hit) {
        Material::Lambertian { .. } => None,
        Material::Mirror { .. } => {
            let r = mirror_direction(d, hit.normal, scene.shading_normal_at(hit));
            Some((scene.spawn_ray(hit, r), scene.albedo_at(hit)))
        }
        Material::Glass { ior } => {
            let eta = if hit.front_face { 1.0 / ior } else { ior };
            let direction = glass_direction(d, hit.normal, scene.shading_normal_at(hit), eta, rng);
            Some((scene.spawn_ray(hit, direction), Vec3::ONE))
        }
    }
}
