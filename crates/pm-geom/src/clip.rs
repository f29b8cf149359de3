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
/// This is the tool for cutting a face along a contact line before rebuilding a mesh; it is
/// [`split_convex_polygon_by_distance`] with the plane's signed distance and no tolerance.
pub fn split_convex_polygon_by_plane(
    polygon: &[Vec3],
    plane: &Plane,
    front: &mut Vec<Vec3>,
    back: &mut Vec<Vec3>,
) {
    split_convex_polygon_by_distance(polygon, |p| plane.signed_distance(p), 0.0, front, back);
}

/// Splits the convex `polygon` by a plane given as the signed `distance` of a point to it (in
/// the polygon's own plane that is a line, such as `side · p − offset`): the part with
/// `distance ≥ −tolerance` goes to `front`, the part with `distance ≤ tolerance` to `back`.
///
/// Vertices within `tolerance` of the plane go to both sides as they are (not moved onto it);
/// an edge is cut only where its ends lie beyond the tolerance on opposite sides, and the cut
/// point goes to both sides, so the two parts share the cut edge exactly. Each part starts at
/// the first of `polygon`'s vertices it keeps, in the polygon's order. Both buffers are
/// cleared first; a side that gets fewer than 3 vertices is left empty.
pub fn split_convex_polygon_by_distance(
    polygon: &[Vec3],
    distance: impl Fn(Vec3) -> f32,
    tolerance: f32,
    front: &mut Vec<Vec3>,
    back: &mut Vec<Vec3>,
) {
    front.clear();
    back.clear();
    walk_split(polygon, distance, tolerance, |side, p| {
        if side != Side::Back {
            front.push(p);
        }
        if side != Side::Front {
            back.push(p);
        }
    });
    if front.len() < 3 {
        front.clear();
    }
    if back.len() < 3 {
        back.clear();
    }
}

/// Keeps the part of the convex `polygon` where `distance ≥ −tolerance`, into `out` (cleared
/// first): the front part of [`split_convex_polygon_by_distance`], without building the back.
/// Fewer than 3 vertices kept leave `out` empty.
pub fn clip_convex_polygon_by_distance(
    polygon: &[Vec3],
    distance: impl Fn(Vec3) -> f32,
    tolerance: f32,
    out: &mut Vec<Vec3>,
) {
    out.clear();
    walk_split(polygon, distance, tolerance, |side, p| {
        if side != Side::Back {
            out.push(p);
        }
    });
    if out.len() < 3 {
        out.clear();
    }
}

/// Which side of a splitting plane a vertex of a split goes to.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Side {
    Front,
    Back,
    /// On the plane (within the tolerance), or a cut point: both parts.
    Both,
}

/// The one walk of a split: each vertex of `polygon` in order with its side, and after it the
/// cut point of its edge to the next vertex when that edge crosses the plane beyond the
/// tolerance.
fn walk_split(
    polygon: &[Vec3],
    distance: impl Fn(Vec3) -> f32,
    tolerance: f32,
    mut emit: impl FnMut(Side, Vec3),
) {
    let n = polygon.len();
    if n < 3 {
        return;
    }
    let first = distance(polygon[0]);
    let mut dp = first;
    for i in 0..n {
        let p = polygon[i];
        let j = i + 1;
        let dq = if j < n { distance(polygon[j]) } else { first };
        if dp.abs() <= tolerance {
            emit(Side::Both, p);
        } else {
            emit(if dp > 0.0 { Side::Front } else { Side::Back }, p);
            if (dp > tolerance && dq < -tolerance) || (dp < -tolerance && dq > tolerance) {
                emit(Side::Both, p.lerp(polygon[j % n], dp / (dp - dq)));
            }
        }
        dp = dq;
    }
}
