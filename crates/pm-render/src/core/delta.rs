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
/// Provisional: 0.1, between those two, not yet measured here. At roughness 0.2 and above
/// (the glossy Cornell box's blocks) the photon reads agree with the path tracer at region
/// level (`tests/glossy_photon_modes.rs`); the bias of a k-nearest read below that, where
/// the lobe is narrower than the photons' spread of directions, is the measurement to make.
pub const NEAR_SPECULAR_ROUGHNESS: f32 = 0.1;

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
