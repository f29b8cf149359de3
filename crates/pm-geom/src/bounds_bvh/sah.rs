//! The surface-area build of a [`BoundsBvh`]: binned splits (Wald 2007) for boxes of very
//! different sizes and shapes, where median splits make queries visit many nodes.

use super::{BoundsBvh, Node};
use crate::aabb::Aabb;
use glam::{UVec3, Vec3A};

impl BoundsBvh {
    /// The hierarchy over `boxes` (non-empty and finite) with up to `leaf` per leaf (at least
    /// 1), each split chosen by the surface-area heuristic over binned box centres instead of
    /// at the median: fewer nodes visited per query where boxes of very different sizes and
    /// shapes mix (the segments where a modelled interior's faces meet: long ones along walls,
    /// short ones round small objects). The node table is sized as it grows, not beforehand.
    pub(crate) fn build_sah(boxes: &[Aabb], leaf: usize) -> Self {
        let mut bvh = BoundsBvh {
            leaf: leaf.max(1),
            nodes: Vec::new(),
            order: (0..boxes.len() as u32).collect(),
        };
        if !boxes.is_empty() {
            let items: Vec<SahItem> = boxes
                .iter()
                .map(|b| SahItem {
                    min: b.min.into(),
                    max: b.max.into(),
                })
                .collect();
            let mut order = std::mem::take(&mut bvh.order);
            let bounds = SahExtent::of(&items, &order);
            let at = Place { offset: 0, depth: 0 };
            build_sah_subtree(&mut bvh.nodes, &items, &mut order, at, bounds, bvh.leaf);
            bvh.order = order;
        }
        bvh.nodes.shrink_to_fit();
        bvh
    }
}

/// Subtrees of at least this many boxes are built beside each other ([`build_sah_subtree`]).
const SAH_PARALLEL_MIN: usize = 4096;

/// Below this depth splits minimise the surface-area cost; deeper ones split at the median, so
/// that the depth stays below `MAX_SAH_DEPTH + log2(n)` (at most 56 for any `u32` count: the
/// traversal stack holds 64) however unevenly the binned splits fall (a binned split may peel
/// off one bin's few boxes a level where the centres crowd towards one end).
const MAX_SAH_DEPTH: u32 = 24;

/// Where a subtree goes: its first box's position in the final order, and its root's depth.
#[derive(Clone, Copy)]
struct Place {
    offset: usize,
    depth: u32,
}

/// Appends to `nodes` the surface-area-heuristic subtree over `order` (which goes `at` its
/// place in the final order and the tree, and spans `bounds`), with up to `leaf` boxes a
/// leaf. A large subtree's right half is built on another thread into a table of its own and
/// appended after the left, its inner nodes' `first` moved by where it lands: the same nodes,
/// in the same order, on any number of threads.
fn build_sah_subtree(
    nodes: &mut Vec<Node>,
    items: &[SahItem],
    order: &mut [u32],
    at: Place,
    bounds: SahExtent,
    leaf: usize,
) {
    let index = nodes.len();
    nodes.push(Node {
        min: bounds.min.into(),
        max: bounds.max.into(),
        first: at.offset as u32,
        count: order.len() as u32,
    });
    if order.len() <= leaf {
        return;
    }
    let binned =
        (order.len() >= SAH_MIN && at.depth < MAX_SAH_DEPTH).then(|| sah_split(items, order, &bounds));
    let (mid, left, right) = binned.flatten().unwrap_or_else(|| {
        let mid = median_split(items, order, &bounds);
        let (l, r) = order.split_at(mid);
        (mid, SahExtent::of(items, l), SahExtent::of(items, r))
    });
    let parallel = order.len() >= SAH_PARALLEL_MIN;
    let (left_order, right_order) = order.split_at_mut(mid);
    let depth = at.depth + 1;
    let (left_at, right_at) = (
        Place {
            offset: at.offset,
            depth,
        },
        Place {
            offset: at.offset + mid,
            depth,
        },
    );
    if parallel {
        let ((), right_nodes) = rayon::join(
            || build_sah_subtree(nodes, items, left_order, left_at, left, leaf),
            || {
                let mut right_nodes = Vec::new();
                build_sah_subtree(&mut right_nodes, items, right_order, right_at, right, leaf);
                right_nodes
            },
        );
        let base = nodes.len() as u32;
        nodes.extend(right_nodes.into_iter().map(|mut node| {
            if node.count == 0 {
                node.first += base;
            }
            node
        }));
        nodes[index].first = base;
    } else {
        build_sah_subtree(nodes, items, left_order, left_at, left, leaf);
        nodes[index].first = nodes.len() as u32;
        build_sah_subtree(nodes, items, right_order, right_at, right, leaf);
    }
    nodes[index].count = 0;
}

/// A box as the surface-area build reads it.
#[derive(Clone, Copy)]
struct SahItem {
    min: Vec3A,
    max: Vec3A,
}

impl SahItem {
    /// Twice the box's centre (binning by it is binning by the centre, without a product).
    #[inline]
    fn centre2(&self) -> Vec3A {
        self.min + self.max
    }
}

/// What a set of boxes spans: the union of the boxes, and the box of their doubled centres.
#[derive(Clone, Copy)]
struct SahExtent {
    min: Vec3A,
    max: Vec3A,
    centre_min: Vec3A,
    centre_max: Vec3A,
}

