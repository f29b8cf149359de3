//! Warping uniform random numbers into directions and points: cosine-weighted hemisphere,
//! uniform sphere and cone, uniform disc, and an orthonormal frame around a normal.

use glam::{Vec2, Vec3};
use std::f32::consts::PI;

/// Two unit vectors `(t, b)` such that `(t, b, n)` is a right-handed orthonormal frame
/// (Duff et al. 2017, branchless). `n` must be unit length.
#[inline]
pub fn orthonormal_frame(n: Vec3) -> (Vec3, Vec3) {
    let sign = 1.0f32.copysign(n.z);
    let a = -1.0 / (sign + n.z);
    let b = n.x * n.y * a;
    let t = Vec3::new(1.0 + sign * n.x * n.x * a, sign * b, -sign * n.x);
    let bt = Vec3::new(b, sign + n.y * n.y * a, -n.y);
    (t, bt)
}

/// A uniform point in the unit disc from `u ∈ [0,1)²` (concentric map, Shirley & Chiu 1997),
/// branchless, with a polynomial sine and cosine (see [`sin_cos_octant`]).
#[inline]
pub fn uniform_disc(u: Vec2) -> Vec2 {
    let o = 2.0 * u - Vec2::ONE;
    // The major axis gives the radius; the ratio minor/major ∈ [-1, 1] the angle within its
    // octant: θ = π/4 · ratio (x major) or π/2 − π/4 · ratio (y major).
    let x_major = o.x.abs() > o.y.abs();
    let (major, minor) = if x_major { (o.x, o.y) } else { (o.y, o.x) };
    let ratio = if major == 0.0 { 0.0 } else { minor / major };
    let (s, c) = sin_cos_octant(PI / 4.0 * ratio);
    // cos(π/2 − φ) = sin φ and sin(π/2 − φ) = cos φ.
    let (x, y) = if x_major { (c, s) } else { (s, c) };
    major * Vec2::new(x, y)
}

/// `(sin φ, cos φ)` for `φ ∈ [-π/4, π/4]` by Taylor polynomials to degree 9 and 10
/// (truncation error below 3e-9, a tenth of an f32 ulp at these magnitudes, so
/// single-precision rounding dominates).
#[inline]
pub fn sin_cos_octant(phi: f32) -> (f32, f32) {
    let x2 = phi * phi;
    let s = phi * (1.0 + x2 * (-1.0 / 6.0 + x2 * (1.0 / 120.0 + x2 * (-1.0 / 5040.0 + x2 / 362_880.0))));
    let c = 1.0
        + x2 * (-0.5 + x2 * (1.0 / 24.0 + x2 * (-1.0 / 720.0 + x2 * (1.0 / 40_320.0 - x2 / 3_628_800.0))));
    (s, c)
}

/// A direction around the unit `normal` with density `cos θ / π` (solid-angle measure), unit
/// length up to rounding (see [`cosine_hemisphere_in_frame`]).
#[inline]
pub fn cosine_hemisphere(normal: Vec3, u: Vec2) -> Vec3 {
    let (t, b) = orthonormal_frame(normal);
    cosine_hemisphere_in_frame(t, b, normal, u)
}

/// [`cosine_hemisphere`] in a given right-handed orthonormal frame `(t, b, normal)` (from
/// [`orthonormal_frame`]), for callers that sample many directions around one normal.
///
/// The result is unit length up to rounding (a few ulps), as the frame is orthonormal and the
/// disc point and height lie on the unit sphere; it is not renormalised.
#[inline]
pub fn cosine_hemisphere_in_frame(t: Vec3, b: Vec3, normal: Vec3, u: Vec2) -> Vec3 {
    let d = uniform_disc(u);
    let z = (1.0 - d.length_squared()).max(0.0).sqrt();
    t * d.x + b * d.y + normal * z
}

/// A uniformly distributed unit vector (density `1 / 4π`).
#[inline]
pub fn uniform_sphere(u: Vec2) -> Vec3 {
    let z = 1.0 - 2.0 * u.x;
    let r = (1.0 - z * z).max(0.0).sqrt();
    let phi = 2.0 * PI * u.y;
    Vec3::new(r * phi.cos(), r * phi.sin(), z)
}

/// A direction uniform in the cone of half-angle `acos(cos_max)` around the unit `axis`
/// (density `1 / (2π (1 − cos_max))`).
#[inline]
pub fn uniform_cone(axis: Vec3, cos_max: f32, u: Vec2) -> Vec3 {
    let z = 1.0 - u.x * (1.0 - cos_max);
    let r = (1.0 - z * z).max(0.0).sqrt();
    let phi = 2.0 * PI * u.y;
    let (t, b) = orthonormal_frame(axis);
    (t * (r * phi.cos()) + b * (r * phi.sin()) + axis * z).normalize()
}

