//! Specular scattering shared by the modes: mirror reflection and Fresnel glass.

use glam::Vec3;
use pm_trace::{Hit, Material, Ray, Rng, Scene};

/// Longest chain of specular bounces followed from the eye.
pub(crate) const MAX_SPECULAR_BOUNCES: u32 = 16;

/// The next ray and throughput factor after a specular bounce at `hit`, or `None` when the
/// material is diffuse.
///
/// Mirrors and glass bend light about the interpolated shading normal
/// ([`Scene::shading_normal_at`]), so a smooth (`NORMAL`-attributed) mesh reflects and
/// refracts like the surface it approximates. The geometric normal still decides sides: where
/// the shading normal faces away from the incoming ray, or the direction it gives would reflect
/// into the surface or refract back out of it (near the silhouette of a coarse mesh), the
/// bounce uses the geometric normal instead, so no path crosses a surface it should not.
#[inline]
pub(crate) fn specular_bounce(scene: &Scene, hit: &Hit, ray: &Ray, rng: &mut Rng) -> Option<(Ray, Vec3)> {
    let d = ray.direction;
    match *scene.material(hit) {
        Material::Lambertian { .. } => None,
        Material::Mirror { .. } => {
            let shading = scene.shading_normal_at(hit);
            let r = if shading == hit.normal {
                reflect(d, hit.normal)
            } else {
                shaded_mirror_direction(d, hit.normal, shading)
            };
            Some((scene.spawn_ray(hit, r), scene.albedo_at(hit)))
        }
        Material::Glass { ior } => {
            let eta = if hit.front_face { 1.0 / ior } else { ior };
            let shading = scene.shading_normal_at(hit);
            let direction = if shading == hit.normal {
                // One uniform number, drawn only when refraction is possible.
                glass_direction(d, hit.normal, eta, &mut || rng.next_f32()).0
            } else {
                shaded_glass_direction(d, hit.normal, shading, eta, rng)
            };
            Some((scene.spawn_ray(hit, direction), Vec3::ONE))
        }
    }
}

/// Mirror reflection of `d` about the shading normal, or about the geometric one where the
/// shading normal faces away from `d` or the reflection would go into the surface. Kept out
/// of line: meshes without normals never come here.
#[inline(never)]
fn shaded_mirror_direction(d: Vec3, geometric: Vec3, shading: Vec3) -> Vec3 {
    let r = reflect(d, shading);
    if shading.dot(d) < 0.0 && r.dot(geometric) > 0.0 {
        r
    } else {
        reflect(d, geometric)
    }
}

/// The glass bounce about the shading normal, or about the geometric one where the shading
/// normal faces away from `d` or the chosen direction lies on the wrong side of the geometric
/// surface (a reflection into it, a refraction back out). One uniform number per bounce,
/// drawn only when refraction is possible. Kept out of line: meshes without normals never
/// come here.
#[inline(never)]
fn shaded_glass_direction(d: Vec3, geometric: Vec3, shading: Vec3, eta: f32, rng: &mut Rng) -> Vec3 {
    let mut drawn = None;
    let mut u = || *drawn.get_or_insert_with(|| rng.next_f32());
    if shading.dot(d) < 0.0 {
        let (t, reflected) = glass_direction(d, shading, eta, &mut u);
        if reflected == (t.dot(geometric) > 0.0) {
            return t;
        }
    }
    glass_direction(d, geometric, eta, &mut u).0
}

/// The direction leaving glass hit along `d` at unit normal `n` (facing against `d`), and
/// whether it was reflected: Fresnel reflection chosen when `u()` falls below the reflectance,
/// always under total internal reflection.
#[inline]
fn glass_direction(d: Vec3, n: Vec3, eta: f32, u: &mut impl FnMut() -> f32) -> (Vec3, bool) {
    let cos_i = (-d.dot(n)).clamp(0.0, 1.0);
    match refract(d, n, cos_i, eta) {
        Some((t, cos_t)) if u() >= fresnel_dielectric(cos_i, cos_t, eta) => (t, false),
        _ => (reflect(d, n), true),
    }
}

#[inline]
fn reflect(d: Vec3, n: Vec3) -> Vec3 {
    d - 2.0 * d.dot(n) * n
}

/// Refracted direction and cosine, with `n` facing the incoming side; `None` on total
/// internal reflection.
#[inline]
fn refract(d: Vec3, n: Vec3, cos_i: f32, eta: f32) -> Option<(Vec3, f32)> {
    let sin2_t = eta * eta * (1.0 - cos_i * cos_i);
    if sin2_t >= 1.0 {
        return None;
    }
    let cos_t = (1.0 - sin2_t).sqrt();
    Some(((eta * d + (eta * cos_i - cos_t) * n).normalize(), cos_t))
}

/// Unpolarised Fresnel reflectance of a smooth dielectric (`eta` = n_incident / n_transmitted).
#[inline]
fn fresnel_dielectric(cos_i: f32, cos_t: f32, eta: f32) -> f32 {
    let r_s = (eta * cos_i - cos_t) / (eta * cos_i + cos_t);
    let r_p = (cos_i - eta * cos_t) / (cos_i + eta * cos_t);
    0.5 * (r_s * r_s + r_p * r_p)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn fresnel_at_normal_incidence_is_the_closed_form() {
        // ((n1 - n2) / (n1 + n2))² = 0.04 for glass of index 1.5.
        let r = fresnel_dielectric(1.0, 1.0, 1.0 / 1.5);
        assert!((r - 0.04).abs() < 1e-6);
    }

    #[test]
    fn refraction_obeys_snell() {
        let n = Vec3::Y;
        let d = Vec3::new(0.6, -0.8, 0.0);
        let (t, _) = refract(d, n, 0.8, 1.0 / 1.5).unwrap();
        assert!((t.length() - 1.0).abs() < 1e-6);
        // sin θ_t = sin θ_i / 1.5
        assert!((t.x - 0.6 / 1.5).abs() < 1e-6);
        assert!(refract(Vec3::new(0.9, -0.435_889_9, 0.0), n, 0.435_889_9, 1.5).is_none());
    }
}
