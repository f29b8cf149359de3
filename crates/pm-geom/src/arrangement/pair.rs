//! How two convex faces meet: the segments along which each must be cut, found from the signed
//! distances of each face's vertices to the other's plane (piercing, an edge lying in the other
//! face, an overlap in one plane, or a near-contact closer than the gap tolerance).

use super::continuation::NO_FACE;
use super::face::{Face, segment_inside, separated};
use crate::aabb::Aabb;
use crate::clip::clip_convex_polygon_by_distance;
use glam::Vec3;

/// Faces whose normals are closer than this (in `1 − |cos|`, about 0.8°) count as parallel.
const PARALLEL: f32 = 1e-4;

/// Faces across an edge whose normals are closer than this (cos 30°) continue one surface: a
/// near-contact is not outlined along the edge between them when both come that close.
const CONTINUED_COS: f32 = 0.866_025_4;

/// What kind of meeting a cut comes from.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(super) enum Meeting {
    /// The faces pass through each other: the segment is inside both.
    Piercing,
    /// An edge of one face lies in the other's plane, across its inside (a wall standing on a
    /// floor).
    InPlane,
    /// The faces lie in one plane and overlap.
    CoplanarOverlap,
    /// The faces do not meet but come closer than the gap tolerance.
    NearContact,
}

/// A segment along which one face is cut; `barrier` when no photon map may cross it.
#[derive(Clone, Copy, Debug)]
pub(super) struct Constraint {
    pub(super) a: Vec3,
    pub(super) b: Vec3,
    pub(super) barrier: bool,
}

/// What one pair gave: cuts on each face, the kind of meeting, and for coplanar faces facing
/// the same way, that the second overlaps the first (its overlapped pieces are duplicates).
#[derive(Debug, Default)]
pub(super) struct PairOutcome {
    pub(super) on_first: Vec<Constraint>,
    pub(super) on_second: Vec<Constraint>,
    pub(super) meeting: Option<Meeting>,
    /// Same-facing overlap in one plane: the second face's overlapped part is hidden by the
    /// first (the first of two copies is the one kept).
    pub(super) second_hidden: bool,
}

/// Reusable buffers for [`meet`].
#[derive(Debug, Default)]
pub(super) struct PairScratch {
    da: Vec<f32>,
    db: Vec<f32>,
    clip: Vec<Vec3>,
    clip_next: Vec<Vec3>,
    section_a: Vec<Vec3>,
    section_b: Vec<Vec3>,
}

/// Finds how faces `a` and `b` (two of `faces`) meet, with `tolerance` the distance under which
/// points coincide and `gap` (≥ `tolerance`) the distance under which faces count as touching.
pub(super) fn meet(
    faces: &[Option<Face>],
    a: &Face,
    b: &Face,
    tolerance: f32,
    gap: f32,
    scratch: &mut PairScratch,
    out: &mut PairOutcome,
) {
    out.on_first.clear();
    out.on_second.clear();
    out.meeting = None;
    out.second_hidden = false;
    // Neighbours in one plane, facing the same way (a tessellated floor): most pairs of a
    // scene, settled without the distances.
    let cos = a.normal.dot(b.normal);
    if 1.0 - cos <= PARALLEL
        && (a.offset - b.offset).abs() <= tolerance
        && (separated(a, b, tolerance) || separated(b, a, tolerance))
    {
        return;
    }
    scratch.da.clear();
    scratch.da.extend(a.vertices.iter().map(|&p| b.distance(p)));
    scratch.db.clear();
    scratch.db.extend(b.vertices.iter().map(|&p| a.distance(p)));
    let beyond = |d: &[f32]| d.iter().all(|&x| x > gap) || d.iter().all(|&x| x < -gap);
    if beyond(&scratch.da) || beyond(&scratch.db) {
        return;
    }
    let max_a = scratch.da.iter().fold(0.0f32, |m, d| m.max(d.abs()));
    let max_b = scratch.db.iter().fold(0.0f32, |m, d| m.max(d.abs()));
    if 1.0 - cos.abs() <= PARALLEL && max_a <= gap && max_b <= gap {
        let separation = max_a.max(max_b);
        meet_in_plane(faces, a, b, cos, separation, tolerance, gap, scratch, out);
        return;
    }
    // A face wholly on one side of the other's plane, beyond the tolerance, has no section
    // there (what `section` would find empty), so most pairs skip the sections.
    let clear = |d: &[f32]| d.iter().all(|&x| x > tolerance) || d.iter().all(|&x| x < -tolerance);
    let (a_clear, b_clear) = (clear(&scratch.da), clear(&scratch.db));
    if !a_clear && !b_clear {
        section(a.vertices, &scratch.da, b, tolerance, &mut scratch.section_a);
        section(b.vertices, &scratch.db, a, tolerance, &mut scratch.section_b);
    }
    match (a_clear, b_clear) {
        (false, false) => meet_across(a, b, tolerance, scratch, out),
        (true, _) => near_contact(
            faces,
            a,
            &scratch.da,
            b,
            tolerance,
            gap,
            &mut out.on_second,
            &mut out.meeting,
        ),
        (false, true) => near_contact(
            faces,
            b,
            &scratch.db,
            a,
            tolerance,
            gap,
            &mut out.on_first,
            &mut out.meeting,
        ),
    }
}

