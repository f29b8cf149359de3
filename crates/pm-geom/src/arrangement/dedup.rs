//! Barrier segments reported once: a segment whose ends lie within the tolerance of an
//! earlier one's (either way round) is the same meeting line seen from the other face.

use crate::fast_hash::FastHashMap;
use glam::Vec3;

/// `segments` without repeats, in order of first appearance. Two segments are the same when
/// each end of one lies within `tolerance` of an end of the other (either way round); ends are
/// matched through a grid of cells four tolerances wide, so a repeat whose ends differ by a
/// rounding step and straddle a cell border may stay (it covers the same edges, harmlessly).
pub(super) fn dedup_segments(segments: Vec<[Vec3; 2]>, tolerance: f32) -> Vec<[Vec3; 2]> {
    let cell = 4.0 * tolerance;
    let key = |p: Vec3| {
        let q = (p / cell).round();
        [q.x as i64, q.y as i64, q.z as i64]
    };
    let same = |s: &[Vec3; 2], t: &[Vec3; 2]| {
        let near = |a: Vec3, b: Vec3| a.distance(b) <= tolerance;
        (near(s[0], t[0]) && near(s[1], t[1])) || (near(s[0], t[1]) && near(s[1], t[0]))
    };
    let mut seen: FastHashMap<([i64; 3], [i64; 3]), Vec<usize>> = FastHashMap::default();
    let mut out: Vec<[Vec3; 2]> = Vec::with_capacity(segments.len());
    for s in segments {
        let (a, b) = (key(s[0]), key(s[1]));
        let k = if a <= b { (a, b) } else { (b, a) };
        let kept = seen.entry(k).or_default();
        if kept.iter().any(|&i| same(&out[i], &s)) {
            continue;
        }
        kept.push(out.len());
        out.push(s);
    }
    // Kept as long as the partition's record: at the size found, not the size given.
    out.shrink_to_fit();
    out
}
