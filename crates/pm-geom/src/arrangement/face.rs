//! One input face of an arrangement as the pair tests read it: its plane, its neighbours across
//! its edges, its padded bounds, and where points and segments lie against it.

use crate::aabb::Aabb;
use glam::Vec3;

/// One input face: its vertices, the faces across its edges (indices into the arrangement's
/// faces, [`NO_FACE`](super::continuation::NO_FACE) where none), unit normal, plane offset and bounds padded by the gap.
#[derive(Clone, Copy, Debug)]
pub(super) struct Face<'a> {
    pub(super) vertices: &'a [Vec3],
    pub(super) across: &'a [u32],
    pub(super) normal: Vec3,
    pub(super) offset: f32,
    pub(super) bounds: Aabb,
}

impl Face<'_> {
    pub(super) fn distance(&self, p: Vec3) -> f32 {
        self.normal.dot(p) - self.offset
    }

    pub(super) fn project(&self, p: Vec3) -> Vec3 {
        p - self.normal * self.distance(p)
    }

    /// The edge that `p` (in or near the face's plane) lies on within `tolerance`, if any.
    pub(super) fn edge_at(&self, p: Vec3, tolerance: f32) -> Option<usize> {
        let n = self.vertices.len();
        (0..n).find(|&i| distance_to_segment(p, self.vertices[i], self.vertices[(i + 1) % n]) <= tolerance)
    }

    /// Whether `p` (in or near the face's plane) lies inside the face or within `tolerance` of
    /// it, seen along the normal.
    pub(super) fn covers(&self, p: Vec3, tolerance: f32) -> bool {
        let n = self.vertices.len();
        (0..n).all(|i| {
            let (a, b) = (self.vertices[i], self.vertices[(i + 1) % n]);
            self.normal
                .cross(b - a)
                .try_normalize()
                .is_none_or(|inward| inward.dot(p - a) >= -tolerance)
        })
    }

    /// Distance from `p` (in or near the face's plane) to the face's border.
    pub(super) fn distance_to_border(&self, p: Vec3) -> f32 {
        let n = self.vertices.len();
        (0..n)
            .map(|i| distance_to_segment(p, self.vertices[i], self.vertices[(i + 1) % n]))
            .fold(f32::INFINITY, f32::min)
    }
}

/// Whether some edge of `b` has all of `a`'s vertices on its outer side (in `b`'s plane): then
/// the two do not overlap.
pub(super) fn separated(a: &Face, b: &Face, tolerance: f32) -> bool {
    let n = b.vertices.len();
    (0..n).any(|i| {
        let (p, q) = (b.vertices[i], b.vertices[(i + 1) % n]);
        // `inward` has the edge's length; compare squares rather than normalise it.
        let inward = b.normal.cross(q - p);
        let reach = tolerance * tolerance * inward.length_squared();
        a.vertices.iter().all(|&v| {
            let d = inward.dot(v - p);
            d <= 0.0 || d * d <= reach
        })
    })
}

/// The part of segment `pq` (in `face`'s plane) inside `face`, when it runs across its inside
/// for more than the tolerance and not only along its border.
pub(super) fn segment_inside(p: Vec3, q: Vec3, face: &Face, tolerance: f32) -> Option<(Vec3, Vec3)> {
    let length = p.distance(q);
    if length <= tolerance {
        return None;
    }
    // Clip the parameter range against every edge's inward half-plane, once exactly (for the
    // end points) and once shrunk by the tolerance (to require the inside).
    let (mut t0, mut t1) = (0.0f32, 1.0f32);
    let (mut s0, mut s1) = (0.0f32, 1.0f32);
    let polygon = face.vertices;
    for i in 0..polygon.len() {
        let (a, b) = (polygon[i], polygon[(i + 1) % polygon.len()]);
        let Some(inward) = face.normal.cross(b - a).try_normalize() else {
            continue;
        };
        let (fp, fq) = (inward.dot(p - a), inward.dot(q - a));
        clip_range(fp, fq, &mut t0, &mut t1);
        clip_range(fp - tolerance, fq - tolerance, &mut s0, &mut s1);
    }
    if t1 <= t0 || (s1 - s0) * length <= tolerance {
        return None;
    }
    Some((p.lerp(q, t0), p.lerp(q, t1)))
}

/// Narrows `[t0, t1]` to where the linear function from `fp` (t = 0) to `fq` (t = 1) is ≥ 0.
fn clip_range(fp: f32, fq: f32, t0: &mut f32, t1: &mut f32) {
    if fp < 0.0 && fq < 0.0 {
        *t1 = -1.0;
    } else if fp < 0.0 {
        *t0 = t0.max(fp / (fp - fq));
    } else if fq < 0.0 {
        *t1 = t1.min(fp / (fp - fq));
    }
}

/// Distance from `p` to the segment `ab`.
pub(super) fn distance_to_segment(p: Vec3, a: Vec3, b: Vec3) -> f32 {
    let ab = b - a;
    let len2 = ab.length_squared();
    let t = if len2 > 0.0 {
        ((p - a).dot(ab) / len2).clamp(0.0, 1.0)
    } else {
        0.0
    };
    p.distance(a + ab * t)
}
