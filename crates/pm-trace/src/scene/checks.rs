//! The checks a scene's inputs pass before it is built (lights, shapes, surfaces) and the
//! table that stores each distinct surface once.

use crate::camera::Camera;
use crate::error::SceneError;
use crate::light::Light;
use crate::material::{Material, Surface};
use crate::shape::Shape;
use glam::Vec3;
use pm_geom::Aabb;

/// Every light valid ([`Light::validate`]) with finite, non-negative power, and the total power
/// finite (photon tracing divides it among the photons).
pub(super) fn check_lights(lights: &[Box<dyn Light>]) -> Result<(), SceneError> {
    let mut total = 0.0f64;
    for (i, light) in lights.iter().enumerate() {
        let fail = |reason: String| SceneError::InvalidLight { light: i, reason };
        light.validate().map_err(fail)?;
        let power = light.power();
        if !power.is_finite() || power.min_element() < 0.0 {
            return Err(fail(format!("power {power} W must be finite and not negative")));
        }
        total += power.as_dvec3().element_sum();
        if total > f32::MAX as f64 {
            return Err(fail(format!(
                "the lights' total power passes {:e} W, the largest f32",
                f32::MAX
            )));
        }
    }
    Ok(())
}

/// The distinct surfaces of a scene, each stored once however many parts use it.
#[derive(Default)]
pub(super) struct SurfaceTable {
    pub(super) surfaces: Vec<Surface>,
    ids: std::collections::HashMap<[u32; 16], u32>,
}

impl SurfaceTable {
    /// The id of `surface`, added if new. Surfaces are compared by their bits.
    pub(super) fn id_of(&mut self, surface: Surface) -> u32 {
        // The material's kind and up to ten parameters, as bits.
        let (kind, parameters): (u32, [f32; 10]) = match surface.material {
            Material::Lambertian { albedo } => (0, pad(albedo.to_array())),
            Material::Mirror { reflectance } => (1, pad(reflectance.to_array())),
            Material::Glass { ior } => (2, pad([ior; 3])),
            // The object's address identifies a custom BSDF (its two halves as parameters).
            Material::Custom(bsdf) => {
                let address = std::ptr::from_ref(bsdf).cast::<u8>() as usize as u64;
                let (low, high) = (address as u32, (address >> 32) as u32);
                (3, pad([f32::from_bits(low), f32::from_bits(high), 0.0]))
            }
            Material::MetallicRoughness(m) => {
                let (c, s) = (m.base_color(), m.specular_color());
                (
                    4,
                    [
                        c.x,
                        c.y,
                        c.z,
                        m.metallic(),
                        m.roughness(),
                        m.ior(),
                        m.specular(),
                        s.x,
                        s.y,
                        s.z,
                    ],
                )
            }
        };
        let e = surface.emission;
        let mut key = [0u32; 16];
        key[0] = kind;
        for (k, p) in key[1..11].iter_mut().zip(parameters) {
            *k = p.to_bits();
        }
        key[11..].copy_from_slice(&[
            e.x.to_bits(),
            e.y.to_bits(),
            e.z.to_bits(),
            surface.camera_visible as u32,
            surface.sides as u32,
        ]);
        *self.ids.entry(key).or_insert_with(|| {
            self.surfaces.push(surface);
            (self.surfaces.len() - 1) as u32
        })
    }
}

/// Three parameters followed by zeros.
fn pad(three: [f32; 3]) -> [f32; 10] {
    let mut all = [0.0; 10];
    all[..3].copy_from_slice(&three);
    all
}

/// On the −z side of the bounds looking along +z at their centre (the built-in scenes' view).
pub(super) fn default_camera(bounds: &Aabb) -> Camera {
    let c = bounds.center();
    let fov = 40f32.to_radians();
    Camera::new(
        c - Vec3::Z * Camera::framing_distance(bounds.size(), fov),
        c,
        Vec3::Y,
        fov,
    )
}

pub(super) fn check_shape(shape: &Shape) -> Result<(), String> {
    match shape {
        Shape::Sphere(s) => {
            if !(s.center.is_finite() && s.radius.is_finite() && s.radius > 0.0) {
                return Err(format!(
                    "sphere needs a finite centre and a positive radius, got {:?}, {}",
                    s.center, s.radius
                ));
            }
        }
        Shape::Ring(r) => {
            let ok = r.center.is_finite()
                && r.axis.is_normalized()
                && r.inner_radius.is_finite()
                && r.outer_radius.is_finite()
                && r.height.is_finite()
                && r.inner_radius >= 0.0
                && r.outer_radius > r.inner_radius
                && r.height > 0.0;
            if !ok {
                return Err(format!(
                    "ring needs a finite centre, a non-zero axis, 0 <= inner < outer radius and a positive height, got {r:?}"
                ));
            }
        }
    }
    Ok(())
}

pub(super) fn check_surface(s: &Surface, what: impl Fn() -> String) -> Result<(), SceneError> {
    let colour_ok = |c: Vec3| c.is_finite() && c.min_element() >= 0.0;
    let reason = match s.material {
        Material::Lambertian { albedo } if !colour_ok(albedo) || albedo.max_element() > 1.0 => {
            Some(format!("albedo {albedo} must be finite and in [0, 1]"))
        }
        Material::Mirror { reflectance } if !colour_ok(reflectance) || reflectance.max_element() > 1.0 => {
            Some(format!("reflectance {reflectance} must be finite and in [0, 1]"))
        }
        Material::Glass { ior } if !(ior.is_finite() && ior > 0.0) => {
            Some(format!("index of refraction {ior} must be finite and positive"))
        }
        _ if !colour_ok(s.emission) => {
            Some(format!("emission {} must be finite and non-negative", s.emission))
        }
        _ => None,
    };
    match reason {
        Some(reason) => Err(SceneError::InvalidSurface { what: what(), reason }),
        None => Ok(()),
    }
}
