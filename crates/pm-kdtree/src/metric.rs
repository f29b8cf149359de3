//! Distance metrics for k-nearest queries: Euclidean (a sphere) and Chebyshev (a cube).
//!
//! Queries compare *ranks*, a monotone stand-in for the distance that is cheaper to compute
//! (the squared distance for Euclidean), and prune kd-tree cells with a lower bound on the
//! rank built one axis offset at a time (Arya & Mount's incremental distance).

use glam::Vec3;

/// A distance metric. Queries are generic over it so the hot loop is monomorphised.
///
/// Only [`Metric::distance`] is required. The defaults of the other methods are correct for
/// every metric whose distance is at least the largest per-axis offset (every Lp norm, for
/// instance); override them for speed or tighter pruning, keeping these rules:
/// `rank` is monotone in the distance, `rank_to_distance(distance_to_rank(d)) ≈ d`, and
/// `grow_bound` never exceeds the rank of any point in the cell it bounds.
pub trait Metric: Copy + Send + Sync + 'static {
    /// Distance between two points (true distance, not squared).
    fn distance(a: Vec3, b: Vec3) -> f32;

    /// Rank of the difference `d = b − a`: orders points the way [`Metric::distance`] does.
    #[inline]
    fn rank(d: Vec3) -> f32 {
        Self::distance(Vec3::ZERO, d)
    }
    /// The distance a rank stands for.
    #[inline]
    fn rank_to_distance(rank: f32) -> f32 {
        rank
    }
    /// The rank of a distance.
    #[inline]
    fn distance_to_rank(distance: f32) -> f32 {
        distance
    }
    /// The contribution to the rank of an offset along one axis.
    #[inline]
    fn axis_rank(offset: f32) -> f32 {
        offset.abs()
    }
    /// A lower bound on the rank of the points of a cell, after the cell's offset along one
    /// axis grows from `old` to `new` (both from [`Metric::axis_rank`]); `bound` is the
    /// lower bound before. The default combines offsets like Chebyshev (the maximum).
    #[inline]
    fn grow_bound(bound: f32, old: f32, new: f32) -> f32 {
        let _ = old;
        bound.max(new)
    }
}

/// Euclidean distance: the k nearest lie in a sphere.
#[derive(Clone, Copy, Debug, Default)]
pub struct Euclidean;
/// Chebyshev (L∞) distance: the k nearest lie in an axis-aligned cube.
#[derive(Clone, Copy, Debug, Default)]
pub struct Chebyshev;

impl Metric for Euclidean {
    #[inline]
    fn distance(a: Vec3, b: Vec3) -> f32 {
        a.distance(b)
    }
    #[inline]
    fn rank(d: Vec3) -> f32 {
        d.x * d.x + d.y * d.y + d.z * d.z
    }
    #[inline]
    fn rank_to_distance(rank: f32) -> f32 {
        rank.sqrt()
    }
    #[inline]
    fn distance_to_rank(distance: f32) -> f32 {
        distance * distance
    }
    #[inline]
    fn axis_rank(offset: f32) -> f32 {
        offset * offset
    }
    #[inline]
    fn grow_bound(bound: f32, old: f32, new: f32) -> f32 {
        bound - old + new
    }
}

impl Metric for Chebyshev {
    #[inline]
    fn distance(a: Vec3, b: Vec3) -> f32 {
        (a - b).abs().max_element()
    }
    #[inline]
    fn rank(d: Vec3) -> f32 {
        // Plain comparisons compile to one `maxps` each, unlike `f32::max` and its NaN rules;
        // queries reject non-finite points before ranking.
        let larger = |a: f32, b: f32| if a > b { a } else { b };
        larger(larger(d.x.abs(), d.y.abs()), d.z.abs())
    }
}