/// Faces in planes that cross: the common part of each face's section by the other's plane.
fn meet_across(a: &Face, b: &Face, tolerance: f32, scratch: &PairScratch, out: &mut PairOutcome) {
    let Some(line) = a.normal.cross(b.normal).try_normalize() else {
        return;
    };
    let extent = |points: &[Vec3]| {
        let (mut lo, mut hi) = ((f32::INFINITY, Vec3::ZERO), (f32::NEG_INFINITY, Vec3::ZERO));
        for &p in points {
            let t = line.dot(p);
            if t < lo.0 {
                lo = (t, p);
            }
            if t > hi.0 {
                hi = (t, p);
            }
        }
        (lo, hi)
    };
    let ((a0, pa0), (a1, pa1)) = extent(&scratch.section_a);
    let ((b0, pb0), (b1, pb1)) = extent(&scratch.section_b);
    let (s0, p0) = if a0 >= b0 { (a0, pa0) } else { (b0, pb0) };
    let (s1, p1) = if a1 <= b1 { (a1, pa1) } else { (b1, pb1) };
    if s1 - s0 <= tolerance {
        return;
    }
    let middle = (p0 + p1) * 0.5;
    if !(a.covers(middle, tolerance) && b.covers(middle, tolerance)) {
        // Planes a few degrees apart, each face within the tolerance of the other's plane over
        // a stretch: the two sections overlap along the line but lie side by side, apart (two
        // letters on one panel, one a sliver whose plane is tilted by rounding).
        return;
    }
    let on_border_a = a.distance_to_border(middle) <= tolerance;
    let on_border_b = b.distance_to_border(middle) <= tolerance;
    if on_border_a && on_border_b {
        // Edge against edge: the faces share (part of) an edge, which welding links.
        return;
    }
    let constraint = Constraint {
        a: p0,
        b: p1,
        barrier: true,
    };
    if !on_border_a {
        out.on_first.push(constraint);
    }
    if !on_border_b {
        out.on_second.push(constraint);
    }
    out.meeting = Some(if on_border_a || on_border_b {
        Meeting::InPlane
    } else {
        Meeting::Piercing
    });
}

