//! Direct irradiance by shadow rays: one sample per light, unoccluded samples only; and its
//! multiple-importance weights against cosine-weighted rays that hit the lights.

use glam::Vec3;
use pm_trace::bsdf::{Bsdf, ShadingPoint};
use pm_trace::{Hit, Light, Rng, Scene};
use std::f32::consts::FRAC_1_PI;

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
    unoccluded_sum(scene, hit, shading, rng, |_, _, _| 1.0)
}

/// The sum over the scene's lights of one shadow-ray sample each, `radiance_over_pdf · cos ·
/// weight(light, direction, cos)` (a number, or a colour such as `f(wo, wi)` times one), counting only samples above both the shading and the
/// geometric surface, finite, and unoccluded.
#[inline]
fn unoccluded_sum<W: Weight>(
    scene: &Scene,
    hit: &Hit,
    shading: Vec3,
    rng: &mut Rng,
    weight: impl Fn(&dyn Light, Vec3, f32) -> W,
) -> Vec3 {
    let mut e = Vec3::ZERO;
    for light in scene.lights() {
        let Some(sample) = light.sample_incident(hit.position, hit.normal, rng) else {
            continue;
        };
        let cos = shading.dot(sample.direction);
        if cos <= 0.0 || hit.normal.dot(sample.direction) <= 0.0 || !sample.radiance_over_pdf.is_finite() {
            continue;
        }
        if scene.occluded_from(hit, hit.position + sample.direction * sample.distance) {
            continue;
        }
        e += weight(light.as_ref(), sample.direction, cos).scale(sample.radiance_over_pdf * cos);
    }
    e
}

/// What a light sample is multiplied by: a number (a weight) or a colour (`f` times one).
trait Weight {
    /// `v` times this.
    fn scale(self, v: Vec3) -> Vec3;
}

impl Weight for f32 {
    #[inline]
    fn scale(self, v: Vec3) -> Vec3 {
        v * self
    }
}

impl Weight for Vec3 {
    #[inline]
    fn scale(self, v: Vec3) -> Vec3 {
        v * self
    }
}

/// True when every light of `scene` gives exact densities for multiple importance sampling
/// ([`pm_trace::Light::supports_mis`]); otherwise shadow rays alone carry direct light.
pub(crate) fn mis_enabled(scene: &Scene) -> bool {
    scene.lights().iter().all(|l| l.supports_mis())
}

/// The power heuristic (Veach 1997, β = 2) of a strategy of density `f` against one of `g`
/// (each already multiplied by its sample count).
#[inline]
pub(crate) fn power_heuristic(f: f32, g: f32) -> f32 {
    let (f2, g2) = (f * f, g * g);
    if f2 + g2 > 0.0 { f2 / (f2 + g2) } else { 0.0 }
}

/// Direct irradiance at `hit` by one shadow ray per light, each weighted by the power heuristic
/// against `bsdf_samples` cosine-weighted rays about `shading` that could hit the same light
/// (their emission weighted by [`bsdf_emission_weight`]). Delta lights keep weight 1.
pub(crate) fn direct_irradiance_mis(
    scene: &Scene,
    hit: &Hit,
    shading: Vec3,
    bsdf_samples: f32,
    rng: &mut Rng,
) -> Vec3 {
    unoccluded_sum(scene, hit, shading, rng, |light, direction, cos| {
        match light.incident_pdf(hit.position, direction) {
            Some(p) => power_heuristic(p.pdf, bsdf_samples * cos * FRAC_1_PI),
            None => 1.0,
        }
    })
}

/// The weight of emission found by a cosine-weighted ray from `from` along `direction` that
/// hit an emitter at distance `t`, one of `bsdf_samples` rays of density `bsdf_pdf` each,
/// against the one shadow ray per light of [`direct_irradiance_mis`]: the power heuristic
/// with the densities of the lights whose surface the ray meets there.
pub(crate) fn bsdf_emission_weight(
    scene: &Scene,
    from: Vec3,
    direction: Vec3,
    t: f32,
    bsdf_samples: f32,
    bsdf_pdf: f32,
) -> f32 {
    let tolerance = 1e-3 * t + 8.0 * scene.epsilon();
    let light_pdf: f32 = scene
        .lights()
        .iter()
        .filter_map(|l| l.incident_pdf(from, direction))
        .filter(|p| (p.distance - t).abs() <= tolerance)
        .map(|p| p.pdf)
        .sum();
    power_heuristic(bsdf_samples * bsdf_pdf, light_pdf)
}

/// Radiance reflected at `hit` towards `wo` straight from the scene's lights through `bsdf`:
/// one shadow ray per light, `f(wo, wi) · L · cos / pdf_light`, weighted by the power heuristic
/// against one sample of the BSDF's own density ([`Bsdf::pdf`]) when `mis` holds (delta lights
/// keep weight 1). For BSDFs with a glossy lobe, whose reflection is not `ρ_d/π` times the
/// irradiance; the BSDF-sampled side is [`bsdf_emission_weight`] with the sample's pdf.
pub(crate) fn direct_radiance_through(
    scene: &Scene,
    hit: &Hit,
    at: &ShadingPoint,
    bsdf: &dyn Bsdf,
    wo: Vec3,
    mis: Mis,
    rng: &mut Rng,
) -> Vec3 {
    unoccluded_sum(scene, hit, at.shading, rng, |light, direction, _| {
        let f = bsdf.eval(at, wo, direction);
        let weight = match (mis, light.incident_pdf(hit.position, direction)) {
            (Mis::Weighted, Some(p)) => power_heuristic(p.pdf, bsdf.pdf(at, wo, direction)),
            _ => 1.0,
        };
        f * weight
    })
}

/// Whether light samples are weighted against BSDF samples (every light gives exact
/// densities, [`mis_enabled`]) or carry direct light alone.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum Mis {
    /// Power-heuristic weights on both strategies.
    Weighted,
    /// Shadow rays alone.
    ShadowRaysOnly,
}
