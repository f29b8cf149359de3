//! Which barriers close a slit against a face's border: a barrier that stops within the gap of
//! the border runs on to it, as long as the slit is narrow next to the barrier line that makes
//! it. A wall that stops just short of the floor closes the strip under it; the outline of a
//! 3 mm letter on a 2 cm button does not cut the button from border to border.

use super::cut::Cut;
use super::pair::{Constraint, Face, segment_inside};
use glam::Vec3;
use std::collections::HashMap;

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
    let extents = chain_extents(barriers, tolerance);
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

/// For each of `barriers`, the size (bounding-box diagonal) of its chain: the barriers linked to
/// it end to end. Ends are linked through a grid of cells one tolerance wide: the ends in one
/// cell and in neighbouring cells are linked, so ends within the tolerance always are and ends
/// farther apart than about three and a half tolerances never are. The work is one pass over
/// the ends and one over the occupied cells (27 look-ups each), however the ends crowd.
pub(super) fn chain_extents(barriers: &[[Vec3; 2]], tolerance: f32) -> Vec<f32> {
    let n = barriers.len();
    let mut parent: Vec<usize> = (0..n).collect();
    fn root(parent: &mut [usize], mut i: usize) -> usize {
        while parent[i] != i {
            parent[i] = parent[parent[i]];
            i = parent[i];
        }
        i
    }
    fn link(parent: &mut [usize], i: usize, j: usize) {
        let (a, b) = (root(parent, i), root(parent, j));
        // The smaller root wins, so the chains are the same in any order.
        parent[a.max(b)] = a.min(b);
    }
    let cell = tolerance.max(f32::MIN_POSITIVE);
    let key = |p: Vec3| {
        let q = (p / cell).floor();
        [q.x as i64, q.y as i64, q.z as i64]
    };
    // Each occupied cell, with the first barrier that has an end in it.
    let mut first: HashMap<[i64; 3], usize> = HashMap::new();
    for (i, s) in barriers.iter().enumerate() {
        for &p in s {
            let j = *first.entry(key(p)).or_insert(i);
            link(&mut parent, i, j);
        }
    }
    let mut cells: Vec<([i64; 3], usize)> = first.iter().map(|(&k, &i)| (k, i)).collect();
    cells.sort_unstable();
    for &([x, y, z], i) in &cells {
        for dx in -1..=1 {
            for dy in -1..=1 {
                for dz in -1..=1 {
                    if let Some(&j) = first.get(&[x + dx, y + dy, z + dz]) {
                        link(&mut parent, i, j);
                    }
                }
            }
        }
    }
    let mut bounds: HashMap<usize, (Vec3, Vec3)> = HashMap::new();
    for (i, s) in barriers.iter().enumerate() {
        let r = root(&mut parent, i);
        let b = bounds.entry(r).or_insert((s[0], s[0]));
        for &p in s {
            b.0 = b.0.min(p);
            b.1 = b.1.max(p);
        }
    }
    (0..n)
        .map(|i| {
            let (lo, hi) = bounds[&root(&mut parent, i)];
            lo.distance(hi)
        })
        .collect()
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

#[cfg(test)]
mod tests {
    use super::*;
    use glam::vec3;

    /// Brute force: chains by repeated linking of all pairs.
    fn brute(barriers: &[[Vec3; 2]], tolerance: f32) -> Vec<f32> {
        let n = barriers.len();
        let mut chain: Vec<usize> = (0..n).collect();
        loop {
            let mut changed = false;
            for i in 0..n {
                for j in 0..n {
                    let linked = barriers[i]
                        .iter()
                        .any(|&p| barriers[j].iter().any(|&q| p.distance(q) <= tolerance));
                    if linked && chain[i] != chain[j] {
                        let m = chain[i].min(chain[j]);
                        chain[i] = m;
                        chain[j] = m;
                        changed = true;
                    }
                }
            }
            if !changed {
                break;
            }
        }
        (0..n)
            .map(|i| {
                let members = (0..n).filter(|&j| chain[j] == chain[i]);
                let (mut lo, mut hi) = (Vec3::splat(f32::MAX), Vec3::splat(f32::MIN));
                for j in members {
                    for p in barriers[j] {
                        lo = lo.min(p);
                        hi = hi.max(p);
                    }
                }
                lo.distance(hi)
            })
            .collect()
    }

    #[test]
    fn a_closed_ring_and_a_loose_segment_are_two_chains() {
        let ring = [
            [vec3(0.0, 0.0, 0.0), vec3(1.0, 0.0, 0.0)],
            [vec3(1.0, 0.0, 0.0), vec3(1.0, 0.0, 1.0)],
            [vec3(1.0, 0.0, 1.0), vec3(0.0, 0.0, 1.0)],
            [vec3(0.0, 0.0, 1.0), vec3(0.0, 0.0, 0.0)],
        ];
        let mut barriers = ring.to_vec();
        // A segment 1 mm off the ring's corner: not linked at a 10 µm tolerance.
        barriers.push([vec3(1.001, 0.0, 1.0), vec3(2.0, 0.0, 1.0)]);
        let extents = chain_extents(&barriers, 1e-5);
        for e in &extents[..4] {
            assert!((e - 2f32.sqrt()).abs() < 1e-6, "{extents:?}");
        }
        assert!((extents[4] - 0.999).abs() < 1e-6, "{extents:?}");
    }

    #[test]
    fn chains_match_brute_force_on_random_segments() {
        let mut state = 0x2545_f491_4f6c_dd1du64;
        let mut next = || {
            state ^= state << 13;
            state ^= state >> 7;
            state ^= state << 17;
            // Coarse coordinates, so that ends often coincide.
            (state % 8) as f32 * 0.25
        };
        for _ in 0..20 {
            let barriers: Vec<[Vec3; 2]> = (0..40)
                .map(|_| [vec3(next(), 0.0, next()), vec3(next(), 0.0, next())])
                .collect();
            assert_eq!(chain_extents(&barriers, 1e-3), brute(&barriers, 1e-3));
        }
    }
}
