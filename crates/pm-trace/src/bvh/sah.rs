//! A binned surface-area-heuristic BVH builder (Wald 2007) for the scene BVH. It writes a
//! binary BVH in obvhs's `Bvh2` layout, which obvhs then collapses into its 8-wide `CwBvh`.
//!
//! Why not obvhs's own PLOC builder: on tessellated coplanar walls it made trees whose rays
//! visited ~120 nodes at 240k triangles (~18 at 2.4k), so ray cost grew 5–7× per decade of
//! triangles, and on a triangle fan (60k thin triangles sharing a vertex) it took 17 s. Binned
//! SAH costs O(n) per level and the depth is bounded (object-median splits past
//! [`MAX_SAH_DEPTH`]), so the build is O(n log n) on any input, and it is deterministic: the
//! tree depends only on the primitive bounds, not on the thread count.

use glam::Vec3A;
use obvhs::aabb::Aabb;
use obvhs::bvh2::Bvh2;
use obvhs::bvh2::node::Bvh2Node;

/// Bins per axis.
const BINS: usize = 16;
/// Below this depth splits minimise the SAH; deeper ones split at the object median, so the
/// depth (and the recursion of both this builder and obvhs's converter) stays below
/// `MAX_SAH_DEPTH + log2(n)`.
const MAX_SAH_DEPTH: u32 = 40;
/// Subtrees of at least this many primitives are built in parallel.
const PARALLEL_MIN: usize = 4096;

/// The binary BVH of `bounds` (one primitive per leaf, as obvhs's `CwBvh` converter expects);
/// leaf `first_index`es index its `primitive_indices`. `bounds` must not be empty.
pub(crate) fn build_bvh2(bounds: &[Aabb]) -> Bvh2 {
    let n = bounds.len();
    let centroids: Vec<Vec3A> = bounds.iter().map(|b| (b.min + b.max) * 0.5).collect();
    let mut items: Vec<u32> = (0..n as u32).collect();
    let mut nodes = vec![Bvh2Node::default(); (2 * n).saturating_sub(1)];
    if let Some((root, descendants)) = nodes.split_first_mut() {
        let builder = Builder {
            bounds,
            centroids: &centroids,
        };
        builder.build(root, descendants, 1, &mut items, 0, 0);
    }
    Bvh2 {
        nodes,
        primitive_indices: items,
        ..Default::default()
    }
}

struct Builder<'a> {
    bounds: &'a [Aabb],
    centroids: &'a [Vec3A],
}

impl Builder<'_> {
    /// Builds the subtree of `items` into `node`; its descendants go to `descendants`, which
    /// starts at node index `first_descendant` and holds exactly `2 · items.len() − 2` nodes
    /// (a binary tree with one primitive per leaf), so both halves can be built in parallel.
    fn build(
        &self,
        node: &mut Bvh2Node,
        descendants: &mut [Bvh2Node],
        first_descendant: u32,
        items: &mut [u32],
        first_item: u32,
        depth: u32,
    ) {
        let aabb = items
            .iter()
            .fold(Aabb::empty(), |a, &i| a.union(&self.bounds[i as usize]));
        if items.len() == 1 {
            *node = Bvh2Node::new(aabb, 1, first_item);
            return;
        }
        let mid = self.split(items, depth);
        *node = Bvh2Node::new(aabb, 0, first_descendant);
        let (pair, rest) = descendants.split_at_mut(2);
        let (left, right) = pair.split_at_mut(1);
        let (left_rest, right_rest) = rest.split_at_mut(2 * mid - 2);
        let parallel = items.len() >= PARALLEL_MIN;
        let (left_items, right_items) = items.split_at_mut(mid);
        let build_left = || {
            self.build(
                &mut left[0],
                left_rest,
                first_descendant + 2,
                left_items,
                first_item,
                depth + 1,
            )
        };
        let build_right = || {
            self.build(
                &mut right[0],
                right_rest,
                first_descendant + 2 * mid as u32,
                right_items,
                first_item + mid as u32,
                depth + 1,
            )
        };
        if parallel {
            rayon::join(build_left, build_right);
        } else {
            let (mut build_left, mut build_right) = (build_left, build_right);
            build_left();
            build_right();
        }
    }

    /// Reorders `items` into two non-empty halves and returns the size of the first.
    fn split(&self, items: &mut [u32], depth: u32) -> usize {
        let n = items.len();
        let (lo, hi) = items.iter().fold(
            (Vec3A::splat(f32::INFINITY), Vec3A::splat(f32::NEG_INFINITY)),
            |(lo, hi), &i| {
                let c = self.centroids[i as usize];
                (lo.min(c), hi.max(c))
            },
        );
        let extent = hi - lo;
        if extent.max_element() <= 0.0 {
            // All centroids coincide: any halving is as good as another.
            return n / 2;
        }
        if depth < MAX_SAH_DEPTH
            && let Some((axis, bin)) = self.best_binned_split(items, lo, extent)
        {
            let scale = BINS as f32 / extent[axis];
            let bin_of = |i: u32| bin_index(self.centroids[i as usize][axis], lo[axis], scale);
            let left = partition_in_place(items, |i| bin_of(i) <= bin);
            if left > 0 && left < n {
                return left;
            }
        }
        self.median_split(items, extent)
    }

    /// The (axis, last bin of the left side) of least SAH cost over `BINS` bins per axis, or
    /// `None` when no binned split separates the items.
    fn best_binned_split(&self, items: &[u32], lo: Vec3A, extent: Vec3A) -> Option<(usize, usize)> {
        let mut best: Option<(f32, usize, usize)> = None;
        for axis in 0..3 {
            if extent[axis] <= 0.0 {
                continue;
            }
            let scale = BINS as f32 / extent[axis];
            let mut bins = [(Aabb::empty(), 0u32); BINS];
            for &i in items {
                let b = bin_index(self.centroids[i as usize][axis], lo[axis], scale);
                bins[b].0 = bins[b].0.union(&self.bounds[i as usize]);
                bins[b].1 += 1;
            }
            // right_cost[k]: area × count of bins k+1.. (the right side of a split after bin k).
            let mut right_cost = [0.0f32; BINS];
            let (mut right_box, mut right_count) = (Aabb::empty(), 0u32);
            for k in (1..BINS).rev() {
                right_box = right_box.union(&bins[k].0);
                right_count += bins[k].1;
                right_cost[k - 1] = if right_count > 0 {
                    right_box.half_area() * right_count as f32
                } else {
                    f32::INFINITY
                };
            }
            let (mut left_box, mut left_count) = (Aabb::empty(), 0u32);
            for k in 0..BINS - 1 {
                left_box = left_box.union(&bins[k].0);
                left_count += bins[k].1;
                if left_count == 0 || right_cost[k] == f32::INFINITY {
                    continue;
                }
                let cost = left_box.half_area() * left_count as f32 + right_cost[k];
                if best.is_none_or(|(c, _, _)| cost < c) {
                    best = Some((cost, axis, k));
                }
            }
        }
        best.map(|(_, axis, bin)| (axis, bin))
    }

    /// Halves `items` at the median centroid along the axis of largest centroid extent.
    fn median_split(&self, items: &mut [u32], extent: Vec3A) -> usize {
        let axis = if extent.x >= extent.y && extent.x >= extent.z {
            0
        } else if extent.y >= extent.z {
            1
        } else {
            2
        };
        let mid = items.len() / 2;
        items.select_nth_unstable_by(mid, |&a, &b| {
            self.centroids[a as usize][axis].total_cmp(&self.centroids[b as usize][axis])
        });
        mid
    }
}

