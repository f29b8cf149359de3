//! Polygon ∩ ball areas against closed forms (disc inside polygon, polygon inside disc,
//! centre on an edge or a vertex, tangent balls) and against dense grid sampling.

mod common;

use common::{arb_polygon, circle_polygon, close, unit};
use pm_geom::glam::{Vec3, vec3};
use pm_geom::{Ball, ClipScratch, GatherVolume, polygon_area_in_ball};
use proptest::prelude::*;
use std::f32::consts::PI;

fn area(poly: &[Vec3], normal: Vec3, ball: Ball) -> f32 {
    ball.polygon_area_inside(poly, normal, &mut ClipScratch::new())
}

/// A square of side `2 half` centred at `center` in the plane with `normal`.
fn square(center: Vec3, normal: Vec3, half: f32) -> Vec<Vec3> {
    let (u, v) = normal.any_orthonormal_pair();
    [(-1., -1.), (1., -1.), (1., 1.), (-1., 1.)]
        .iter()
        .map(|&(a, b)| center + half * (a * u + b * v))
        .collect()
}

/// Area of polygon ∩ disc by midpoint sampling on an `n × n` grid over the polygon's
/// in-plane bounding square (f64, independent of the edge formula).
fn sampled_area(poly: &[Vec3], normal: Vec3, ball: Ball, n: usize) -> f64 {
    let (u, v) = normal.any_orthonormal_pair();
    let to2 = |p: Vec3| ((p - ball.center).dot(u) as f64, (p - ball.center).dot(v) as f64);
    let pts: Vec<(f64, f64)> = poly.iter().map(|&p| to2(p)).collect();
    let d = normal.dot(ball.center - poly[0]) as f64;
    let rho2 = (ball.radius as f64).powi(2) - d * d;
    let (mut lo, mut hi) = ((f64::MAX, f64::MAX), (f64::MIN, f64::MIN));
    for &(x, y) in &pts {
        lo = (lo.0.min(x), lo.1.min(y));
        hi = (hi.0.max(x), hi.1.max(y));
    }
    let (w, h) = ((hi.0 - lo.0) / n as f64, (hi.1 - lo.1) / n as f64);
    let mut count = 0usize;
    for i in 0..n {
        for j in 0..n {
            let (x, y) = (lo.0 + (i as f64 + 0.5) * w, lo.1 + (j as f64 + 0.5) * h);
            if x * x + y * y > rho2 {
                continue;
            }
            // Inside the convex counter-clockwise polygon: left of every edge.
            let inside = (0..pts.len()).all(|k| {
                let (a, b) = (pts[k], pts[(k + 1) % pts.len()]);
                (b.0 - a.0) * (y - a.1) - (b.1 - a.1) * (x - a.0) >= 0.0
            });
            count += usize::from(inside);
        }
    }
    count as f64 * w * h
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(256))]

    /// A disc well inside a square gives π ρ², with ρ² = R² − d².
    #[test]
    fn disc_inside_polygon_gives_full_disc(
        center in prop::array::uniform3(-3.0f32..3.0),
        dir in (0.0f32..1.0, 0.0f32..1.0),
        offset in prop::array::uniform2(-0.5f32..0.5),
        radius in 0.02f32..0.4,
        // Well-conditioned: near-tangent balls turn f32 input rounding into large ρ² errors.
        height in -0.9f32..0.9,
    ) {
        let normal = unit(dir.0, dir.1);
        let c = Vec3::from_array(center);
        let poly = square(c, normal, 1.0);
        let (u, v) = normal.any_orthonormal_pair();
        let ball = Ball::new(c + offset[0] * u + offset[1] * v + height * radius * normal, radius);
        let rho2 = radius * radius * (1.0 - height * height);
        let expected = PI * rho2;
        let got = area(&poly, normal, ball);
        prop_assert!(close(got, expected, expected, 1e-4), "got {got}, expected {expected}");
    }

    /// A polygon inside the disc keeps its closed-form area.
    #[test]
    fn polygon_inside_disc_gives_polygon_area(poly in arb_polygon(), extra in 0.0f32..2.0, height in -0.9f32..0.9) {
        let rho = poly.radius * 1.0001 + extra;
        let r = rho / (1.0 - height * height).sqrt();
        let ball = Ball::new(poly.center + height * r * poly.normal, r);
        let got = area(&poly.vertices, poly.normal, ball);
        prop_assert!(close(got, poly.area, poly.area, 1e-4), "got {got}, expected {}", poly.area);
    }

    /// Partial overlaps against dense sampling (error bound of the 600² grid ≈ 2e-3).
    #[test]
    fn partial_overlap_matches_dense_sampling(
        poly in arb_polygon(),
        shift in prop::array::uniform2(-1.0f32..1.0),
        radius in 0.1f32..1.0,
        height in -0.7f32..0.7,
    ) {
        let (u, v) = poly.normal.any_orthonormal_pair();
        let center = poly.center + poly.radius * (shift[0] * u + shift[1] * v) + height * radius * poly.normal;
        let ball = Ball::new(center, radius);
        let got = area(&poly.vertices, poly.normal, ball);
        let expected = sampled_area(&poly.vertices, poly.normal, ball, 600) as f32;
        prop_assert!(close(got, expected, poly.area, 4e-3), "got {got}, sampled {expected}");
        prop_assert!(got <= poly.area * (1.0 + 1e-5) && got <= PI * radius * radius * (1.0 + 1e-5));
    }

    /// Any floats: finite, non-negative, never a panic.
    #[test]
    fn arbitrary_input_never_panics_or_gives_nan(
        poly in prop::collection::vec(prop::array::uniform3(prop::num::f32::ANY), 0..8),
        center in prop::array::uniform3(prop::num::f32::ANY),
        radius in prop::num::f32::ANY,
        normal in prop::array::uniform3(prop::num::f32::ANY),
    ) {
        let poly: Vec<Vec3> = poly.into_iter().map(Vec3::from_array).collect();
        let got = area(&poly, Vec3::from_array(normal), Ball::new(Vec3::from_array(center), radius));
        prop_assert!(got.is_finite() && got >= 0.0);
    }
}

