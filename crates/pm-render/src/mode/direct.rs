//! Direct irradiance by shadow rays: one sample per light, unoccluded samples only.

use glam::Vec3;
use pm_trace::{Hit, Rng, Scene};

/// Irradiance (W/m²) at `hit` straight from the scene's lights, one shadow ray per light.
///
/// The cosine is taken with the shading normal ([`Scene::shading_normal_at`]); a light
/// below the geometric surface counts nothing even where the shading normal faces it, so no
/// light leaks through a coarse mesh's shadow terminator.
pub fn direct_irradiance(scene: &Scene, hit: &Hit, rng: &mut Rng) -> Vec3 {
    direct_irradiance_shaded(scene, hit, scene.shading_normal_at(hit), rng)
}

/// [`direct_irradiance`] with the shading normal already known (callers that need it for
/// more than this do not interpolate it twice).
pub(crate) fn direct_irradiance_shaded(scene: &Scene, hit: &Hit, shading: Vec3, rng: &mut Rng) -> Vec3 {
    let mut e = Vec3::ZERO;
    for light in scene.lights() {
        let Some(sample) = light.sample_incident(hit.position, hit.normal, rng) else {
            continue;
        };
        let cos = shading.dot(sample.direction);
        if cos <= 0.0 || hit.normal.dot(sample.direction) <= 0.0 || !sample.radiance_over_pdf.is_finite() {
            continue;
        }
        if !scene.occluded(hit.position, hit.position + sample.direction * sample.distance) {
            e += sample.radiance_over_pdf * cos;
        }
    }
    e
}
