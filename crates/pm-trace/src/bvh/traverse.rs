//! Ray traversal of an obvhs `CwBvh` with our own node test and stack.
//!
//! The node test is obvhs's, four children at a time, but culls child boxes by the ray's own
//! `t_min` instead of obvhs's absolute 1e-4: that `EPSILON` culled a box the ray leaves before
//! `t = 1e-4`, so a wall within 0.1 mm of the origin was never hit. (An earlier fix traversed
//! from an origin moved back along the ray; that made every ray leaving a surface visit the
//! leaves of the surface it leaves.)
//!
//! The stack is ours too: obvhs's traversal (built for GPUs) keeps groups of sibling nodes
//! without their distances, so once a hit is found it still reads and tests every sibling
//! queued before it. Here each queued child carries the distance at which the ray enters its
//! box; closest-hit searches take the nearest first and drop, unread, every box that starts
//! beyond the hit found so far.

use crate::ray::Ray;
use glam::{Vec3, Vec3A, Vec4};
use obvhs::cwbvh::CwBvh;
use obvhs::cwbvh::node::CwBvhNode;

/// The obvhs ray for distances `(t_min, t_max)` of `ray`.
///
/// Two fixes to what `obvhs::ray::Ray::new` would make:
/// - its node test picks slab sides by `direction < 0` but inverts −0.0 to a large *negative*
///   number, so an axis-aligned ray with a −0.0 component missed every node (found by the
///   watertightness test); adding +0.0 turns −0.0 into +0.0;
/// - it inverts any component below `f32::EPSILON` to `±1/f32::EPSILON`, so a ray running
///   along an axis 1e-7 inside a box's face saw that box end after t ≈ 0.8 and missed what
///   lies beyond. The inverse here is `1/d` clamped to ±1e30 (a zero component gives 1e30,
///   and `0 · 1e30` stays 0 rather than NaN), as in the flat scan's slab test.
#[inline]
fn traversal_ray(ray: &Ray, t_min: f32, t_max: f32) -> obvhs::ray::Ray {
    let direction = Vec3A::from(ray.direction + Vec3::ZERO);
    obvhs::ray::Ray {
        origin: Vec3A::from(ray.origin),
        direction,
        inv_direction: direction.recip().clamp(Vec3A::splat(-1e30), Vec3A::splat(1e30)),
        tmin: t_min,
        tmax: t_max,
    }
}

/// The rounding bound of a slab distance `q·scale + offset`: each of its terms went through at
/// most five roundings of relative size ε = 2⁻²⁴ (the origin's difference, the reciprocal, the
/// products, the sum, the folded padding), so it errs by at most `5ε·(q·|scale| + |offset|)`;
/// 8 ε = 16 units of 2⁻²⁴ leaves a margin.
const SLAB_ROUNDING: f32 = 8.0 * f32::EPSILON;

/// Four of a node's quantized child bounds along one axis, from `first`.
#[inline(always)]
fn quantized(bounds: &[u8; 8], first: usize) -> Vec4 {
    Vec4::new(
        bounds[first] as f32,
        bounds[first + 1] as f32,
        bounds[first + 2] as f32,
        bounds[first + 3] as f32,
    )
}

