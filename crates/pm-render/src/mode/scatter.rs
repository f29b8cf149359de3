//! Specular scattering shared by the modes: mirror reflection and Fresnel glass.

use glam::Vec3;
use pm_trace::{Hit, Material, Ray, Rng, Scene};

/// Longest chain of specular bounces followed from the eye.
pub(crate) const MAX_SPECULAR_BOUNCES: u32 = 16;

/// The next ray and throughput factor after a specular bounce at `hit`, or `None` when the
/// material is diffuse.
#[inline]
pub(crate) fn specular_bounce(scene: &Scene, hit: &Hit, ray: &Ray, rng: &mut Rng) -> Option<(Ray, Vec3)> {
    match *scene.material(hit) {
        Material::Lambertian { .. } => None,
        Material::Mirror { .. } => Some((
            scene.spawn_ray(hit, reflect(ray.direction, hit.normal)),
            scene.albedo_at(hit),
        )),
        Material::Glass { ior } => {
            let eta = if hit.front_face { 1.0 / ior } else { ior };
            let cos_i = (-ray.direction.dot(hit.normal)).clamp(0.0, 1.0);
            let direction = match refract(ray.direction, hit.normal, cos_i, eta) {
                Some((t, cos_t)) if rng.next_f32() >= fresnel_dielectric(cos_i, cos_t, eta) => t,
                _ => reflect(ray.direction, hit.normal),
            };
            Some((scene.spawn_ray(hit, direction), Vec3::ONE))
        }
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
