//! The isotropic point light.

use super::{EmittedRay, Light, LightSample, ray_from_point, sample_point_light};
use crate::rng::Rng;
use crate::sampling::uniform_sphere;
use glam::{Vec2, Vec3};
use std::f32::consts::PI;

/// A point emitting `power` watts uniformly in all directions (intensity `power / 4π`).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct PointLight {
    /// Position (metres).
    pub position: Vec3,
    /// Total flux per channel (watts).
    pub power: Vec3,
}

impl PointLight {
    /// A point light.
    pub fn new(position: Vec3, power: Vec3) -> Self {
        PointLight { position, power }
    }
}

impl Light for PointLight {
    fn power(&self) -> Vec3 {
        self.power
    }

    fn validate(&self) -> Result<(), String> {
        super::check_point("position", self.position)
    }

    fn emit(&self, rng: &mut Rng) -> EmittedRay {
        let d = uniform_sphere(Vec2::new(rng.next_f32(), rng.next_f32()));
        ray_from_point(self.position, d)
    }

    /// A delta light: no ray meets it, so multiple importance sampling leaves it to shadow
    /// rays.
    fn supports_mis(&self) -> bool {
        true
    }

    fn sample_incident(&self, point: Vec3, _normal: Vec3, _rng: &mut Rng) -> Option<LightSample> {
        sample_point_light(self.position, point, |_| Some(self.power / (4.0 * PI)))
    }
}
