//! A bounding-volume hierarchy over boxes, answering "which boxes overlap this box" without
//! allocating: the overlap index of [`crate::PolygonSet`] and of the T-junction points (median
//! splits), and the arrangement's broad phase, barrier segments and sealed pieces (surface-area
//! splits, [`BoundsBvh::build_sah`]).

use crate::aabb::Aabb;
use glam::Vec3;

mod sah;

/// Items per leaf; small leaves suit the few-polygons-per-query pattern of the estimator.
pub(crate) const MAX_LEAF: usize = 4;
/// Traversal stack depth. Median splits give depth ≤ log2(n / MAX_LEAF) + 1 < 32 for any
/// `u32` item count, the surface-area build at most 56 (it splits at the median past depth
/// 24), and at most one sibling per level waits on the stack.
const STACK: usize = 64;

/// A node: a leaf when `count > 0` (items `order[first..first + count]`), otherwise an
/// inner node whose children are `self + 1` and `first`.
#[derive(Clone, Copy, Debug)]
struct Node {
    min: Vec3,
    max: Vec3,
    first: u32,
    count: u32,
}

/// Binary BVH over item boxes, built by median splits on the widest centroid axis
/// ([`BoundsBvh::build_by`]) or by the binned surface-area heuristic ([`BoundsBvh::build_sah`]).
#[derive(Clone, Debug, Default)]
pub(crate) struct BoundsBvh {
    /// Most items per leaf.
    leaf: usize,
    nodes: Vec<Node>,
    order: Vec<u32>,
}

impl BoundsBvh {
    /// The hierarchy of median splits over `count` items whose boxes `box_of` gives (non-empty
    /// and finite), with up to `leaf` items per leaf (at least 1), asked again each time one is
    /// needed (it must give the same box each time): for boxes made from other data (padded
    /// points), so that no table of them is held. `count` must fit in `u32`. Quick to build and
    /// good for boxes of like sizes; [`Self::build_sah`] for a mix of long and small ones.
    pub(crate) fn build_by(count: usize, box_of: impl Fn(u32) -> Aabb, leaf: usize) -> Self {
        let leaf = leaf.max(1);
        let mut bvh = BoundsBvh {
            leaf,
            nodes: Vec::with_capacity(node_count(count, leaf)),
            order: Vec::new(),
        };
        if count == 0 {
            return bvh;
        }
        // The items are sorted into the leaves' order in place, each beside one coordinate of
        // its box's centre: the one the split of the node it is in sorts by, remade from
        // `box_of` for each node (eight bytes an item, not sixteen, at the split's peak, and
        // one centre an item per level, not one a comparison).
        let mut items: Vec<(f32, u32)> = (0..count as u32).map(|i| (0.0, i)).collect();
        bvh.build_node(&box_of, &mut items, 0);
        bvh.order = items.iter().map(|&(_, i)| i).collect();
        bvh
    }

    /// Appends the subtree over `items` (which start at `offset` in the final order) and
    /// returns its node index.
    fn build_node(&mut self, box_of: &impl Fn(u32) -> Aabb, items: &mut [(f32, u32)], offset: usize) -> u32 {
        let bounds = items.iter().fold(Aabb::EMPTY, |b, &(_, i)| b.union(box_of(i)));
        let index = self.nodes.len();
        self.nodes.push(Node {
            min: bounds.min,
            max: bounds.max,
            first: offset as u32,
            count: items.len() as u32,
        });
        if items.len() <= self.leaf {
            return index as u32;
        }
        let centre = |i: u32| box_of(i).center();
        let centroids = items.iter().fold(Aabb::EMPTY, |b, &(_, i)| b.grow(centre(i)));
        let axis = centroids.size().max_position();
        for item in items.iter_mut() {
            item.0 = centre(item.1)[axis];
        }
        let mid = items.len() / 2;
        items.select_nth_unstable_by(mid, |a, b| a.0.total_cmp(&b.0));
        let (left, right) = items.split_at_mut(mid);
        self.build_node(box_of, left, offset);
        let right_index = self.build_node(box_of, right, offset + mid);
        self.nodes[index].first = right_index;
        self.nodes[index].count = 0;
        index as u32
    }

    /// Calls `f(item)` for every item whose node path overlaps `query`; the caller filters
    /// by the item's own box. Allocates nothing.
    pub(crate) fn for_each_candidate(&self, query: &Aabb, mut f: impl FnMut(u32)) {
        if self.nodes.is_empty() {
            return;
        }
        let mut stack = [0u32; STACK];
        let mut top = 1;
        while top > 0 {
            top -= 1;
            let index = stack[top];
            let node = self.nodes[index as usize];
            if !(node.min.cmple(query.max).all() && query.min.cmple(node.max).all()) {
                continue;
            }
            if node.count > 0 {
                let first = node.first as usize;
                for &item in &self.order[first..first + node.count as usize] {
                    f(item);
                }
            } else if top + 2 <= STACK {
                stack[top] = node.first;
                stack[top + 1] = index + 1;
                top += 2;
            }
        }
    }
}