/// The bin of coordinate `c` for bins starting at `lo`, `scale` bins per unit.
#[inline]
fn bin_index(c: f32, lo: f32, scale: f32) -> usize {
    // `as usize` saturates (and maps NaN to 0), so this never indexes out of range.
    (((c - lo) * scale) as usize).min(BINS - 1)
}

/// Moves the items for which `left` holds to the front; returns how many there are.
fn partition_in_place(items: &mut [u32], left: impl Fn(u32) -> bool) -> usize {
    let mut first_right = 0;
    for k in 0..items.len() {
        if left(items[k]) {
            items.swap(first_right, k);
            first_right += 1;
        }
    }
    first_right
}

#[cfg(test)]
mod tests {
    use super::*;

    fn check(bvh: &Bvh2, bounds: &[Aabb]) -> u32 {
        let mut seen = vec![false; bounds.len()];
        let mut max_depth = 0;
        let mut stack = vec![(0usize, 0u32)];
        while let Some((i, depth)) = stack.pop() {
            max_depth = max_depth.max(depth);
            let node = &bvh.nodes[i];
            if node.prim_count > 0 {
                assert_eq!(node.prim_count, 1);
                let p = bvh.primitive_indices[node.first_index as usize] as usize;
                assert!(!seen[p], "primitive {p} twice");
                seen[p] = true;
                let b = bounds[p];
                assert!(node.aabb.min.cmple(b.min).all() && node.aabb.max.cmpge(b.max).all());
            } else {
                for c in [node.first_index as usize, node.first_index as usize + 1] {
                    let child = &bvh.nodes[c].aabb;
                    assert!(node.aabb.min.cmple(child.min).all() && node.aabb.max.cmpge(child.max).all());
                    stack.push((c, depth + 1));
                }
            }
        }
        assert!(seen.iter().all(|&s| s), "every primitive in exactly one leaf");
        max_depth
    }

    #[test]
    fn every_primitive_lands_in_one_leaf_inside_its_ancestors_bounds() {
        let mut rng = crate::Rng::new(5, 9);
        for n in [1usize, 2, 3, 17, 1000, 20_000] {
            let bounds: Vec<Aabb> = (0..n)
                .map(|_| {
                    let c = Vec3A::new(rng.next_f32(), rng.next_f32(), rng.next_f32()) * 10.0;
                    let h = Vec3A::new(rng.next_f32(), rng.next_f32(), rng.next_f32()) * 0.1;
                    Aabb::new(c - h, c + h)
                })
                .collect();
            let bvh = build_bvh2(&bounds);
            assert_eq!(bvh.nodes.len(), 2 * n - 1);
            check(&bvh, &bounds);
        }
    }

    #[test]
    fn identical_and_degenerate_bounds_keep_the_depth_logarithmic() {
        // 50,000 identical boxes, then a fan of thin boxes sharing a corner: neither can be
        // separated well by SAH; the depth must stay bounded (and the build quick).
        let same = vec![Aabb::new(Vec3A::ZERO, Vec3A::ONE); 50_000];
        assert!(check(&build_bvh2(&same), &same) <= 17);
        let fan: Vec<Aabb> = (0..60_000)
            .map(|i| {
                let a = i as f32 / 60_000.0 * std::f32::consts::TAU;
                let tip = Vec3A::new(a.cos(), a.sin(), 0.0);
                Aabb::new(Vec3A::ZERO.min(tip), Vec3A::ZERO.max(tip))
            })
            .collect();
        assert!(check(&build_bvh2(&fan), &fan) <= MAX_SAH_DEPTH + 17);
    }
}
