//! Shared by the GGX tests: directions and frames built independently of the crate, the
//! materials they test, and midpoint-rule quadratures over the hemisphere and sphere.
#![allow(dead_code)]

use pm_trace::bsdf::{MIN_ALPHA, MetallicRoughness};
use pm_trace::glam::{DVec3, Vec3};
use std::f64::consts::PI;

/// A unit direction at polar angle `acos(cos_theta)` from `n`, turned by `phi` about it (a
/// frame by Gram–Schmidt, independent of the crate's).
pub fn direction(n: Vec3, cos_theta: f64, phi: f64) -> Vec3 {
    let (t, b) = frame(n);
    let s = (1.0 - cos_theta * cos_theta).max(0.0).sqrt();
    let (t, b, n) = (t.as_dvec3(), b.as_dvec3(), n.as_dvec3());
    (t * (s * phi.cos()) + b * (s * phi.sin()) + n * cos_theta)
        .normalize()
        .as_vec3()
}

pub fn frame(n: Vec3) -> (Vec3, Vec3) {
    let helper = if n.x.abs() < 0.9 { Vec3::X } else { Vec3::Y };
    let t = (helper - n * helper.dot(n)).normalize();
    (t, n.cross(t))
}

/// A local direction (z up) at `cos θ`, `φ`.
pub fn local(cos_theta: f64, phi: f64) -> Vec3 {
    let s = (1.0 - cos_theta * cos_theta).max(0.0).sqrt();
    DVec3::new(s * phi.cos(), s * phi.sin(), cos_theta).as_vec3()
}

pub const TILTED: Vec3 = Vec3::new(0.48, -0.6, 0.64);

pub fn material(base: Vec3, metallic: f32, roughness: f32) -> MetallicRoughness {
    MetallicRoughness::new(base, metallic, roughness).unwrap()
}

/// The midpoint rule over the upper hemisphere in `(θ, φ)`, with `θ = atan(s · tan ψ)` for
/// `ψ` uniform (a change of variables that puts the nodes where a lobe of width `s` about
/// the pole is, with its Jacobian), `nt × np` nodes: `∫ g(ω) dω`.
pub fn hemisphere_integral(s: f64, nt: usize, np: usize, mut g: impl FnMut(Vec3) -> f64) -> f64 {
    let mut total = 0.0;
    for i in 0..nt {
        let psi = (i as f64 + 0.5) / nt as f64 * PI / 2.0;
        let theta = (s * psi.tan()).atan();
        let jacobian = s / psi.cos().powi(2) / (1.0 + (s * psi.tan()).powi(2));
        let weight = theta.sin() * jacobian * (PI / 2.0 / nt as f64) * (2.0 * PI / np as f64);
        for j in 0..np {
            let phi = (j as f64 + 0.5) / np as f64 * 2.0 * PI;
            total += g(local(theta.cos(), phi)) * weight;
        }
    }
    total
}

/// The midpoint rule over the whole sphere in polar coordinates about the unit `axis`, with
/// `θ = 2 atan(s · tan ψ)` for `ψ` uniform in `[0, π/2)` (nodes gathered near the axis for
/// `s < 1`, with the Jacobian): `∫ g(ω) dω`.
pub fn sphere_integral_about(
    axis: Vec3,
    s: f64,
    nt: usize,
    np: usize,
    mut g: impl FnMut(Vec3) -> f64,
) -> f64 {
    let mut total = 0.0;
    for i in 0..nt {
        let psi = (i as f64 + 0.5) / nt as f64 * PI / 2.0;
        let theta = 2.0 * (s * psi.tan()).atan();
        let jacobian = 2.0 * s / psi.cos().powi(2) / (1.0 + (s * psi.tan()).powi(2));
        let weight = theta.sin() * jacobian * (PI / 2.0 / nt as f64) * (2.0 * PI / np as f64);
        for j in 0..np {
            let phi = (j as f64 + 0.5) / np as f64 * 2.0 * PI;
            total += g(direction(axis, theta.cos(), phi)) * weight;
        }
    }
    total
}

pub const ALPHAS: [f32; 5] = [MIN_ALPHA, 0.01, 0.09, 0.36, 1.0];
