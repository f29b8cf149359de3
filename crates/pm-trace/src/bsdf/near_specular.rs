//! Near-specular surfaces: glossy ones so smooth that paths pass through them as through a
//! mirror (the camera's path samples their BSDF, and a photon's path keeps its caustic label
//! there and stores nothing), rather than reading or storing photons on them.

use super::Bsdf;

/// Below this glossy roughness ([`Bsdf::glossy_roughness`], glTF's perceptual roughness,
/// `α = roughness²`) a surface without a diffuse lobe is near-specular: the camera path keeps
/// sampling its BSDF through it (pm-render's delta chain, `core::follow_delta_bounces`)
/// rather than reading photons there, and a photon path bounces off it as off a mirror (no
/// photon stored, the caustic label kept), as pbrt-v4's SPPM does for specular lobes (its `α < 10⁻³`, roughness 0.03) and LuxCore's
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

/// True when paths pass through a surface of `material` (camera paths instead of reading
/// radiance there, photon paths instead of storing a photon): it has only delta lobes, or no
/// diffuse lobe and a glossy roughness below [`NEAR_SPECULAR_ROUGHNESS`].
#[inline]
pub fn passes_through(material: &(impl Bsdf + ?Sized)) -> bool {
    let lobes = material.lobes();
    !lobes.has_non_delta()
        || (!lobes.has_diffuse()
            && material
                .glossy_roughness()
                .is_some_and(|r| r < NEAR_SPECULAR_ROUGHNESS))
}
