//! Groups of items linked where their points meet, and each group's size: the chains of
//! barriers whose size decides which slits close (`slits`).

use crate::fast_hash::FastHashMap;
use glam::Vec3;

/// For each of `items` (segments, polygons), the size (bounding-box diagonal) of the group it is
/// linked into: items are linked where a point of one lies at a point of another (a chain of
/// barriers end to end). Points are linked through a grid of cells one tolerance wide: the
/// points in one cell and in neighbouring cells are linked, so points within the tolerance
/// always are and points farther apart than about three and a half tolerances never are. The work is one pass
/// over the points and one over the occupied cells (27 look-ups each), however they crowd.
pub(super) fn linked_extents<P: AsRef<[Vec3]>>(items: &[P], tolerance: f32) -> Vec<f32> {
    let n = items.len();
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
    let mut first: FastHashMap<[i64; 3], usize> = FastHashMap::default();
    for (i, s) in items.iter().enumerate() {
        for &p in s.as_ref() {
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
    let mut bounds: FastHashMap<usize, (Vec3, Vec3)> = FastHashMap::default();
    for (i, s) in items.iter().enumerate() {
        let r = root(&mut parent, i);
        let Some(&start) = s.as_ref().first() else {
            continue;
        };
        let b = bounds.entry(r).or_insert((start, start));
        for &p in s.as_ref() {
            b.0 = b.0.min(p);
            b.1 = b.1.max(p);
        }
    }
    (0..n)
        .map(|i| {
            let r = root(&mut parent, i);
            bounds.get(&r).map_or(0.0, |(lo, hi)| lo.distance(*hi))
        })
        .collect()
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
        let extents = linked_extents(&barriers, 1e-5);
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
            assert_eq!(linked_extents(&barriers, 1e-3), brute(&barriers, 1e-3));
        }
    }
}
