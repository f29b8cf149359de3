//! Closed outlines of merged polygons: exact vertex keys for matching shared edges, removal of
//! collinear and doubled-back vertices, and the convexity and area checks a merge must pass.

use glam::{DVec3, Vec3};

/// A vertex compared bit for bit (after the mesh's welding, shared edges have identical
/// endpoints); `-0.0` and `0.0` are the same key.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub(super) struct VertexKey([u32; 3]);

impl VertexKey {
    pub(super) fn of(p: Vec3) -> Self {
        let p = p + Vec3::ZERO; // -0.0 + 0.0 = +0.0
        VertexKey([p.x.to_bits(), p.y.to_bits(), p.z.to_bits()])
    }
}

/// True when dropping `v` from `… u, v, w …` moves the outline by at most `tol`: `v` repeats a
/// neighbour, the outline doubles back on itself (`w == u`), or `v` lies on the line `uw`.
fn redundant(u: Vec3, v: Vec3, w: Vec3, tol: f32) -> bool {
    let (uv, uw) = (v - u, w - u);
    if uv.length() <= tol || (w - v).length() <= tol {
        return true;
    }
    let len = uw.length();
    len <= tol || uv.cross(uw).length() <= tol * len
}

/// Copies `outline` into `out` without its redundant vertices (see [`redundant`]), repeating
/// until none is left; `out` may end with fewer than 3 vertices.
pub(super) fn simplify_outline(outline: &[Vec3], tol: f32, out: &mut Vec<Vec3>) {
    out.clear();
    for &p in outline {
        out.push(p);
        while out.len() >= 3 {
            let n = out.len();
            if !redundant(out[n - 3], out[n - 2], out[n - 1], tol) {
                break;
            }
            out.remove(n - 2);
        }
    }
    // Where the outline closes, the last and first vertices may be redundant too.
    while out.len() >= 3 {
        let n = out.len();
        if redundant(out[n - 2], out[n - 1], out[0], tol) {
            out.pop();
        } else if redundant(out[n - 1], out[0], out[1], tol) {
            out.remove(0);
        } else {
            break;
        }
    }
}

/// Removes exact back-and-forth steps `… x, y, x …` (a shared edge walked both ways after two
/// polygons are joined along it), also across the outline's closing point.
pub(super) fn cancel_spikes(outline: &mut Vec<Vec3>) {
    let mut out: Vec<Vec3> = Vec::with_capacity(outline.len());
    for &p in outline.iter() {
        out.push(p);
        loop {
            let n = out.len();
            if n >= 3 && VertexKey::of(out[n - 3]) == VertexKey::of(out[n - 1]) {
                out.truncate(n - 2);
            } else if n >= 2 && VertexKey::of(out[n - 2]) == VertexKey::of(out[n - 1]) {
                out.pop();
            } else {
                break;
            }
        }
    }
    loop {
        let n = out.len();
        if n >= 3 && VertexKey::of(out[n - 2]) == VertexKey::of(out[0]) {
            out.pop(); // … x, y | x …: drop y and the second x
            out.pop();
        } else if n >= 3 && VertexKey::of(out[n - 1]) == VertexKey::of(out[1]) {
            out.pop(); // … y | x, y …: drop the trailing y and the leading x
            out.remove(0);
        } else if n >= 2 && VertexKey::of(out[n - 1]) == VertexKey::of(out[0]) {
            out.pop();
        } else {
            break;
        }
    }
    *outline = out;
}

/// The signed area of `outline` about `normal`, in `f64` (positive when counter-clockwise
/// seen from the normal's tip).
pub(super) fn signed_area(outline: &[Vec3], normal: Vec3) -> f64 {
    let [first, rest @ ..] = outline else {
        return 0.0;
    };
    let first = first.as_dvec3();
    let mut sum = DVec3::ZERO;
    for pair in rest.windows(2) {
        sum += (pair[0].as_dvec3() - first).cross(pair[1].as_dvec3() - first);
    }
    0.5 * sum.dot(normal.as_dvec3())
}

/// True when `outline` (already simplified) turns left at every vertex about `normal` and
/// winds around exactly once: a strictly convex, simple polygon.
pub(super) fn is_strictly_convex(outline: &[Vec3], normal: Vec3) -> bool {
    let n = outline.len();
    if n < 3 {
        return false;
    }
    let mut turning = 0.0f64;
    for i in 0..n {
        let (u, v, w) = (outline[i], outline[(i + 1) % n], outline[(i + 2) % n]);
        let (a, b) = ((v - u).as_dvec3(), (w - v).as_dvec3());
        let left = a.cross(b).dot(normal.as_dvec3());
        if left <= 0.0 {
            return false;
        }
        turning += left.atan2(a.dot(b));
    }
    (turning - std::f64::consts::TAU).abs() < 1e-3
}

/// True when `merged` is a strictly convex outline whose area equals `area` (the sum of the
/// areas of the polygons it replaces) to a relative `1e-5`.
pub(super) fn accepts(merged: &[Vec3], normal: Vec3, area: f64) -> bool {
    is_strictly_convex(merged, normal) && (signed_area(merged, normal) - area).abs() <= 1e-5 * area
}

#[cfg(test)]
mod tests {
    use super::*;
    use glam::vec3;

    #[test]
    fn collinear_and_repeated_vertices_are_removed_also_across_the_closing_point() {
        let square = [
            vec3(0.5, 0., 0.),
            vec3(1., 0., 0.),
            vec3(1., 0.5, 0.),
            vec3(1., 0.5, 0.),
            vec3(1., 1., 0.),
            vec3(0., 1., 0.),
            vec3(0., 0., 0.),
            vec3(0.25, 0., 0.),
        ];
        let mut out = Vec::new();
        simplify_outline(&square, 1e-6, &mut out);
        assert_eq!(out.len(), 4, "{out:?}");
        assert!((signed_area(&out, Vec3::Z) - 1.0).abs() < 1e-9);
        assert!(is_strictly_convex(&out, Vec3::Z));
        assert!(!is_strictly_convex(&out, -Vec3::Z));
    }

    #[test]
    fn an_outline_walked_back_and_forth_along_a_shared_edge_cancels() {
        // Two unit squares joined along x = 1, their shared edges walked both ways.
        let (a, b, c) = (vec3(1., 0., 0.), vec3(1., 0.5, 0.), vec3(1., 1., 0.));
        let mut outline = vec![vec3(0., 0., 0.), a, b, c, b, a, vec3(2., 0., 0.)];
        cancel_spikes(&mut outline);
        assert_eq!(outline, vec![vec3(0., 0., 0.), a, vec3(2., 0., 0.)]);
    }

    #[test]
    fn an_l_shape_and_a_doubly_wound_star_are_not_convex() {
        let l = [
            vec3(0., 0., 0.),
            vec3(2., 0., 0.),
            vec3(2., 1., 0.),
            vec3(1., 1., 0.),
            vec3(1., 2., 0.),
            vec3(0., 2., 0.),
        ];
        assert!(!is_strictly_convex(&l, Vec3::Z));
        let star: Vec<Vec3> = (0..5)
            .map(|i| {
                let t = i as f32 * 2.0 * std::f32::consts::TAU / 5.0;
                vec3(t.cos(), t.sin(), 0.)
            })
            .collect();
        assert!(!is_strictly_convex(&star, Vec3::Z));
    }
}
