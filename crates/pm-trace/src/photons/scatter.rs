//! Specular scattering: mirror reflection, refraction and the dielectric Fresnel reflectance.

use glam::Vec3;

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