#[test]
fn disc_centred_on_an_edge_gives_half_disc() {
    let poly = square(Vec3::ZERO, Vec3::Y, 1.0);
    let mid = (poly[0] + poly[1]) * 0.5;
    for r in [1e-6, 0.1, 0.5, 0.999] {
        let got = area(&poly, Vec3::Y, Ball::new(mid, r));
        assert!(close(got, 0.5 * PI * r * r, PI * r * r, 1e-4), "r {r}: {got}");
    }
}

#[test]
fn disc_centred_on_a_vertex_gives_the_corner_angle_sector() {
    let poly = square(Vec3::ZERO, Vec3::Y, 1.0);
    for r in [1e-6, 0.3, 1.5] {
        let got = area(&poly, Vec3::Y, Ball::new(poly[2], r));
        assert!(close(got, 0.25 * PI * r * r, PI * r * r, 1e-4), "r {r}: {got}");
    }
    // A triangle's 60° corner.
    let tri = circle_polygon(Vec3::ZERO, Vec3::Z, 1.0, &[0.5, 0.5, 0.5]);
    let got = area(&tri.vertices, Vec3::Z, Ball::new(tri.vertices[0], 0.5));
    assert!(close(got, PI / 6.0 * 0.25, 0.25, 1e-4), "{got}");
}

#[test]
fn tangent_and_missing_balls_give_zero() {
    let poly = square(Vec3::ZERO, Vec3::Y, 1.0);
    assert_eq!(area(&poly, Vec3::Y, Ball::new(vec3(0., 0.5, 0.), 0.5)), 0.0);
    assert_eq!(area(&poly, Vec3::Y, Ball::new(vec3(0., -0.6, 0.), 0.5)), 0.0);
    assert_eq!(area(&poly, Vec3::Y, Ball::new(vec3(3., 0., 0.), 0.5)), 0.0);
    assert_eq!(area(&poly, Vec3::Y, Ball::new(vec3(0., 0., 0.), 0.0)), 0.0);
    // Touching the polygon's edge from outside, in its plane.
    assert_eq!(area(&poly, Vec3::Y, Ball::new(vec3(1.5, 0., 0.), 0.5)), 0.0);
}

#[test]
fn flipped_normal_gives_the_same_area() {
    let poly = square(Vec3::ZERO, Vec3::Y, 1.0);
    let ball = Ball::new(vec3(0.8, 0.1, 0.3), 0.6);
    let mut scratch = ClipScratch::new();
    let up = polygon_area_in_ball(&poly, Vec3::Y, &ball, &mut scratch);
    let down = polygon_area_in_ball(&poly, -Vec3::Y, &ball, &mut scratch);
    let derived = polygon_area_in_ball(&poly, Vec3::ZERO, &ball, &mut scratch);
    assert!(up > 0.1 && (up - down).abs() < 1e-6 && (up - derived).abs() < 1e-6);
}
