//! Balls, and the exact area of a convex polygon inside a ball (polygon ∩ disc in its plane).
//!
//! The ball cuts the polygon's plane in a disc of radius `ρ = sqrt(R² − d²)`. The area of
//! polygon ∩ disc is the sum over the polygon's edges of the *signed* area of the triangle
//! (disc centre, edge) intersected with the disc; each term is a triangle, a circular sector,
//! or a sector–triangle–sector chain where the edge crosses the circle. The terms are summed
//! in f64, which keeps the sum exact to f32 precision even when large sectors cancel or
//! the ball is nearly tangent to the plane.

use crate::clip::ClipScratch;
use crate::polygon::polygon_normal;
use glam::{DVec2, Vec3};
use std::cmp::Ordering::{Greater, Less};

/// A solid ball.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Ball {
    /// Centre.
    pub center: Vec3,
    /// Radius (≥ 0).
    pub radius: f32,
}

impl Ball {
    /// A ball from centre and radius.
    pub const fn new(center: Vec3, radius: f32) -> Self {
        Ball { center, radius }
    }
}

/// Area of the convex planar `polygon` inside `ball`, exactly (up to rounding).
///
/// `normal` is the polygon's unit normal; when it is zero or non-finite the polygon's own
/// normal is used. The result is finite and `≥ 0` for any input (0 for degenerate polygons,
/// non-finite coordinates, a negative radius, or a plane that misses the ball); a tangent
/// ball gives 0 and the disc centre may lie on an edge or a vertex.
pub fn polygon_area_in_ball(polygon: &[Vec3], normal: Vec3, ball: &Ball, scratch: &mut ClipScratch) -> f32 {
    if polygon.len() < 3 || ball.radius.partial_cmp(&0.0) != Some(Greater) {
        return 0.0;
    }
    let Some(n) = normal.try_normalize().or_else(|| polygon_normal(polygon)) else {
        return 0.0;
    };
    // f64 from here on: near-tangent balls subtract nearly equal squares.
    let n = n.as_dvec3();
    let center = ball.center.as_dvec3();
    let distance = n.dot(center - polygon[0].as_dvec3());
    let radius = f64::from(ball.radius);
    let rho2 = radius * radius - distance * distance;
    if rho2.partial_cmp(&0.0) != Some(Greater) {
        return 0.0;
    }
    // In-plane coordinates centred on the disc (the projection drops the normal part).
    let (u, v) = n.any_orthonormal_pair();
    let points = scratch.plane2d_mut();
    points.clear();
    let mut min = DVec2::INFINITY;
    let mut max = DVec2::NEG_INFINITY;
    let mut farthest2 = 0.0f64;
    let mut twice_polygon_area = 0.0;
    let in_plane = |p: Vec3| {
        let w = p.as_dvec3() - center;
        DVec2::new(w.dot(u), w.dot(v))
    };
    let mut prev = in_plane(polygon[polygon.len() - 1]);
    for &p in polygon {
        let q = in_plane(p);
        min = min.min(q);
        max = max.max(q);
        farthest2 = farthest2.max(q.length_squared());
        twice_polygon_area += prev.perp_dot(q);
        points.push(q);
        prev = q;
    }
    let polygon_area = (0.5 * twice_polygon_area).abs();
    let area = if farthest2 <= rho2 {
        // Every vertex in the disc, so the whole convex polygon is.
        polygon_area
    } else {
        // The disc misses the polygon's bounding rectangle: nothing inside.
        let nearest = DVec2::ZERO.max(min).min(max);
        if nearest.length_squared().partial_cmp(&rho2) != Some(Less) {
            return 0.0;
        }
        // The intersection never exceeds the polygon or the disc; the clamp also bounds the
        // rounding residue of huge, degenerate input.
        polygon_disc_area(points, rho2)
            .abs()
            .min(polygon_area)
            .min(std::f64::consts::PI * rho2)
    } as f32;
    if area.is_finite() { area } else { 0.0 }
}

/// Signed area of the simple 2-D `polygon` intersected with the disc of squared radius
/// `rho2` centred at the origin (positive for counter-clockwise vertices).
pub(crate) fn polygon_disc_area(polygon: &[DVec2], rho2: f64) -> f64 {
    let Some(&last) = polygon.last() else {
        return 0.0;
    };
    let mut prev = last;
    let mut sum = 0.0;
    for &cur in polygon {
        sum += edge_disc_area(prev, cur, rho2);
        prev = cur;
    }
    sum
}

/// Signed area of triangle (origin, a, b) ∩ disc(origin, sqrt(rho2)).
fn edge_disc_area(a: DVec2, b: DVec2, rho2: f64) -> f64 {
    let a2 = a.length_squared();
    let b2 = b.length_squared();
    if a2 <= rho2 && b2 <= rho2 {
        return 0.5 * a.perp_dot(b);
    }
    let d = b - a;
    let dd = d.length_squared();
    if dd == 0.0 {
        return 0.0;
    }
    // |a + t d|² = rho2  ⇔  dd t² + 2 (a·d) t + (a² − rho2) = 0
    let half_b = a.dot(d);
    let discriminant = half_b * half_b - dd * (a2 - rho2);
    if discriminant <= 0.0 {
        return sector_area(a, b, rho2);
    }
    let s = discriminant.sqrt();
    let t1 = (-half_b - s) / dd;
    let t2 = (-half_b + s) / dd;
    if t1 >= 1.0 || t2 <= 0.0 {
        return sector_area(a, b, rho2);
    }
    let p1 = a + d * t1.max(0.0);
    let p2 = a + d * t2.min(1.0);
    sector_area(a, p1, rho2) + 0.5 * p1.perp_dot(p2) + sector_area(p2, b, rho2)
}

/// Signed area of the circular sector between the directions of `a` and `b`.
fn sector_area(a: DVec2, b: DVec2, rho2: f64) -> f64 {
    0.5 * rho2 * a.perp_dot(b).atan2(a.dot(b))
}