/// How many nodes the median splits make over `count` items with up to `leaf` per leaf, so
/// that the node table is allocated once at its size. The sizes at one depth differ by at most
/// one, so each depth is at most two (size, how many) pairs.
fn node_count(count: usize, leaf: usize) -> usize {
    if count == 0 {
        return 0;
    }
    let mut nodes = 0;
    let mut level: Vec<(usize, usize)> = vec![(count, 1)];
    while !level.is_empty() {
        let mut next: Vec<(usize, usize)> = Vec::with_capacity(4);
        for &(size, many) in &level {
            nodes += many;
            if size > leaf {
                for half in [size / 2, size - size / 2] {
                    match next.iter_mut().find(|(s, _)| *s == half) {
                        Some((_, m)) => *m += many,
                        None => next.push((half, many)),
                    }
                }
            }
        }
        level = next;
    }
    nodes
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A tiny deterministic generator, so the test needs no dependency.
    fn lcg(state: &mut u64) -> f32 {
        *state = state
            .wrapping_mul(6364136223846793005)
            .wrapping_add(1442695040888963407);
        (*state >> 40) as f32 / (1u64 << 24) as f32
    }

    /// 1,000 small boxes in a 10 m cube, and (for the surface-area build's reason to be) as
    /// many again long and thin along the axes, as the segments where faces meet are.
    fn mixed_boxes(count: usize) -> Vec<Aabb> {
        let mut s = 7;
        let mut r = || lcg(&mut s);
        (0..count)
            .map(|k| {
                let c = Vec3::new(r(), r(), r()) * 10.0;
                let size = if k % 2 == 0 {
                    Vec3::new(r(), r(), r()) * 0.5
                } else {
                    [Vec3::X, Vec3::Y, Vec3::Z][k % 3] * r() * 8.0 + Vec3::splat(1e-3)
                };
                Aabb::new(c, c + size)
            })
            .collect()
    }

    /// The median-split hierarchy over a table of boxes.
    fn median(boxes: &[Aabb], leaf: usize) -> BoundsBvh {
        BoundsBvh::build_by(boxes.len(), |i| boxes[i as usize], leaf)
    }

    /// Asserts that the boxes `bvh`'s candidates for `q` overlap are those a scan of all
    /// `boxes` finds, and returns how many there are.
    fn overlaps_as_brute_force_finds(bvh: &BoundsBvh, boxes: &[Aabb], q: &Aabb, case: &str) -> usize {
        let mut got = Vec::new();
        bvh.for_each_candidate(q, |i| {
            if boxes[i as usize].overlaps(q) {
                got.push(i)
            }
        });
        got.sort_unstable();
        let want: Vec<u32> = (0..boxes.len() as u32)
            .filter(|&i| boxes[i as usize].overlaps(q))
            .collect();
        assert_eq!(got, want, "{case}");
        got.len()
    }

    #[test]
    fn candidates_match_brute_force_overlaps() {
        let boxes = mixed_boxes(2000);
        let mut s = 11;
        let mut r = || lcg(&mut s);
        // Every leaf size the crate builds with (the estimator's, the broad phase's, the
        // T-junction points'), and one item a leaf; by median and by surface-area splits.
        for leaf in [1, MAX_LEAF, 12, 16] {
            let trees = [
                ("median", median(&boxes, leaf)),
                ("sah", BoundsBvh::build_sah(&boxes, leaf)),
            ];
            for (kind, bvh) in trees {
                for _ in 0..200 {
                    let q = Aabb::cube(Vec3::new(r(), r(), r()) * 10.0, r() * 2.0);
                    overlaps_as_brute_force_finds(&bvh, &boxes, &q, &format!("{kind}, leaves of {leaf}"));
                }
            }
        }
    }

    /// The surface-area build makes the same tree on one thread and on many (its halves past
    /// `SAH_PARALLEL_MIN` are built beside each other), and one whose queries visit fewer
    /// nodes than the median build's where long boxes mix with small ones.
    #[test]
    fn the_surface_area_tree_is_the_same_on_any_thread_count_and_visits_fewer_nodes() {
        let boxes = mixed_boxes(20_000);
        let on = |threads: usize| {
            let pool = rayon::ThreadPoolBuilder::new()
                .num_threads(threads)
                .build()
                .unwrap();
            pool.install(|| BoundsBvh::build_sah(&boxes, 12))
        };
        let one = on(1);
        for threads in [2, 8] {
            let many = on(threads);
            assert_eq!(one.order, many.order, "{threads} threads");
            let bits = |b: &BoundsBvh| -> Vec<[u32; 8]> {
                b.nodes
                    .iter()
                    .map(|n| {
                        let [a, b, c] = n.min.to_array().map(f32::to_bits);
                        let [d, e, f] = n.max.to_array().map(f32::to_bits);
                        [a, b, c, d, e, f, n.first, n.count]
                    })
                    .collect()
            };
            assert_eq!(bits(&one), bits(&many), "{threads} threads");
        }
        let visits = |bvh: &BoundsBvh| {
            let mut s = 3;
            let mut visited = 0usize;
            for _ in 0..2000 {
                let p = Vec3::new(lcg(&mut s), lcg(&mut s), lcg(&mut s)) * 10.0;
                let mut stack = vec![0u32];
                while let Some(i) = stack.pop() {
                    visited += 1;
                    let n = bvh.nodes[i as usize];
                    if n.count == 0 && n.min.cmple(p).all() && p.cmple(n.max).all() {
                        stack.extend([n.first, i + 1]);
                    }
                }
            }
            visited
        };
        let (median, sah) = (visits(&median(&boxes, 12)), visits(&one));
        assert!(
            sah < median,
            "surface-area tree visits {sah} nodes, median tree {median}"
        );
    }

    /// The same brute-force check at the ends of the operating range: the boxes a micrometre
    /// across at the origin, and ten kilometres across ten thousand kilometres from it (where
    /// a float step is a metre and the binned centres crowd into few distinct values).
    #[test]
    fn candidates_match_brute_force_at_micrometres_and_far_from_the_origin() {
        for (scale, origin) in [(1e-7, Vec3::ZERO), (1e3, Vec3::new(1e7, -6e6, 3e6))] {
            let boxes: Vec<Aabb> = mixed_boxes(3000)
                .iter()
                .map(|b| Aabb::new(origin + b.min * scale, origin + b.max * scale))
                .collect();
            let mut s = 5;
            let mut r = || lcg(&mut s);
            for (kind, bvh) in [
                ("median", median(&boxes, 12)),
                ("sah", BoundsBvh::build_sah(&boxes, 12)),
            ] {
                let mut found = 0;
                for _ in 0..200 {
                    let q = Aabb::cube(origin + Vec3::new(r(), r(), r()) * 10.0 * scale, r() * scale);
                    let case = format!("{kind}, scale {scale}, origin {origin}");
                    found += overlaps_as_brute_force_finds(&bvh, &boxes, &q, &case);
                }
                assert!(
                    found > 1000,
                    "{kind}, scale {scale}: too few overlaps to test ({found})"
                );
            }
        }
    }

    #[test]
    fn identical_boxes_and_empty_input_work() {
        for (kind, build) in [
            ("median", median as fn(&[Aabb], usize) -> BoundsBvh),
            ("sah", BoundsBvh::build_sah),
        ] {
            let empty = build(&[], MAX_LEAF);
            empty.for_each_candidate(&Aabb::cube(Vec3::ZERO, 1.0), |_| {
                panic!("{kind}: empty tree reported an item")
            });
            // Coincident boxes no split separates: each is reported once.
            let boxes = vec![Aabb::cube(Vec3::ONE, 0.1); 5000];
            let bvh = build(&boxes, MAX_LEAF);
            let mut seen = vec![0u32; boxes.len()];
            bvh.for_each_candidate(&Aabb::cube(Vec3::ONE, 0.01), |i| seen[i as usize] += 1);
            assert!(seen.iter().all(|&n| n == 1), "{kind}: {seen:?}");
        }
    }

    /// The node table is sized exactly: as many nodes as the build makes, for leaf sizes and
    /// counts around the powers of two.
    #[test]
    fn node_count_is_the_number_built() {
        for leaf in [1, 4, 12] {
            for count in (0..300).chain([1023, 1024, 1025, 4097]) {
                let boxes: Vec<Aabb> = (0..count)
                    .map(|i| Aabb::cube(Vec3::splat(i as f32), 0.5))
                    .collect();
                let bvh = median(&boxes, leaf);
                assert_eq!(
                    bvh.nodes.len(),
                    node_count(count, leaf),
                    "{count} items, leaves of {leaf}"
                );
                assert_eq!(bvh.nodes.capacity(), bvh.nodes.len());
            }
        }
    }
}
