//! Vertex welding through a spatial hash grid: exporters split vertices along seams, and
//! twins can only be found once the copies are one vertex again.

use crate::fast_hash::{FastHashMap, FastHashSet};
use glam::Vec3;

const NONE: u32 = u32::MAX;

/// Cells per side of the blocks that record where representatives lie (a power of two: a
/// cell's block is its key shifted right).
const BLOCK_SHIFT: u32 = 2;

/// Welds `positions` (all finite): returns the welded positions and, for each input
/// position, the index of its welded vertex.
///
/// Greedy: each position joins the vertex an identical earlier position joined, else the
/// first earlier representative within `tolerance` (Euclidean) it finds, else becomes a
/// representative itself. With a positive tolerance the grid has cells of that size, so
/// only the 27 cells around a point are searched (O(n) expected), and only when a block of
/// 4³ cells ([`BLOCK_SHIFT`]) that the 27 overlap holds a representative at all: vertices of a model
/// lie far apart at the tolerance's scale, so most points are settled by one to eight block
/// lookups instead of 27 cell lookups, with the same result.
/// A zero, negative or non-finite tolerance welds only bit-identical positions (`-0 = +0`).
pub(crate) fn weld(positions: &[Vec3], tolerance: f32) -> (Vec<Vec3>, Vec<u32>) {
    if tolerance > 0.0 && tolerance.is_finite() {
        weld_within(positions, tolerance)
    } else {
        weld_exact(positions)
    }
}

fn weld_exact(positions: &[Vec3]) -> (Vec<Vec3>, Vec<u32>) {
    // Grown as vertices are found, not sized by the positions: exported meshes repeat each
    // position up to five times, and room for every one would hold four times what is used.
    let mut ids: FastHashMap<[u32; 3], u32> = FastHashMap::default();
    let mut welded = Vec::new();
    let remap = positions
        .iter()
        .map(|&p| {
            let p = p + Vec3::ZERO; // -0.0 + 0.0 = +0.0
            *ids.entry([p.x.to_bits(), p.y.to_bits(), p.z.to_bits()])
                .or_insert_with(|| {
                    welded.push(p);
                    (welded.len() - 1) as u32
                })
        })
        .collect();
    (welded, remap)
}

fn weld_within(positions: &[Vec3], tolerance: f32) -> (Vec<Vec3>, Vec<u32>) {
    let inv_cell = 1.0 / tolerance;
    let tolerance2 = tolerance * tolerance;
    // Head of each cell's chain of representatives; `next` links the chain.
    // Both maps grow as they fill, not sized by the positions: exported meshes repeat each
    // position up to five times, and room for every one would hold four times what is used
    // (13 MB of the contact split's peak on the obvhs kitchen).
    let mut heads: FastHashMap<[i64; 3], u32> = FastHashMap::default();
    // The blocks that hold a representative.
    let mut blocks: FastHashSet<[i64; 3]> = FastHashSet::default();
    // The vertex of each position seen, by its bits: a copy of a position joins the vertex the
    // first copy joined (the search below could find a representative made in between, within
    // the tolerance too, and split the copies), and exported meshes repeat most positions, so
    // most points are settled by one lookup instead of 27.
    let mut copies: FastHashMap<[u32; 3], u32> = FastHashMap::default();
    let mut next: Vec<u32> = Vec::new();
    let mut welded: Vec<Vec3> = Vec::new();
    let mut remap = Vec::with_capacity(positions.len());
    for &p in positions {
        let q = p + Vec3::ZERO; // -0.0 + 0.0 = +0.0
        let bits = [q.x.to_bits(), q.y.to_bits(), q.z.to_bits()];
        if let Some(&id) = copies.get(&bits) {
            remap.push(id);
            continue;
        }
        let cell = (p * inv_cell).floor();
        // Points whose cells do not fit an i64: there one float step is far larger than the
        // tolerance, so only identical points can weld (the copies above), rather than being
        // crammed into the outermost cells, where a long chain would make welding quadratic.
        let found = if cell.abs().max_element() < 4.0e18 {
            let key = [cell.x as i64, cell.y as i64, cell.z as i64];
            let near = if any_block_around(&blocks, key) {
                nearest_in_cells(&heads, &next, &welded, key, p, tolerance2)
            } else {
                NONE
            };
            match near {
                NONE => {
                    let id = welded.len() as u32;
                    welded.push(p);
                    next.push(heads.insert(key, id).unwrap_or(NONE));
                    blocks.insert(key.map(|k| k >> BLOCK_SHIFT));
                    id
                }
                rep => rep,
            }
        } else {
            welded.push(p);
            next.push(NONE);
            (welded.len() - 1) as u32
        };
        copies.insert(bits, found);
        remap.push(found);
    }
    (welded, remap)
}

