//! Which barriers close a slit against a face's border: a barrier that stops within the gap of
//! the border runs on to it, as long as the slit is narrow next to the barrier line that makes
//! it. A wall that stops just short of the floor closes the strip under it; the outline of a
//! 3 mm letter on a 2 cm button does not cut the button from border to border.

use super::cut::Cut;
use super::face::{Face, segment_inside};
use super::linked::linked_extents;
use super::pair::Constraint;
use glam::Vec3;

/// A slit counts as narrow when it is at most this fraction of the size of the barrier chain
/// that makes it: a wall's footprint is metres long and its slit millimetres wide, while a
/// letter's outline is as small as its distance to the border of the button it sits on.
const NARROW: f32 = 0.1;

/// A barrier found on a face, not yet run on to the border: where its segment went in the
/// face's cuts and in the list of barriers.
#[derive(Clone, Copy, Debug)]
pub(super) struct PendingBarrier {
    pub(super) face: usize,
    /// Index of the cut in the face's cuts, and of the segment's first point in its contacts.
    pub(super) cut: usize,
    pub(super) contact: usize,
    /// Index of the segment in the barriers.
    pub(super) barrier: usize,
}

/// Runs each pending barrier's ends on to its face's border where the slit left is narrower
/// than the gap and than the barrier's chain (its linked barriers' size), in the face's cuts and
/// in `barriers` alike.
pub(super) fn close_slits(
    cuts: &mut [Vec<Cut>],
    barriers: &mut [[Vec3; 2]],
    pending: &[PendingBarrier],
    faces: &[Option<Face>],
    tolerance: f32,
    gap: f32,
) {
    let extents = linked_extents(barriers, tolerance);
    for p in pending {
        let Some(face) = &faces[p.face] else { continue };
        let [a, b] = barriers[p.barrier];
        let reach = gap.min(extents[p.barrier] * NARROW);
        let closed = close_barrier_ends(Constraint { a, b, barrier: true }, face, tolerance, reach);
        barriers[p.barrier] = [closed.a, closed.b];
        let contacts = &mut cuts[p.face][p.cut].contacts;
        contacts[p.contact] = closed.a;
        contacts[p.contact + 1] = closed.b;
    }
}

/// A barrier that stops within `reach` of `face`'s border (along its own line) runs on to the
/// border: a slit that narrow counts as closed, so no map joins around its end (the strip of a
/// back wall under a dividing wall that stops just short of the floor). `reach` is the gap, or
/// the size of the barrier's chain where that is smaller.
pub(super) fn close_barrier_ends(c: Constraint, face: &Face, tolerance: f32, reach: f32) -> Constraint {
    let Some(direction) = (c.b - c.a).try_normalize() else {
        return c;
    };
    let span = face.bounds.diagonal();
    let Some((start, end)) = segment_inside(c.a - direction * span, c.b + direction * span, face, tolerance)
    else {
        return c;
    };
    let a = if c.a.distance(start) <= reach { start } else { c.a };
    let b = if c.b.distance(end) <= reach { end } else { c.b };
    Constraint { a, b, ..c }
}