impl SahExtent {
    const EMPTY: SahExtent = SahExtent {
        min: Vec3A::splat(f32::INFINITY),
        max: Vec3A::splat(f32::NEG_INFINITY),
        centre_min: Vec3A::splat(f32::INFINITY),
        centre_max: Vec3A::splat(f32::NEG_INFINITY),
    };

    /// The extent of the boxes `order` lists.
    fn of(items: &[SahItem], order: &[u32]) -> Self {
        let mut e = SahExtent::EMPTY;
        for &i in order {
            e.grow(&items[i as usize]);
        }
        e
    }

    #[inline]
    fn grow(&mut self, item: &SahItem) {
        let c = item.centre2();
        self.min = self.min.min(item.min);
        self.max = self.max.max(item.max);
        self.centre_min = self.centre_min.min(c);
        self.centre_max = self.centre_max.max(c);
    }

    #[inline]
    fn union(&self, other: &SahExtent) -> SahExtent {
        SahExtent {
            min: self.min.min(other.min),
            max: self.max.max(other.max),
            centre_min: self.centre_min.min(other.centre_min),
            centre_max: self.centre_max.max(other.centre_max),
        }
    }

    /// Half the surface area of the boxes' union (0 when empty).
    #[inline]
    fn half_area(&self) -> f32 {
        let d = (self.max - self.min).max(Vec3A::ZERO);
        d.x * d.y + d.y * d.z + d.z * d.x
    }
}

/// Bins per axis of [`sah_split`].
const SAH_BINS: usize = 16;

/// Nodes of fewer boxes are split at the median: clearing and weighing 48 bins would cost
/// more than their few boxes (and the queries saved in a subtree so small).
const SAH_MIN: usize = 48;

/// Reorders `order` (spanning `bounds`) into two non-empty halves at the split of least
/// surface-area cost over [`SAH_BINS`] bins of box centres per axis (binned on all three axes
/// in one pass); returns the first half's size and both halves' extents, or `None` when no
/// binned split separates the boxes.
fn sah_split(
    items: &[SahItem],
    order: &mut [u32],
    bounds: &SahExtent,
) -> Option<(usize, SahExtent, SahExtent)> {
    let lo = bounds.centre_min;
    let span = bounds.centre_max - lo;
    let spread = span.cmpgt(Vec3A::ZERO);
    let scale = Vec3A::select(spread, Vec3A::splat(SAH_BINS as f32) / span, Vec3A::ZERO);
    // The casts saturate (and take NaN to 0), so every bin is in range.
    let bin_of = |c: Vec3A| {
        ((c - lo) * scale)
            .as_uvec3()
            .min(UVec3::splat(SAH_BINS as u32 - 1))
    };
    let mut bins = [[(SahExtent::EMPTY, 0u32); SAH_BINS]; 3];
    for &i in order.iter() {
        let item = &items[i as usize];
        let bin = bin_of(item.centre2());
        for (axis, bins) in bins.iter_mut().enumerate() {
            let b = &mut bins[bin[axis] as usize];
            b.0.grow(item);
            b.1 += 1;
        }
    }
    let mut best: Option<(f32, usize, usize)> = None;
    for axis in (0..3).filter(|&a| spread.test(a)) {
        let bins = &bins[axis];
        let mut right = [0.0f32; SAH_BINS];
        let (mut right_box, mut right_count) = (SahExtent::EMPTY, 0u32);
        for k in (1..SAH_BINS).rev() {
            right_box = right_box.union(&bins[k].0);
            right_count += bins[k].1;
            right[k - 1] = right_box.half_area() * right_count as f32;
        }
        let (mut left_box, mut left_count) = (SahExtent::EMPTY, 0u32);
        for k in 0..SAH_BINS - 1 {
            left_box = left_box.union(&bins[k].0);
            left_count += bins[k].1;
            if left_count == 0 || left_count as usize == order.len() {
                continue;
            }
            let cost = left_box.half_area() * left_count as f32 + right[k];
            if best.is_none_or(|(c, _, _)| cost < c) {
                best = Some((cost, axis, k));
            }
        }
    }
    let (_, axis, bin) = best?;
    let mut first_right = 0;
    for k in 0..order.len() {
        if bin_of(items[order[k] as usize].centre2())[axis] as usize <= bin {
            order.swap(first_right, k);
            first_right += 1;
        }
    }
    let side = |range: &[(SahExtent, u32)]| range.iter().fold(SahExtent::EMPTY, |e, b| e.union(&b.0));
    (first_right > 0 && first_right < order.len()).then(|| {
        (
            first_right,
            side(&bins[axis][..=bin]),
            side(&bins[axis][bin + 1..]),
        )
    })
}

/// Halves `order` at the median centre along the axis of widest centre spread.
fn median_split(items: &[SahItem], order: &mut [u32], bounds: &SahExtent) -> usize {
    let axis = (bounds.centre_max - bounds.centre_min).max_position();
    let mid = order.len() / 2;
    order.select_nth_unstable_by(mid, |&a, &b| {
        items[a as usize].centre2()[axis].total_cmp(&items[b as usize].centre2()[axis])
    });
    mid
}