/// Parallel faces within the gap of each other: their overlap, and the overlap's edges that
/// run inside each face as cuts of that face.
#[allow(clippy::too_many_arguments)]
fn meet_in_plane(
    faces: &[Option<Face>],
    a: &Face,
    b: &Face,
    cos: f32,
    separation: f32,
    tolerance: f32,
    gap: f32,
    scratch: &mut PairScratch,
    out: &mut PairOutcome,
) {
    if cos > 0.0 && separation > tolerance {
        // A panel or a lamp mounted a little in front of a wall, facing the same way: the
        // slit behind it is left alone (light barely enters it, and nothing shows it).
        return;
    }
    if separated(a, b, tolerance) || separated(b, a, tolerance) {
        return; // side by side in one plane (neighbours across a shared edge, most often)
    }
    // A projected into B's plane, clipped to B's inward half-planes.
    scratch.clip.clear();
    scratch.clip.extend(a.vertices.iter().map(|&p| b.project(p)));
    let n = b.vertices.len();
    for i in 0..n {
        let (p, q) = (b.vertices[i], b.vertices[(i + 1) % n]);
        let Some(inward) = b.normal.cross(q - p).try_normalize() else {
            continue;
        };
        let offset = inward.dot(p);
        clip_convex_polygon_by_distance(
            &scratch.clip,
            |v| inward.dot(v) - offset,
            0.0,
            &mut scratch.clip_next,
        );
        std::mem::swap(&mut scratch.clip, &mut scratch.clip_next);
        if scratch.clip.len() < 3 {
            return;
        }
    }
    let overlap = &scratch.clip;
    let area = crate::polygon::polygon_area(overlap);
    let size = Aabb::from_points(overlap).diagonal();
    if area <= tolerance * size {
        return; // touching along an edge or at a point
    }
    let barrier = cos < 0.0;
    let m = overlap.len();
    for i in 0..m {
        let (p, q) = (overlap[i], overlap[(i + 1) % m]);
        if p.distance(q) <= tolerance {
            continue;
        }
        let middle = (p + q) * 0.5;
        // Faces facing each other are outlined where the contact ends, not along the edges
        // inside a surface that goes on touching (a tessellated box bottom on a floor).
        let inside_contact = |face: &Face, other: &Face, point: Vec3| {
            barrier
                && face
                    .edge_at(point, tolerance)
                    .is_some_and(|edge| continued_in_plane(faces, face, edge, other, gap))
        };
        if b.distance_to_border(middle) > tolerance && !inside_contact(a, b, a.project(middle)) {
            out.on_second.push(Constraint { a: p, b: q, barrier });
        }
        let (pa, qa) = (a.project(p), a.project(q));
        if a.distance_to_border(a.project(middle)) > tolerance && !inside_contact(b, a, middle) {
            out.on_first.push(Constraint {
                a: pa,
                b: qa,
                barrier,
            });
        }
    }
    out.meeting = Some(if separation <= tolerance {
        Meeting::CoplanarOverlap
    } else {
        Meeting::NearContact
    });
    if !barrier {
        // Copies in one plane facing the same way: the later one's overlapped part is hidden.
        out.second_hidden = true;
    }
}

/// Face `far` does not reach `near`'s plane: each of its edges within the gap of that plane is
/// projected onto it, and the part across `near`'s inside becomes a cut of `near` — unless the
/// face across that edge continues `far`'s surface and comes as close on the same side, so the
/// edge lies inside the region that comes close, not on its outline (a tessellated panel over a
/// floor cuts the floor along the panel's outline, not along each of its triangles).
#[allow(clippy::too_many_arguments)]
fn near_contact(
    faces: &[Option<Face>],
    far: &Face,
    distances: &[f32],
    near: &Face,
    tolerance: f32,
    gap: f32,
    cuts: &mut Vec<Constraint>,
    meeting: &mut Option<Meeting>,
) {
    if separated(far, near, tolerance) {
        return; // its shadow on the plane misses `near` (most candidate pairs)
    }
    let n = far.vertices.len();
    for i in 0..n {
        let j = (i + 1) % n;
        if distances[i].abs() > gap || distances[j].abs() > gap {
            continue;
        }
        let (p, q) = (near.project(far.vertices[i]), near.project(far.vertices[j]));
        if let Some((c0, c1)) = segment_inside(p, q, near, tolerance)
            && !continued_within_gap(faces, far, i, distances[i], near, tolerance, gap)
        {
            cuts.push(Constraint {
                a: c0,
                b: c1,
                barrier: true,
            });
            *meeting = Some(Meeting::NearContact);
        }
    }
}

