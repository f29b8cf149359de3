//! The directional light: parallel rays from a disc that covers the scene.

use super::{EmittedRay, Light, LightSample};
use crate::ray::Ray;
use crate::rng::Rng;
use crate::sampling::{orthonormal_frame, uniform_disc};
use glam::{Vec2, Vec3};
use pm_geom::Aabb;
use std::f32::consts::PI;

/// Parallel light travelling along `direction` with irradiance `irradiance` (W/m² per
/// channel) on a surface perpendicular to it. Photons start on a disc perpendicular to the
/// direction that covers the bounding sphere of the scene, outside it; its power is
/// `irradiance · π R²` with `R` that sphere's radius (known after [`Light::attach`]).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct DirectionalLight {
    direction: Vec3,
    irradiance: Vec3,
    center: Vec3,
    radius: f32,
}

impl DirectionalLight {
    /// A light travelling along `direction` (normalised; a zero or non-finite direction is
    /// refused when the scene is built).
    pub fn new(direction: Vec3, irradiance: Vec3) -> Self {
        DirectionalLight {
            direction: super::normalize_or_invalid(direction),
            irradiance,
            center: Vec3::ZERO,
            radius: 0.0,
        }
    }

    /// Unit direction of travel.
    pub fn direction(&self) -> Vec3 {
        self.direction
    }

    /// Irradiance on a perpendicular surface.
    pub fn irradiance(&self) -> Vec3 {
        self.irradiance
    }
}

impl Light for DirectionalLight {
    fn power(&self) -> Vec3 {
        self.irradiance * (PI * self.radius * self.radius)
    }

    fn emit(&self, rng: &mut Rng) -> EmittedRay {
        let (t, b) = orthonormal_frame(self.direction);
        let d = uniform_disc(Vec2::new(rng.next_f32(), rng.next_f32())) * self.radius;
        let origin = self.center - self.direction * (2.0 * self.radius) + t * d.x + b * d.y;
        EmittedRay {
            ray: Ray {
                origin,
                direction: self.direction,
            },
            weight: Vec3::ONE,
        }
    }

    /// A delta light: no ray meets it, so multiple importance sampling leaves it to shadow
    /// rays.
    fn supports_mis(&self) -> bool {
        true
    }

    fn sample_incident(&self, _point: Vec3, _normal: Vec3, _rng: &mut Rng) -> Option<LightSample> {
        Some(LightSample {
            direction: -self.direction,
            distance: 4.0 * self.radius.max(1.0),
            radiance_over_pdf: self.irradiance,
        })
    }

    fn validate(&self) -> Result<(), String> {
        super::check_direction("direction", self.direction)?;
        super::check_point("irradiance", self.irradiance)
    }

    fn attach(&mut self, scene_bounds: &Aabb) {
        if scene_bounds.is_empty() {
            return;
        }
        self.center = scene_bounds.center();
        // A little margin so that photons also reach surfaces exactly on the bounds.
        self.radius = 0.5 * scene_bounds.diagonal() * 1.001 + 1e-4;
    }
}
