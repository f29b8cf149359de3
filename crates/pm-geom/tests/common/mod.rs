//! Shared generators for the property tests: convex polygons with a closed-form area.

#![allow(dead_code)]

use pm_geom::glam::{Vec3, vec3};
use proptest::prelude::*;

/// A convex polygon inscribed in a circle, with its area from the closed form
/// `½ r² Σ sin(θᵢ₊₁ − θᵢ)` (independent of the code under test).
#[derive(Clone, Debug)]
pub struct CirclePolygon {
    /// Vertices, counter-clockwise about `normal`.
    pub vertices: Vec<Vec3>,
    /// Unit normal.
    pub normal: Vec3,
    /// Centre of the circumscribed circle.
    pub center: Vec3,
    /// Radius of the circumscribed circle.
    pub radius: f32,
    /// Area from the closed form.
    pub area: f32,
}

/// A unit vector from two uniform numbers.
pub fn unit(u: f32, v: f32) -> Vec3 {
    let z = 2.0 * u - 1.0;
    let phi = std::f32::consts::TAU * v;
    let s = (1.0 - z * z).max(0.0).sqrt();
    vec3(s * phi.cos(), s * phi.sin(), z)
}

/// A polygon with one vertex in each of `jitter.len()` equal sectors of the circle.
pub fn circle_polygon(center: Vec3, normal: Vec3, radius: f32, jitter: &[f32]) -> CirclePolygon {
    let n = jitter.len();
    let (u, v) = normal.any_orthonormal_pair();
    // Vertex i sits in the i-th of n equal sectors: angles strictly increase, so convex.
    let angles: Vec<f64> = jitter
        .iter()
        .enumerate()
        .map(|(i, j)| std::f64::consts::TAU * (i as f64 + 0.8 * *j as f64 + 0.1) / n as f64)
        .collect();
    let vertices = angles
        .iter()
        .map(|&a| center + radius * (u * a.cos() as f32 + v * a.sin() as f32))
        .collect();
    let mut area = 0.0;
    for i in 0..n {
        let next = if i + 1 == n {
            angles[0] + std::f64::consts::TAU
        } else {
            angles[i + 1]
        };
        area += (next - angles[i]).sin();
    }
    let area = (0.5 * f64::from(radius).powi(2) * area) as f32;
    CirclePolygon {
        vertices,
        normal: u.cross(v),
        center,
        radius,
        area,
    }
}

/// Convex polygons of 3–8 vertices, radius 0.2–1, centred within 1 of the origin.
pub fn arb_polygon() -> impl Strategy<Value = CirclePolygon> {
    (
        prop::array::uniform3(-1.0f32..1.0),
        (0.0f32..1.0, 0.0f32..1.0),
        0.2f32..1.0,
        prop::collection::vec(0.0f32..1.0, 3..9),
    )
        .prop_map(|(c, (a, b), r, jitter)| circle_polygon(Vec3::from_array(c), unit(a, b), r, &jitter))
}

/// Relative difference scaled by `scale` (for comparing areas against a polygon's size).
pub fn close(a: f32, b: f32, scale: f32, rel: f32) -> bool {
    (a - b).abs() <= rel * scale.max(f32::MIN_POSITIVE)
}
