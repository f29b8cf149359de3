//! Delta scattering: the bounces the render core follows at surfaces whose BSDF has only delta
//! lobes (mirror reflection, Fresnel glass, or a renderer author's own), sampled through
//! [`Bsdf`].

use glam::Vec3;
use pm_trace::{Bsdf, Hit, Material, Ray, Rng, Scene};

/// Below this glossy roughness ([`Bsdf::glossy_roughness`], glTF's perceptual roughness,
/// `α = roughness²`) a surface without a diffuse lobe is near-specular: the camera path keeps
/// sampling its BSDF through it ([`super::follow_delta_bounces`]) rather than reading photons there,
/// as pbrt-v4's SPPM does for specular lobes (its `α < 10⁻³`, roughness 0.03) and LuxCore's
/// PhotonGI below its glossiness threshold (0.05 on `α`, roughness 0.22).
///
/// 0.25, by measurement (`tests/glossy_roughness_sweep.rs`: a box with a rough metal floor,
/// the floor's mean against the path tracer over 4 seeds, shadow-rays mode, cube estimator,
/// 100,000 photons, 4 samples per pixel). Read from the photons, the floor is high and noisy
/// as its lobe narrows: +14.5 ± 6.2 % at roughness 0.1, +7.9 ± 2.4 % at 0.2, +1.6 ± 1.5 % at
/// 0.3. Sampled through, it is unbiased but carries the next vertex's noise: −1.1 ± 0.4 % at
/// 0.1, +0.3 ± 3.5 % at 0.2, −7.6 ± 8.4 % at 0.3. The root-mean-square errors of one image
/// cross between 0.2 and 0.3. The progressive mode converges either way (within 1 % at 16
/// passes from 0.1 to 0.5).
pub const NEAR_SPECULAR_ROUGHNESS: f32 = 0.25;

/// True when a camera path passes through a surface of `material` instead of reading
/// radiance there: it has only delta lobes, or no diffuse lobe and a glossy roughness below
/// [`NEAR_SPECULAR_ROUGHNESS`].
#[inline]
pub fn passes_through(material: &Material) -> bool {
    let lobes = material.lobes();
    !lobes.has_non_delta()
        || (!lobes.has_diffuse()
            && material
                .glossy_roughness()
                .is_some_and(|r| r < NEAR_SPECULAR_ROUGHNESS))
}

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