/// The children of `node` the ray meets within `[ray.tmin, ray.tmax]`, as a mask by slot
/// (bit `i` for child slot `i`, empty slots included: the caller skips them), and each child
/// box's entry distance by slot. The arithmetic is obvhs's `intersect_ray_simd`, with each
/// slab widened by its rounding bound so that no box the ray touches is lost to rounding.
#[inline(always)]
fn intersect_node(node: &CwBvhNode, ray: &obvhs::ray::Ray) -> (u32, [Vec4; 2]) {
    let scale = node.compute_extent() * ray.inv_direction;
    let offset = (Vec3A::from(node.p) - ray.origin) * ray.inv_direction;
    // Each slab distance is widened by its own rounding bound: where tight boxes meet (the
    // vertex a fan's triangles share), a ray through the meeting point takes a box's entry and
    // exit from different axes, and a rounding error either way would lose the hit. Relative
    // padding (pbrt's 2γ₃) is not enough here: `q·scale` and `offset` nearly cancel when the
    // direction has a small component, so the error scales with them, not with the distance.
    // The widening is folded into the per-node factors (`q·s + o ∓ (q·|s| + |o|)·k` is
    // `q·(s ∓ |s|k) + (o ∓ |o|k)` for q ≥ 0), so the per-child work is obvhs's.
    let (pad_scale, pad_offset) = (scale.abs() * SLAB_ROUNDING, offset.abs() * SLAB_ROUNDING);
    let split = |v: Vec3A| [v.x, v.y, v.z].map(Vec4::splat);
    let (near_scale, near_offset) = (split(scale - pad_scale), split(offset - pad_offset));
    let (far_scale, far_offset) = (split(scale + pad_scale), split(offset + pad_offset));
    let negative = ray.direction.cmplt(Vec3A::ZERO);
    let (t_min, t_max) = (Vec4::splat(ray.tmin), Vec4::splat(ray.tmax));
    let mut mask = 0u32;
    let mut entries = [Vec4::ZERO; 2];
    for (group, first) in [0, 4].into_iter().enumerate() {
        let near_far = |lo: &[u8; 8], hi: &[u8; 8], negative: bool| {
            let (lo, hi) = (quantized(lo, first), quantized(hi, first));
            if negative { (hi, lo) } else { (lo, hi) }
        };
        let (x0, x1) = near_far(&node.child_min_x, &node.child_max_x, negative.test(0));
        let (y0, y1) = near_far(&node.child_min_y, &node.child_max_y, negative.test(1));
        let (z0, z1) = near_far(&node.child_min_z, &node.child_max_z, negative.test(2));
        let near = |q: Vec4, a: usize| q * near_scale[a] + near_offset[a];
        let far = |q: Vec4, a: usize| q * far_scale[a] + far_offset[a];
        let entry = near(x0, 0).max(near(y0, 1).max(near(z0, 2))).max(t_min);
        let exit = far(x1, 0).min(far(y1, 1).min(far(z1, 2))).min(t_max);
        mask |= entry.cmple(exit).bitmask() << first;
        entries[group] = entry;
    }
    (mask, entries)
}

/// A child box waiting on the traversal stack: the distance at which the ray enters it, and
/// what it holds (a node index, or with [`LEAF`] set a leaf's first primitive and count).
#[derive(Clone, Copy, Debug, Default)]
struct Pending {
    t: f32,
    item: u32,
}

/// Marks a [`Pending`] leaf; its primitive count (1–3) sits in the two bits below.
const LEAF: u32 = 1 << 31;
const COUNT_SHIFT: u32 = 29;
const FIRST_MASK: u32 = (1 << COUNT_SHIFT) - 1;

/// Primitives a BVH may hold for [`Pending`]'s packing (the scene allows 2²⁷ triangles).
pub(crate) const MAX_PRIMITIVES: usize = FIRST_MASK as usize;

/// Entries held without touching the heap; deeper stacks (degenerate trees only: each level
/// adds at most seven) spill into a vector.
const INLINE_STACK: usize = 32;

/// The traversal stack: a fixed array, spilling into a vector past [`INLINE_STACK`].
struct Stack {
    inline: [Pending; INLINE_STACK],
    len: usize,
    spill: Vec<Pending>,
}

impl Stack {
    #[inline(always)]
    fn new() -> Self {
        Stack {
            inline: [Pending::default(); INLINE_STACK],
            len: 0,
            spill: Vec::new(),
        }
    }

    #[inline(always)]
    fn push(&mut self, p: Pending) {
        if self.len < INLINE_STACK {
            self.inline[self.len] = p;
        } else {
            self.spill.push(p);
        }
        self.len += 1;
    }

    #[inline(always)]
    fn clear(&mut self) {
        self.len = 0;
        self.spill.clear();
    }

    #[inline(always)]
    fn pop(&mut self) -> Option<Pending> {
        if self.len == 0 {
            return None;
        }
        self.len -= 1;
        if self.len < INLINE_STACK {
            Some(self.inline[self.len])
        } else {
            self.spill.pop()
        }
    }
}

