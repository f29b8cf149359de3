//! The spot light: a point light restricted to a cone, with uniform intensity inside.

use super::{EmittedRay, Light, LightSample, ray_from_point, sample_point_light};
use crate::rng::Rng;
use crate::sampling::uniform_cone;
use glam::{Vec2, Vec3};
use std::f32::consts::PI;

/// A point emitting `power` watts uniformly into the cone of half-angle `cone_angle` around
/// `direction` (intensity `power / (2π (1 − cos cone_angle))` inside, zero outside).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SpotLight {
    /// Position (metres).
    pub position: Vec3,
    /// Unit axis of the cone.
    pub direction: Vec3,
    /// Half-angle of the cone in radians, in `(0, π]`.
    pub cone_angle: f32,
    /// Total flux per channel (watts).
    pub power: Vec3,
}

impl SpotLight {
    /// A spot light (the direction is normalised; a zero or non-finite direction is refused
    /// when the scene is built).
    pub fn new(position: Vec3, direction: Vec3, cone_angle: f32, power: Vec3) -> Self {
        SpotLight {
            position,
            direction: super::normalize_or_invalid(direction),
            cone_angle,
            power,
        }
    }

    fn cos_max(&self) -> f32 {
        self.cone_angle.clamp(1e-4, PI).cos()
    }
}

impl Light for SpotLight {
    fn power(&self) -> Vec3 {
        self.power
    }

    fn validate(&self) -> Result<(), String> {
        super::check_point("position", self.position)?;
        super::check_direction("direction", self.direction)?;
        if !(self.cone_angle > 0.0 && self.cone_angle <= PI) {
            return Err(format!("cone angle {} rad is not in (0, π]", self.cone_angle));
        }
        Ok(())
    }

    fn emit(&self, rng: &mut Rng) -> EmittedRay {
        let cos_max = self.cos_max();
        let d = uniform_cone(self.direction, cos_max, Vec2::new(rng.next_f32(), rng.next_f32()));
        ray_from_point(self.position, d)
    }

    /// A delta light: no ray meets it, so multiple importance sampling leaves it to shadow
    /// rays.
    fn supports_mis(&self) -> bool {
        true
    }

    fn sample_incident(&self, point: Vec3, _normal: Vec3, _rng: &mut Rng) -> Option<LightSample> {
        let cos_max = self.cos_max();
        sample_point_light(self.position, point, |direction| {
            ((-direction).dot(self.direction) >= cos_max).then(|| self.power / (2.0 * PI * (1.0 - cos_max)))
        })
    }
}