/// Whether edge `edge` of `far` lies inside the region where `far`'s surface comes close to
/// `near`, not on its outline: the face across it lies within the gap of `near`'s plane on the
/// side of `far` (`side`, the signed distance of one of `far`'s vertices; `far` does not reach
/// the plane), and either continues `far`'s surface (normals within 30°) or, seen from `near`,
/// goes on past the edge rather than folding back over `far` (its shadow on `near`'s plane lies
/// on the edge's other side, or on the edge's line: the cap of raised lettering and its walls).
#[allow(clippy::too_many_arguments)]
fn continued_within_gap(
    faces: &[Option<Face>],
    far: &Face,
    edge: usize,
    side: f32,
    near: &Face,
    tolerance: f32,
    gap: f32,
) -> bool {
    let across = far.across[edge];
    if across == NO_FACE {
        return false;
    }
    let Some(next) = &faces[across as usize] else {
        return false;
    };
    let within_gap = next.vertices.iter().all(|&v| {
        let d = near.distance(v);
        d.abs() <= gap && (d > 0.0) == (side > 0.0)
    });
    within_gap
        && (next.normal.dot(far.normal) >= CONTINUED_COS || goes_on_past(far, edge, next, near, tolerance))
}

/// Whether `next` (across edge `edge` of `far`), projected onto `near`'s plane, lies on the
/// other side of the projected edge's line than `far` does, or on that line within the
/// tolerance; false when `far`'s own projection is a sliver along the edge (a wall standing on
/// `near`), whose edges are the outline.
fn goes_on_past(far: &Face, edge: usize, next: &Face, near: &Face, tolerance: f32) -> bool {
    let n = far.vertices.len();
    let (p, q) = (
        near.project(far.vertices[edge]),
        near.project(far.vertices[(edge + 1) % n]),
    );
    let Some(outward) = near.normal.cross(q - p).try_normalize() else {
        return false;
    };
    let offset = |v: Vec3| outward.dot(near.project(v) - p);
    let far_side = far
        .vertices
        .iter()
        .map(|&v| offset(v))
        .fold(0.0f32, |m, d| if d.abs() > m.abs() { d } else { m });
    if far_side.abs() <= tolerance {
        return false;
    }
    next.vertices
        .iter()
        .all(|&v| offset(v) * far_side.signum() <= tolerance)
}

/// Whether the face across edge `edge` of `face` continues its surface (normals within 30°,
/// wound alike) and lies within the gap of `other`'s plane, parallel to it as `face` is.
fn continued_in_plane(faces: &[Option<Face>], face: &Face, edge: usize, other: &Face, gap: f32) -> bool {
    let across = face.across[edge];
    if across == NO_FACE {
        return false;
    }
    let Some(next) = &faces[across as usize] else {
        return false;
    };
    next.normal.dot(face.normal) >= CONTINUED_COS
        && 1.0 - next.normal.dot(other.normal).abs() <= PARALLEL
        && next.vertices.iter().all(|&v| other.distance(v).abs() <= gap)
}

/// The points where `polygon` meets the plane of `other`: vertices within the tolerance of it
/// (projected onto it) and crossings of edges from one side to the other.
fn section(polygon: &[Vec3], distances: &[f32], other: &Face, tolerance: f32, out: &mut Vec<Vec3>) {
    out.clear();
    let n = polygon.len();
    for i in 0..n {
        let j = (i + 1) % n;
        let (di, dj) = (distances[i], distances[j]);
        if di.abs() <= tolerance {
            out.push(other.project(polygon[i]));
        } else if (di > tolerance && dj < -tolerance) || (di < -tolerance && dj > tolerance) {
            out.push(polygon[i].lerp(polygon[j], di / (di - dj)));
        }
    }
}