/// Visits the primitives (leaf indices) of every leaf the ray `(t_min, t_max)` meets.
/// `visit(i, t_max)` may shrink `t_max` (for a closest-hit search) and returns false to stop.
/// See [`Traversal`] for the order.
#[inline(always)]
pub(super) fn for_each_leaf_primitive<const NEAREST_FIRST: bool>(
    bvh: &CwBvh,
    ray: &Ray,
    t_min: f32,
    t_max: f32,
    mut visit: impl FnMut(usize, &mut f32) -> bool,
) {
    let mut traversal = Traversal::<NEAREST_FIRST>::new(bvh, ray, t_min, t_max);
    while traversal.step(bvh, &mut visit) {}
}

/// One ray's walk through a `CwBvh`, a node or leaf per [`Traversal::step`], so that the walks
/// of two rays can be interleaved (their cache misses then overlap).
///
/// With `NEAREST_FIRST` (closest-hit searches) the children a node's test finds are taken
/// nearest entry first, and a child whose box the ray enters beyond the current `t_max` is
/// dropped when it is popped, before its node is read: once a hit is found, the boxes behind
/// it cost nothing. Without it (any-hit searches, which stop at the first hit) they are taken
/// in slot order.
pub(super) struct Traversal<const NEAREST_FIRST: bool> {
    ray: obvhs::ray::Ray,
    stack: Stack,
    /// The child to take next without a round trip through the stack (the nearest found).
    next: Option<Pending>,
}

impl<const NEAREST_FIRST: bool> Traversal<NEAREST_FIRST> {
    /// A walk of `bvh` for the ray `(t_min, t_max)`, at its root.
    #[inline(always)]
    pub(super) fn new(bvh: &CwBvh, ray: &Ray, t_min: f32, t_max: f32) -> Self {
        Traversal {
            ray: traversal_ray(ray, t_min, t_max),
            stack: Stack::new(),
            next: (!bvh.nodes.is_empty()).then_some(Pending { t: t_min, item: 0 }),
        }
    }

    /// Takes the next node or leaf: tests a node's children, or calls `visit(i, t_max)` for
    /// each primitive of a leaf (`visit` may shrink `t_max`, and returns false to stop).
    /// Returns false once the walk is over.
    #[inline(always)]
    pub(super) fn step(&mut self, bvh: &CwBvh, visit: &mut impl FnMut(usize, &mut f32) -> bool) -> bool {
        let Some(pending) = self.next.take().or_else(|| self.stack.pop()) else {
            return false;
        };
        if pending.t > self.ray.tmax {
            return true;
        }
        if pending.item & LEAF != 0 {
            let first = (pending.item & FIRST_MASK) as usize;
            let count = ((pending.item & !LEAF) >> COUNT_SHIFT) as usize;
            for i in first..first + count {
                if !visit(i, &mut self.ray.tmax) {
                    self.stack.clear();
                    return false;
                }
            }
            return true;
        }
        let node = &bvh.nodes[pending.item as usize];
        let (mut mask, entries) = intersect_node(node, &self.ray);
        let entries: [f32; 8] = lanes8(entries);
        let mut children = [Pending::default(); 8];
        let mut n = 0;
        while mask != 0 {
            let slot = mask.trailing_zeros();
            mask &= mask - 1;
            let meta = node.child_meta[slot as usize] as u32;
            let item = if node.imask & (1 << slot) != 0 {
                node.child_base_idx + (node.imask as u32 & ((1 << slot) - 1)).count_ones()
            } else if meta != 0 {
                let count = (meta & 0b1110_0000).count_ones();
                LEAF | (count << COUNT_SHIFT) | (node.primitive_base_idx + (meta & 0b1_1111))
            } else {
                continue;
            };
            children[n] = Pending {
                t: entries[slot as usize],
                item,
            };
            n += 1;
        }
        if NEAREST_FIRST {
            // Farthest pushed first, so the nearest is popped first (insertion sort: n ≤ 8).
            for i in 1..n {
                let mut j = i;
                while j > 0 && children[j - 1].t < children[j].t {
                    children.swap(j - 1, j);
                    j -= 1;
                }
            }
        }
        if let Some((&nearest, rest)) = children[..n].split_last() {
            for &child in rest {
                self.stack.push(child);
            }
            self.next = Some(nearest);
        }
        true
    }
}

/// The eight lanes of two `Vec4`s, in order.
#[inline(always)]
fn lanes8(v: [Vec4; 2]) -> [f32; 8] {
    let (a, b) = (v[0].to_array(), v[1].to_array());
    [a[0], a[1], a[2], a[3], b[0], b[1], b[2], b[3]]
}
