//! Two rays searched together: their BVH walks interleaved a node at a time, so that the
//! cache misses of one overlap those of the other.

use super::traverse::Traversal;
use super::watertight::WatertightRay;
use super::{HitPrimitive, Leaving, SceneBvh, Search};
use crate::ray::Ray;

impl SceneBvh {
    /// The closest hits of two rays in `(0, t_max)` among all primitives but the triangle each
    /// leaves: the same hits as two calls of [`SceneBvh::closest`], but the two rays' BVH walks are interleaved a node
    /// at a time, so that the cache misses of one overlap those of the other (incoherent rays,
    /// as photon paths cast, spend most of their time waiting for memory).
    pub(crate) fn closest_pair(
        &self,
        rays: [&Ray; 2],
        t_max: f32,
        leaving: [Leaving; 2],
    ) -> [Option<(f32, HitPrimitive)>; 2] {
        let skipped = leaving.map(|l| match l {
            Leaving::Triangle(i) => i as usize,
            Leaving::Nothing => usize::MAX,
        });
        let Search::Bvh(bvh) = &self.triangle_search else {
            return [0, 1].map(|k| {
                self.closest(rays[k], 0.0, t_max, |c| {
                    c.primitive != HitPrimitive::Triangle(skipped[k] as u32) || skipped[k] == usize::MAX
                })
            });
        };
        let [a, b] = rays;
        let (wa, wb) = (
            WatertightRay::new(a.origin, a.direction),
            WatertightRay::new(b.origin, b.direction),
        );
        let (mut best_a, mut best_b) = ((t_max, u32::MAX), (t_max, u32::MAX));
        let mut visit_a =
            |i: usize, limit: &mut f32| i == skipped[0] || self.visit_closest(&wa, i, &mut best_a, limit);
        let mut visit_b =
            |i: usize, limit: &mut f32| i == skipped[1] || self.visit_closest(&wb, i, &mut best_b, limit);
        let mut walk_a = Traversal::<true>::new(bvh, a, 0.0, t_max);
        let mut walk_b = Traversal::<true>::new(bvh, b, 0.0, t_max);
        let (mut live_a, mut live_b) = (true, true);
        while live_a && live_b {
            live_a = walk_a.step(bvh, &mut visit_a);
            live_b = walk_b.step(bvh, &mut visit_b);
        }
        while live_a {
            live_a = walk_a.step(bvh, &mut visit_a);
        }
        while live_b {
            live_b = walk_b.step(bvh, &mut visit_b);
        }
        let mut hits =
            [best_a, best_b].map(|(t, i)| (i != u32::MAX).then_some((t, HitPrimitive::Triangle(i))));
        if !matches!(self.shape_search, Search::Empty) {
            for (hit, ray) in hits.iter_mut().zip(rays) {
                let limit = hit.map_or(t_max, |(t, _)| t);
                if let Some(shape_hit) = self.closest_shape(ray, 0.0, limit, &|_: &_| true) {
                    *hit = Some(shape_hit);
                }
            }
        }
        hits
    }

    /// A closest-hit search's test of leaf triangle `i`: keeps it in `best` if nearer, and
    /// shrinks the walk's `limit` to it.
    #[inline(always)]
    fn visit_closest(&self, w: &WatertightRay, i: usize, best: &mut (f32, u32), limit: &mut f32) -> bool {
        let t = w.intersect_triangle(&self.triangles[i].v, 0.0, best.0);
        if t < best.0 {
            *best = (t, i as u32);
            // Rounded up a little, so that pruning by it stays conservative.
            *limit = t * (1.0 + 1e-6);
        }
        true
    }
}
