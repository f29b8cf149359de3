//! Sutherland–Hodgman clipping of a convex polygon against an axis-aligned box or a plane,
//! into caller-owned buffers so that the hot path allocates nothing once warm.

use crate::aabb::Aabb;
use crate::plane::Plane;
use crate::polygon::polygon_vector_area;
use glam::{DVec2, Vec3};

/// Reusable buffers for clipping; keep one per thread.
#[derive(Clone, Debug, Default)]
pub struct ClipScratch {
    a: Vec<Vec3>,
    b: Vec<Vec3>,
    plane2d: Vec<DVec2>,
}

impl ClipScratch {
    /// Empty scratch; grows on first use.
    pub fn new() -> Self {
        Self::default()
    }

    /// The buffer of in-plane coordinates used by the ball area.
    pub(crate) fn plane2d_mut(&mut self) -> &mut Vec<DVec2> {
        &mut self.plane2d
    }
}

/// Clips the convex `polygon` to the closed `aabb` and returns the clipped polygon, which
/// borrows `scratch`. Degenerate results (fewer than 3 vertices, or zero area as when the
/// polygon only touches the box along an edge) are empty.
///
/// Each of the six planes is applied in turn (Sutherland–Hodgman). Points created on a box
/// face get that face's coordinate exactly, so clipped polygons tile a box split into
/// sub-boxes without gaps. Non-finite input gives an empty result or non-finite vertices,
/// never a panic.
pub fn clip_polygon_to_aabb<'s>(polygon: &[Vec3], aabb: &Aabb, scratch: &'s mut ClipScratch) -> &'s [Vec3] {
    clip_into_scratch(polygon, &Aabb::from_points(polygon), aabb, scratch);
    if polygon_vector_area(&scratch.a) == Vec3::ZERO {
        scratch.a.clear();
    }
    &scratch.a[..]
}

/// Sutherland–Hodgman into `scratch.a`, without the zero-area check (callers that compute
/// the area anyway skip it). `bounds` are the polygon's bounds: planes that no vertex lies
/// beyond are skipped (clipping by one plane never moves vertices out through another).
pub(crate) fn clip_into_scratch<'s>(
    polygon: &[Vec3],
    bounds: &Aabb,
    aabb: &Aabb,
    scratch: &'s mut ClipScratch,
) -> &'s [Vec3] {
    let ClipScratch { a, b, .. } = scratch;
    a.clear();
    if polygon.len() < 3 || aabb.is_empty() {
        return &a[..];
    }
    a.extend_from_slice(polygon);
    // Each plane adds at most one vertex.
    b.reserve(polygon.len() + 6);
    a.reserve(6);
    // (polygon already inside this plane, the clipper for it)
    let steps: [(bool, ClipByPlane); 6] = [
        (bounds.min.x >= aabb.min.x, clip_axis::<0, true>),
        (bounds.max.x <= aabb.max.x, clip_axis::<0, false>),
        (bounds.min.y >= aabb.min.y, clip_axis::<1, true>),
        (bounds.max.y <= aabb.max.y, clip_axis::<1, false>),
        (bounds.min.z >= aabb.min.z, clip_axis::<2, true>),
        (bounds.max.z <= aabb.max.z, clip_axis::<2, false>),
    ];
    let planes = [
        aabb.min.x, aabb.max.x, aabb.min.y, aabb.max.y, aabb.min.z, aabb.max.z,
    ];
    for ((all_inside, clip), bound) in steps.into_iter().zip(planes) {
        if all_inside {
            continue;
        }
        clip(a, b, bound);
        std::mem::swap(a, b);
        if a.len() < 3 {
            a.clear();
            break;
        }
    }
    &a[..]
}

/// Clips a polygon by one box plane at the given coordinate, from the first buffer into the
/// second.
type ClipByPlane = fn(&[Vec3], &mut Vec<Vec3>, f32);

/// Keeps the part of `src` with `p[AXIS] >= bound` (`ABOVE`) or `p[AXIS] <= bound`, writing
/// it to `dst`. Monomorphised per plane: the axis and side are constants in the loop.
fn clip_axis<const AXIS: usize, const ABOVE: bool>(src: &[Vec3], dst: &mut Vec<Vec3>, bound: f32) {
    dst.clear();
    let Some(&last) = src.last() else {
        return;
    };
    let distance = |p: Vec3| if ABOVE { p[AXIS] - bound } else { bound - p[AXIS] };
    let mut prev = last;
    let mut prev_d = distance(prev);
    for &cur in src {
        let cur_d = distance(cur);
        if (prev_d > 0.0 && cur_d < 0.0) || (prev_d < 0.0 && cur_d > 0.0) {
            let mut hit = intersect(prev, prev_d, cur, cur_d);
            hit[AXIS] = bound;
            dst.push(hit);
        }
        if cur_d >= 0.0 {
            dst.push(cur);
        }
        prev = cur;
        prev_d = cur_d;
    }
}

/// The point where the segment from `p` (signed distance `dp`) to `q` (`dq`, opposite sign)
/// crosses the plane. Interpolates from the end on the kept side (`d ≥ 0`), so an edge
/// shared by two polygons, walked in opposite directions, is cut at the same point in both.
fn intersect(p: Vec3, dp: f32, q: Vec3, dq: f32) -> Vec3 {
    let (from, d_from, to, d_to) = if dp >= 0.0 { (p, dp, q, dq) } else { (q, dq, p, dp) };
    let t = d_from / (d_from - d_to);
    if t.is_finite() {
        from + (to - from) * t.clamp(0.0, 1.0)
    } else {
        from
    }
}

/// Splits the convex `polygon` by `plane` into the part on the positive side (`front`,
/// `signed_distance >= 0`) and the part on the negative side (`back`). Both buffers are
/// cleared first; a side that gets fewer than 3 vertices is left empty. Vertices on the
/// plane go to both sides, so the two parts share the cut edge exactly.
///
/// This is the tool for cutting a face along a contact line before rebuilding a mesh.
pub fn split_convex_polygon_by_plane(
    polygon: &[Vec3],
    plane: &Plane,
    front: &mut Vec<Vec3>,
    back: &mut Vec<Vec3>,
) {
    front.clear();
    back.clear();
    let Some(&last) = polygon.last() else {
        return;
    };
    if polygon.len() < 3 {
        return;
    }
    let mut prev = last;
    let mut prev_d = plane.signed_distance(prev);
    for &cur in polygon {
        let cur_d = plane.signed_distance(cur);
        if (prev_d > 0.0 && cur_d < 0.0) || (prev_d < 0.0 && cur_d > 0.0) {
            let hit = intersect(prev, prev_d, cur, cur_d);
            front.push(hit);
            back.push(hit);
        }
        if cur_d >= 0.0 {
            front.push(cur);
        }
        if cur_d <= 0.0 {
            back.push(cur);
        }
        prev = cur;
        prev_d = cur_d;
    }
    if front.len() < 3 {
        front.clear();
    }
    if back.len() < 3 {
        back.clear();
    }
}
