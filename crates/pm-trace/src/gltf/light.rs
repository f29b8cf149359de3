//! `KHR_lights_punctual` lights to radiometric lights. Photometric glTF units become watts
//! by [`LightUnits::punctual_factor`](super::LightUnits::punctual_factor) (by default the
//! luminous efficacy of 555 nm light, 683 lm/W), times
//! [`GltfOptions::light_scale`](super::GltfOptions::light_scale).

use std::path::Path;

use glam::{DMat4, DVec3, Vec3};
use gltf::json;
use json::extensions::scene::khr_lights_punctual::{Light, Type};
use json::validation::Checked;

use super::error::GltfError;
use super::options::GltfOptions;
use super::origin::unit_f32;

/// A punctual light placed in the world, in radiometric units.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum GltfLight {
    /// Emits equally in all directions.
    Point {
        /// Position in metres, relative to [`GltfContent::origin_offset`](super::GltfContent::origin_offset).
        position: Vec3,
        /// Radiant intensity in W/sr per channel: `color × candela × punctual_factor ×
        /// light_scale` (`punctual_factor` is 1/683 by default; see `LightUnits`).
        intensity: Vec3,
    },
    /// Emits in a cone around `direction` (the node's −Z axis).
    Spot {
        /// Position in metres, relative to [`GltfContent::origin_offset`](super::GltfContent::origin_offset).
        position: Vec3,
        /// Unit direction of the cone's axis.
        direction: Vec3,
        /// Radiant intensity inside the inner cone in W/sr: `color × candela × punctual_factor × light_scale`.
        intensity: Vec3,
        /// Angle from the axis where the falloff starts, radians.
        inner_cone_angle: f32,
        /// Angle from the axis where the light reaches zero, radians.
        outer_cone_angle: f32,
    },
    /// Parallel light travelling along `direction` (the node's −Z axis).
    Directional {
        /// Unit direction the light travels in.
        direction: Vec3,
        /// Irradiance on a surface facing the light in W/m²: `color × lux × punctual_factor × light_scale`.
        irradiance: Vec3,
    },
}

/// Places light `light` of the file at a node with world transform `world` (f64), its
/// position re-centred on `origin`. `range` is ignored: the inverse-square law needs no
/// cut-off.
pub(super) fn place_light(
    file: &Path,
    root: &json::Root,
    node: usize,
    light: usize,
    world: DMat4,
    origin: DVec3,
    options: &GltfOptions,
) -> Result<GltfLight, GltfError> {
    let error = |reason: String| GltfError::Node {
        file: file.to_path_buf(),
        node,
        reason,
    };
    let lights = root
        .extensions
        .as_ref()
        .and_then(|e| e.khr_lights_punctual.as_ref())
        .map_or(&[][..], |l| &l.lights[..]);
    let l: &Light = lights.get(light).ok_or_else(|| {
        error(format!(
            "light {light} does not exist (the file has {})",
            lights.len()
        ))
    })?;
    let power =
        Vec3::from(l.color) * l.intensity * options.light_units.punctual_factor() * options.light_scale;
    if !power.is_finite() || power.min_element() < 0.0 {
        return Err(error(format!(
            "light {light}: colour × intensity {power} is not finite and non-negative"
        )));
    }
    let position = (world.transform_point3(DVec3::ZERO) - origin).as_vec3();
    let direction = unit_f32(world.transform_vector3(DVec3::NEG_Z));
    let Checked::Valid(ty) = l.type_ else {
        return Err(error(format!("light {light}: invalid type")));
    };
    let need_direction = || {
        let reason = format!("light {light}: the node's −Z axis is degenerate");
        direction.ok_or_else(|| error(reason))
    };
    let need_position = || {
        let reason = format!("light {light}: its position is not finite in f32 once re-centred on {origin}");
        if position.is_finite() {
            Ok(position)
        } else {
            Err(error(reason))
        }
    };
    Ok(match ty {
        Type::Point => GltfLight::Point {
            position: need_position()?,
            intensity: power,
        },
        Type::Spot => {
            let (inner, outer) = spot_cone(l).map_err(|r| error(format!("light {light}: {r}")))?;
            GltfLight::Spot {
                position: need_position()?,
                direction: need_direction()?,
                intensity: power,
                inner_cone_angle: inner,
                outer_cone_angle: outer,
            }
        }
        Type::Directional => GltfLight::Directional {
            direction: need_direction()?,
            irradiance: power,
        },
    })
}

/// The spot's inner and outer cone angles (glTF defaults 0 and π/4), checked.
fn spot_cone(l: &Light) -> Result<(f32, f32), String> {
    let (inner, outer) = l.spot.as_ref().map_or((0.0, std::f32::consts::FRAC_PI_4), |s| {
        (s.inner_cone_angle, s.outer_cone_angle)
    });
    let valid = outer > 0.0 && outer <= std::f32::consts::FRAC_PI_2 && (0.0..=outer).contains(&inner);
    if valid {
        Ok((inner, outer))
    } else {
        Err(format!(
            "cone angles inner {inner}, outer {outer} need 0 ≤ inner ≤ outer, 0 < outer ≤ π/2"
        ))
    }
}