/// The index `i` of the interval of a cumulative table (`cumulative[i]` is the sum of weights
/// `0..=i`, non-decreasing, non-empty) that `u · total` falls in, for `u` in `[0, 1)`: index `i`
/// is drawn with probability `weight[i] / total`.
pub fn pick_cumulative(cumulative: &[f32], u: f32) -> usize {
    let total = cumulative.last().copied().unwrap_or(0.0);
    let x = u * total;
    cumulative
        .partition_point(|&c| c <= x)
        .min(cumulative.len().saturating_sub(1))
}

/// A uniform point on the triangle `(a, b, c)` from `u ∈ [0,1)²`.
#[inline]
pub fn uniform_triangle(a: Vec3, b: Vec3, c: Vec3, u: Vec2) -> Vec3 {
    let s = u.x.sqrt();
    let (b0, b1) = (1.0 - s, u.y * s);
    a * b0 + b * b1 + c * (1.0 - b0 - b1)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::Rng;

    fn u2(rng: &mut Rng) -> Vec2 {
        Vec2::new(rng.next_f32(), rng.next_f32())
    }

    #[test]
    fn frame_is_orthonormal() {
        let mut rng = Rng::new(1, 2);
        for _ in 0..1000 {
            let n = uniform_sphere(u2(&mut rng));
            let (t, b) = orthonormal_frame(n);
            assert!((t.length() - 1.0).abs() < 1e-4 && (b.length() - 1.0).abs() < 1e-4);
            assert!(t.dot(n).abs() < 1e-4 && b.dot(n).abs() < 1e-4 && t.dot(b).abs() < 1e-4);
            assert!((t.cross(b) - n).length() < 1e-4);
        }
    }

    #[test]
    fn cosine_hemisphere_has_mean_cosine_two_thirds() {
        // E[cos θ] under p = cos θ / π is 2/3; Var = 1/2 - 4/9 = 1/18.
        let mut rng = Rng::new(3, 4);
        let n = Vec3::new(0.3, -0.5, 0.8).normalize();
        let count = 100_000;
        let mut sum = 0.0f64;
        for _ in 0..count {
            let d = cosine_hemisphere(n, u2(&mut rng));
            let c = d.dot(n);
            assert!(c >= -1e-6);
            assert!((d.length() - 1.0).abs() < 1e-6, "not unit: {d}");
            sum += c as f64;
        }
        let se = (1.0f64 / 18.0 / count as f64).sqrt();
        assert!((sum / count as f64 - 2.0 / 3.0).abs() < 4.0 * se);
    }

    #[test]
    fn uniform_sphere_has_zero_mean_and_unit_length() {
        let mut rng = Rng::new(5, 6);
        let count = 100_000;
        let mut sum = Vec3::ZERO;
        for _ in 0..count {
            let d = uniform_sphere(u2(&mut rng));
            assert!((d.length() - 1.0).abs() < 1e-5);
            sum += d;
        }
        // Each component has variance 1/3.
        let se = (1.0f32 / 3.0 / count as f32).sqrt();
        assert!((sum / count as f32).abs().max_element() < 4.0 * se);
    }

    #[test]
    fn octant_sine_and_cosine_match_the_standard_library() {
        for k in -1000..=1000 {
            let phi = std::f32::consts::FRAC_PI_4 * k as f32 / 1000.0;
            let (s, c) = sin_cos_octant(phi);
            let (es, ec) = (phi as f64).sin_cos();
            assert!(
                (s as f64 - es).abs() < 1.2e-7 && (c as f64 - ec).abs() < 1.2e-7,
                "at {phi}"
            );
        }
    }

    #[test]
    fn disc_points_are_uniform_in_angle() {
        // Seven equal sectors (not aligned with the map's octants) get 1/7 of the points each.
        let mut rng = Rng::new(10, 11);
        let count = 70_000;
        let mut sectors = [0u32; 7];
        for _ in 0..count {
            let p = uniform_disc(u2(&mut rng));
            let a = p.y.atan2(p.x).rem_euclid(2.0 * PI);
            sectors[((a / (2.0 * PI) * 7.0) as usize).min(6)] += 1;
        }
        let se = (count as f64 / 7.0 * (6.0 / 7.0)).sqrt();
        for (i, &n) in sectors.iter().enumerate() {
            assert!(
                (n as f64 - count as f64 / 7.0).abs() < 4.0 * se,
                "sector {i}: {n}"
            );
        }
    }

    #[test]
    fn disc_points_are_inside_and_cover_area_uniformly() {
        let mut rng = Rng::new(8, 9);
        let count = 100_000;
        let mut inside_half = 0;
        for _ in 0..count {
            let p = uniform_disc(u2(&mut rng));
            assert!(p.length() <= 1.0 + 1e-6);
            if p.length() < 0.5 {
                inside_half += 1;
            }
        }
        // P(r < 1/2) = 1/4.
        let f = inside_half as f64 / count as f64;
        let se = (0.25f64 * 0.75 / count as f64).sqrt();
        assert!((f - 0.25).abs() < 4.0 * se);
    }
}
