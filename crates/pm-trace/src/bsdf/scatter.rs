//! Specular scattering: mirror reflection, refraction and the dielectric Fresnel reflectance,
//! and the mirror and glass bounces about a shading normal that the built-in delta BSDFs
//! ([`super::Mirror`], [`super::Glass`]) make.

use crate::rng::Rng;
use glam::Vec3;

/// The direction a mirror reflects `d` to at a hit with unit geometric normal `geometric`
/// (facing against `d`) and unit shading normal `shading` (on the same side): reflection
/// about the shading normal, unless the shading normal faces away from `d` or the reflection
/// would go into the surface (near a coarse mesh's silhouette), where the geometric normal
/// is used instead.
#[inline]
pub fn mirror_direction(d: Vec3, geometric: Vec3, shading: Vec3) -> Vec3 {
    if shading == geometric {
        reflect(d, geometric)
    } else {
        shaded_mirror_direction(d, geometric, shading)
    }
}

/// [`mirror_direction`] where the normals differ; out of line, as meshes without normals
/// never come here.
#[inline(never)]
fn shaded_mirror_direction(d: Vec3, geometric: Vec3, shading: Vec3) -> Vec3 {
    let r = reflect(d, shading);
    if shading.dot(d) < 0.0 && r.dot(geometric) > 0.0 {
        r
    } else {
        reflect(d, geometric)
    }
}

/// The direction a photon leaves smooth glass in, hitting it along `d` with normals as for
/// [`mirror_direction`] and `eta = n_incident / n_transmitted`: Fresnel reflection or
/// refraction about the shading normal, chosen with one uniform number, drawn only when
/// refraction is possible. Where the shading normal faces away from `d`, or the chosen
/// direction is on the wrong side of the geometric surface (a reflection into it, a
/// refraction back out), the bounce is made about the geometric normal instead.
#[inline]
pub fn glass_direction(d: Vec3, geometric: Vec3, shading: Vec3, eta: f32, rng: &mut Rng) -> Vec3 {
    glass_bounce(d, geometric, shading, eta, &mut || rng.next_f32()).direction
}

/// One bounce off smooth glass: the direction, whether it reflected, and the probability of
/// that choice (the Fresnel reflectance, or one minus it; 1 under total internal reflection).
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct GlassBounce {
    pub(crate) direction: Vec3,
    pub(crate) reflected: bool,
    pub(crate) probability: f32,
}

/// [`glass_direction`] with its uniform number from `draw`, called at most once and only when
/// refraction is possible (so a caller drawing from a stream keeps the stream's order).
#[inline]
pub(crate) fn glass_bounce(
    d: Vec3,
    geometric: Vec3,
    shading: Vec3,
    eta: f32,
    draw: &mut impl FnMut() -> f32,
) -> GlassBounce {
    if shading == geometric {
        glass_about(d, geometric, eta, draw)
    } else {
        shaded_glass_bounce(d, geometric, shading, eta, draw)
    }
}

/// [`glass_bounce`] where the normals differ; out of line, as meshes without normals never
/// come here.
#[inline(never)]
fn shaded_glass_bounce(
    d: Vec3,
    geometric: Vec3,
    shading: Vec3,
    eta: f32,
    draw: &mut impl FnMut() -> f32,
) -> GlassBounce {
    let mut drawn = None;
    let mut u = || *drawn.get_or_insert_with(&mut *draw);
    if shading.dot(d) < 0.0 {
        let bounce = glass_about(d, shading, eta, &mut u);
        if bounce.reflected == (bounce.direction.dot(geometric) > 0.0) {
            return bounce;
        }
    }
    glass_about(d, geometric, eta, &mut u)
}

/// Fresnel reflection or refraction of `d` about the unit normal `n` (facing against `d`),
/// refraction chosen when `u()` (called only when refraction is possible) is at least the
/// reflectance.
#[inline]
fn glass_about(d: Vec3, n: Vec3, eta: f32, u: &mut impl FnMut() -> f32) -> GlassBounce {
    let f = fresnel_dielectric(-d.dot(n), eta);
    match refract(d, n, eta) {
        Some(t) if u() >= f => GlassBounce {
            direction: t,
            reflected: false,
            probability: 1.0 - f,
        },
        Some(_) => GlassBounce {
            direction: reflect(d, n),
            reflected: true,
            probability: f,
        },
        None => GlassBounce {
            direction: reflect(d, n),
            reflected: true,
            probability: 1.0,
        },
    }
}

/// Mirror reflection of direction `d` about the unit normal `n`.
#[inline]
pub fn reflect(d: Vec3, n: Vec3) -> Vec3 {
    d - 2.0 * d.dot(n) * n
}

/// Fresnel reflectance of unpolarised light hitting a smooth dielectric interface at
/// incidence cosine `cos_i` (> 0) with `eta = n_incident / n_transmitted`; 1 under total
/// internal reflection.
#[inline]
pub fn fresnel_dielectric(cos_i: f32, eta: f32) -> f32 {
    let sin2_t = eta * eta * (1.0 - cos_i * cos_i).max(0.0);
    if sin2_t >= 1.0 {
        return 1.0;
    }
    let cos_t = (1.0 - sin2_t).sqrt();
    let rs = (eta * cos_i - cos_t) / (eta * cos_i + cos_t);
    let rp = (cos_i - eta * cos_t) / (cos_i + eta * cos_t);
    0.5 * (rs * rs + rp * rp)
}

/// Refraction of unit direction `d` through the unit normal `n` facing against `d`, with
/// `eta = n_incident / n_transmitted`; `None` under total internal reflection.
#[inline]
pub fn refract(d: Vec3, n: Vec3, eta: f32) -> Option<Vec3> {
    let cos_i = -d.dot(n);
    let sin2_t = eta * eta * (1.0 - cos_i * cos_i).max(0.0);
    if sin2_t >= 1.0 {
        return None;
    }
    let cos_t = (1.0 - sin2_t).sqrt();
    Some((eta * d + (eta * cos_i - cos_t) * n).normalize())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn fresnel_at_normal_incidence_is_the_closed_form() {
        // R0 = ((n1 − n2) / (n1 + n2))² = 0.04 for glass of 1.5.
        assert!((fresnel_dielectric(1.0, 1.0 / 1.5) - 0.04).abs() < 1e-6);
        assert!((fresnel_dielectric(1.0, 1.5) - 0.04).abs() < 1e-6);
        // Beyond the critical angle asin(1/1.5) ≈ 41.8°, everything reflects.
        assert_eq!(fresnel_dielectric(45f32.to_radians().cos(), 1.5), 1.0);
    }

    #[test]
    fn refraction_obeys_snell() {
        let n = Vec3::Y;
        let theta_i = 30f32.to_radians();
        let d = Vec3::new(theta_i.sin(), -theta_i.cos(), 0.0);
        let t = refract(d, n, 1.0 / 1.5).unwrap();
        let sin_t = t.x;
        assert!((sin_t - theta_i.sin() / 1.5).abs() < 1e-6);
        assert!(t.y < 0.0);
        assert!(refract(Vec3::new(0.8, -0.6, 0.0), n, 1.5).is_none());
        assert!((reflect(d, n) - Vec3::new(d.x, -d.y, 0.0)).length() < 1e-6);
    }
}