/// Whether any block that one of the 27 cells around `key` lies in holds a representative:
/// along each axis the cells `k - 1 ..= k + 1` lie in one block or two.
fn any_block_around(blocks: &FastHashSet<[i64; 3]>, key: [i64; 3]) -> bool {
    let span = key.map(|k| (k.wrapping_sub(1) >> BLOCK_SHIFT, k.wrapping_add(1) >> BLOCK_SHIFT));
    let [(x0, x1), (y0, y1), (z0, z1)] = span;
    for x in [x0, x1].into_iter().take(1 + (x1 != x0) as usize) {
        for y in [y0, y1].into_iter().take(1 + (y1 != y0) as usize) {
            for z in [z0, z1].into_iter().take(1 + (z1 != z0) as usize) {
                if blocks.contains(&[x, y, z]) {
                    return true;
                }
            }
        }
    }
    false
}

/// The first representative within the tolerance (`tolerance2`, squared) of `p` in the 27
/// cells around `key`, or [`NONE`].
fn nearest_in_cells(
    heads: &FastHashMap<[i64; 3], u32>,
    next: &[u32],
    welded: &[Vec3],
    key: [i64; 3],
    p: Vec3,
    tolerance2: f32,
) -> u32 {
    for dx in -1..=1i64 {
        for dy in -1..=1i64 {
            for dz in -1..=1i64 {
                let k = [
                    key[0].wrapping_add(dx),
                    key[1].wrapping_add(dy),
                    key[2].wrapping_add(dz),
                ];
                let mut rep = heads.get(&k).copied().unwrap_or(NONE);
                while rep != NONE {
                    if welded[rep as usize].distance_squared(p) <= tolerance2 {
                        return rep;
                    }
                    rep = next[rep as usize];
                }
            }
        }
    }
    NONE
}

#[cfg(test)]
mod tests {
    use super::*;
    use proptest::prelude::*;

    proptest! {
        /// Every point lies within the tolerance of its vertex, and no two vertices are that
        /// close (checked by brute force over all pairs). Points are drawn on a coarse lattice
        /// plus jitter so that many fall near cell borders and near each other.
        #[test]
        fn welded_vertices_cover_points_and_stay_apart(
            points in prop::collection::vec(
                (prop::array::uniform3(-3i32..3), prop::array::uniform3(-1.0f32..1.0)), 0..200),
            tolerance in prop_oneof![Just(0.0f32), 0.01f32..0.5],
        ) {
            let positions: Vec<Vec3> = points
                .iter()
                .map(|&(l, j)| Vec3::new(l[0] as f32, l[1] as f32, l[2] as f32) * 0.25 + Vec3::from_array(j) * 0.1)
                .collect();
            let (welded, remap) = weld(&positions, tolerance);
            prop_assert_eq!(remap.len(), positions.len());
            for (p, &v) in positions.iter().zip(&remap) {
                prop_assert!(welded[v as usize].distance(*p) <= tolerance);
            }
            for i in 0..welded.len() {
                for j in 0..i {
                    prop_assert!(welded[i].distance(welded[j]) > tolerance);
                }
            }
        }
    }

