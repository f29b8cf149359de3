//! Lights: a trait with photon emission and shadow-ray sampling, and the point, spot,
//! directional, area and textured area lights.

pub(crate) mod area;
pub(crate) mod directional;
pub(crate) mod point;
pub(crate) mod spot;
pub(crate) mod textured_area;

pub use area::AreaLight;
pub use directional::DirectionalLight;
pub use point::PointLight;
pub use spot::SpotLight;
pub use textured_area::TexturedAreaLight;

use crate::ray::Ray;
use crate::rng::Rng;
use glam::Vec3;
use pm_geom::Aabb;

/// A photon ray leaving a light.
///
/// Emission is importance-sampled by the light's own emission distribution, so every photon
/// of a light carries the same power: with `N` photons emitted from the scene and the light
/// chosen with probability `p`, each starts with `power() / (N · p)` (times `weight`, which
/// all built-in lights set to 1 except [`TexturedAreaLight`], whose photons carry the texture
/// at their starting point).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct EmittedRay {
    /// Origin on the light and unit direction of travel.
    pub ray: Ray,
    /// Per-channel multiplier of the photon's share of power (expected value 1).
    pub weight: Vec3,
}

/// A shadow-ray sample towards a light from a receiving point.
///
/// The irradiance at the point is estimated by `E ≈ radiance_over_pdf · max(0, n · direction)`
/// when the segment to the light is unoccluded (`Scene::occluded_from(hit, point + direction ·
/// distance)`). For delta lights (point, spot, directional) `radiance_over_pdf` is the
/// incident irradiance on a surface facing the light.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct LightSample {
    /// Unit direction from the point towards the light.
    pub direction: Vec3,
    /// Distance to the sampled point on the light (finite; for directional lights, beyond the scene).
    pub distance: f32,
    /// Incident radiance divided by the solid-angle pdf of the sample, W/m² per channel.
    pub radiance_over_pdf: Vec3,
}

/// Where a ray meets a light's emitting surface, for multiple importance sampling
/// ([`Light::incident_pdf`]).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct IncidentPdf {
    /// Distance along the ray to the emitting surface.
    pub distance: f32,
    /// Solid-angle density (1/sr) with which [`Light::sample_incident`] from the ray's origin
    /// picks the ray's direction.
    pub pdf: f32,
}

/// Copies a boxed light, so that scenes and their builders can be cloned. Implemented for every
/// `Light + Clone`: a light only needs `#[derive(Clone)]`.
pub trait LightClone {
    /// A boxed copy of this light.
    fn box_clone(&self) -> Box<dyn Light>;
}

impl<T: Light + Clone + 'static> LightClone for T {
    fn box_clone(&self) -> Box<dyn Light> {
        Box::new(self.clone())
    }
}

impl Clone for Box<dyn Light> {
    fn clone(&self) -> Self {
        self.box_clone()
    }
}

/// A light source. Units: watts for power, W/(m²·sr) for radiance. Lights are `Clone` (through
/// [`LightClone`]) so that scenes can be.
pub trait Light: LightClone + Send + Sync + std::fmt::Debug {
    /// Total emitted flux per RGB channel, in watts.
    fn power(&self) -> Vec3;

    /// Emits one photon ray (see [`EmittedRay`] for how power is shared).
    fn emit(&self, rng: &mut Rng) -> EmittedRay;

    /// Samples a direction towards the light from `point` (with surface normal `normal`, which
    /// lights may use to skip samples behind the surface); `None` when the light cannot
    /// reach the point.
    fn sample_incident(&self, point: Vec3, normal: Vec3, rng: &mut Rng) -> Option<LightSample>;

    /// For multiple importance sampling: where the ray from `point` along the unit `direction`
    /// meets this light's emitting side, with the solid-angle density of
    /// [`Light::sample_incident`] picking that direction from `point`; `None` when the ray
    /// misses it. Delta lights (point, spot, directional), which no ray meets, return `None`.
    /// Default: `None`.
    fn incident_pdf(&self, point: Vec3, direction: Vec3) -> Option<IncidentPdf> {
        let _ = (point, direction);
        None
    }

    /// True when [`Light::incident_pdf`] is exact for this light (always `None` for a delta
    /// light). Renderers combine shadow rays with rays that hit emitters by multiple
    /// importance sampling only when every light of the scene says so; otherwise shadow rays
    /// alone carry direct light. Default: `false`.
    fn supports_mis(&self) -> bool {
        false
    }

    /// Called once by the scene builder with the bounds of the scene's geometry, before any
    /// other call (the directional light sizes its emission disc here). Default: nothing.
    fn attach(&mut self, scene_bounds: &Aabb) {
        let _ = scene_bounds;
    }

    /// Checks the light's own parameters (positions, directions, angles, areas); the reason
    /// names the bad one. The scene builder calls it after [`Light::attach`] and refuses the
    /// scene on an error; it checks [`Light::power`] (finite, not negative) itself. Default:
    /// nothing to check.
    fn validate(&self) -> Result<(), String> {
        Ok(())
    }
}

/// `Ok` when `p` is a finite point; the reason names `what`.
pub(crate) fn check_point(what: &str, p: Vec3) -> Result<(), String> {
    if p.is_finite() {
        Ok(())
    } else {
        Err(format!("{what} {p} is not finite"))
    }
}

/// `Ok` when `d` is a finite unit direction; the reason names `what`.
pub(crate) fn check_direction(what: &str, d: Vec3) -> Result<(), String> {
    if d.is_finite() && (d.length() - 1.0).abs() < 1e-3 {
        Ok(())
    } else {
        Err(format!("{what} {d} is not a finite, non-zero direction"))
    }
}

/// A direction normalised; a zero or non-finite one becomes NaN so that [`Light::validate`]
/// refuses it rather than the light silently pointing somewhere.
pub(crate) fn normalize_or_invalid(d: Vec3) -> Vec3 {
    match d.try_normalize() {
        Some(d) => d,
        None => Vec3::NAN,
    }
}

/// A photon leaving a point light at `origin` along `direction`, at the light's full weight.
pub(crate) fn ray_from_point(origin: Vec3, direction: Vec3) -> EmittedRay {
    EmittedRay {
        ray: Ray { origin, direction },
        weight: Vec3::ONE,
    }
}

/// The shadow-ray sample of a point light at `position` seen from `point`, for a light of
/// `intensity(direction towards the light)` watts per steradian: `radiance_over_pdf` is the
/// irradiance `I / d²` on a surface facing the light. `None` at the light itself.
pub(crate) fn sample_point_light(
    position: Vec3,
    point: Vec3,
    intensity: impl FnOnce(Vec3) -> Option<Vec3>,
) -> Option<LightSample> {
    let to = position - point;
    let d2 = to.length_squared();
    let distance = d2.sqrt();
    let direction = (to / distance).try_normalize()?;
    Some(LightSample {
        direction,
        distance,
        radiance_over_pdf: intensity(direction)? / d2,
    })
}