    /// The greedy rule restated by brute force over every representative: a point takes the
    /// vertex its first identical copy took, else the representative within the tolerance
    /// whose cell comes first in the 27-cell order around the point's cell (offsets −1, 0, 1
    /// by x, then y, then z), the newest first within a cell (each cell's chain starts at its
    /// newest), else becomes one.
    fn weld_by_brute_force(positions: &[Vec3], tolerance: f32) -> (Vec<Vec3>, Vec<u32>) {
        let cell = |p: Vec3| (p * (1.0 / tolerance)).floor().to_array().map(|c| c as i64);
        let mut welded: Vec<Vec3> = Vec::new();
        let mut remap: Vec<u32> = Vec::new();
        for (i, &p) in positions.iter().enumerate() {
            let bits = |q: Vec3| (q + Vec3::ZERO).to_array().map(f32::to_bits);
            if let Some(j) = (0..i).find(|&j| bits(positions[j]) == bits(p)) {
                remap.push(remap[j]);
                continue;
            }
            let key = cell(p);
            let order = |r: usize| {
                let rk = cell(welded[r]);
                let d = [0, 1, 2].map(|a| rk[a] - key[a]);
                let near =
                    d.iter().all(|d| d.abs() <= 1) && welded[r].distance_squared(p) <= tolerance * tolerance;
                near.then(|| ((d[0] + 1) * 9 + (d[1] + 1) * 3 + (d[2] + 1), std::cmp::Reverse(r)))
            };
            match (0..welded.len()).filter_map(|r| order(r).map(|o| (o, r))).min() {
                Some((_, r)) => remap.push(r as u32),
                None => {
                    welded.push(p);
                    remap.push((welded.len() - 1) as u32);
                }
            }
        }
        (welded, remap)
    }

    proptest! {
        /// The grid with its blocks welds exactly as the brute-force statement of its rule, on
        /// points in clusters (tolerance apart and less, across cell and block borders, with
        /// exact copies) and spread out, near the origin and 10⁷ m from it.
        #[test]
        fn welding_matches_the_rule_by_brute_force(
            points in prop::collection::vec(
                (prop::array::uniform3(-6i32..6), prop::array::uniform3(-1.5f32..1.5), 0..3usize), 0..160),
            tolerance in 0.001f32..0.02,
            // Near the origin, and far out on negative and positive keys (where an f32 step
            // is coarser than the tolerance, so most points are copies).
            offset in prop_oneof![Just(0.0f32), Just(-3.3e3), Just(1.0e7)],
        ) {
            let mut positions: Vec<Vec3> = Vec::new();
            for &(l, j, copy) in &points {
                if copy == 0 && !positions.is_empty() {
                    positions.push(positions[l[0].unsigned_abs() as usize % positions.len()]);
                    continue;
                }
                let lattice = Vec3::new(l[0] as f32, l[1] as f32, l[2] as f32) * (2.5 * tolerance);
                positions.push(Vec3::splat(offset) + lattice + Vec3::from_array(j) * tolerance);
            }
            prop_assert_eq!(weld(&positions, tolerance), weld_by_brute_force(&positions, tolerance));
        }
    }

    /// Copies of one position weld to one vertex, even when a representative made between them
    /// lies within the tolerance too (here 0.9 t on either side of the copies): the second
    /// copy used to find the later representative first and split the vertex.
    #[test]
    fn copies_of_a_position_weld_to_the_same_vertex() {
        let t = 1e-3;
        let x = |v: f32| Vec3::new(v, 0.5, 0.5);
        let (welded, remap) = weld(&[x(0.9 * t), x(0.0), x(-0.9 * t), x(0.0)], t);
        assert_eq!(welded.len(), 2);
        assert_eq!(remap[1], remap[3], "{remap:?}");
    }

    #[test]
    fn points_across_a_cell_border_weld() {
        let t = 1e-3;
        let (welded, remap) = weld(
            &[
                Vec3::splat(t * 0.9999),
                Vec3::splat(t * 1.0001),
                Vec3::splat(-0.0),
            ],
            t,
        );
        assert_eq!(welded.len(), 2);
        assert_eq!(remap, [0, 0, 1]);
        let (welded, remap) = weld(&[Vec3::ZERO, Vec3::splat(-0.0), Vec3::X], 0.0);
        assert_eq!((welded.len(), remap), (2, vec![0, 0, 1]));
    }
}
