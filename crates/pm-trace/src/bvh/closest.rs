//! Closest-hit queries: the nearest crossing a caller's filter takes, among the triangles (a
//! flat scan or the BVH) and then the analytic shapes, the filter seeing each crossing nearer
//! than the best so far.

use super::traverse::for_each_leaf_primitive;
use super::watertight::WatertightRay;
use super::{HitPrimitive, SceneBvh, Search};
use crate::ray::Ray;
use obvhs::cwbvh::CwBvh;

/// A primitive a ray crosses, as a closest-hit query offers it to the caller's filter: its
/// surface (an index in the scene's surface table), which primitive, and where along the ray.
#[derive(Clone, Copy, Debug)]
pub(crate) struct Crossing {
    pub surface: u32,
    pub primitive: HitPrimitive,
    pub t: f32,
}

impl SceneBvh {
    /// Closest hit in `(t_min, t_max)` among the crossings `accept` takes. The filter sees
    /// each crossing nearer than the best so far, so a rejected one never hides another at
    /// the same distance (a culled back face in front of a coincident front face).
    #[inline]
    pub(crate) fn closest(
        &self,
        ray: &Ray,
        t_min: f32,
        t_max: f32,
        accept: impl Fn(&Crossing) -> bool,
    ) -> Option<(f32, HitPrimitive)> {
        let w = WatertightRay::new(ray.origin, ray.direction);
        let mut best = match &self.triangle_search {
            Search::Empty => None,
            Search::Scan(batches) => {
                let best = std::cell::Cell::new((t_max, u32::MAX));
                batches.for_each_hit(
                    &w,
                    t_min,
                    || best.get().0,
                    |i, t| {
                        let crossing = Crossing {
                            surface: self.triangles[i].surface,
                            primitive: HitPrimitive::Triangle(i as u32),
                            t,
                        };
                        if accept(&crossing) {
                            best.set((t, i as u32));
                        }
                        true
                    },
                );
                let (t, i) = best.get();
                (i != u32::MAX).then_some((t, HitPrimitive::Triangle(i)))
            }
            Search::Bvh(bvh) => self.closest_triangle_in_bvh(bvh, ray, &w, t_min, t_max, &accept),
        };
        if !matches!(self.shape_search, Search::Empty) {
            let limit = best.map_or(t_max, |(t, _)| t);
            if let Some(hit) = self.closest_shape(ray, t_min, limit, &accept) {
                best = Some(hit);
            }
        }
        best
    }

    /// The closest triangle through the BVH. Not inlined: the BVH serves large scenes, where
    /// a call is nothing beside the traversal, and keeping it out of line keeps the small
    /// scenes' scan tight.
    #[inline(never)]
    fn closest_triangle_in_bvh(
        &self,
        bvh: &CwBvh,
        ray: &Ray,
        w: &WatertightRay,
        t_min: f32,
        t_max: f32,
        accept: &impl Fn(&Crossing) -> bool,
    ) -> Option<(f32, HitPrimitive)> {
        let mut best = (t_max, u32::MAX);
        for_each_leaf_primitive::<true>(bvh, ray, t_min, t_max, |i, limit| {
            let record = &self.triangles[i];
            let t = w.intersect_triangle(&record.v, t_min, best.0);
            let crossing = || Crossing {
                surface: record.surface,
                primitive: HitPrimitive::Triangle(i as u32),
                t,
            };
            if t < best.0 && accept(&crossing()) {
                best = (t, i as u32);
                // Rounded up a little, so that pruning by it stays conservative.
                *limit = t * (1.0 + 1e-6);
            }
            true
        });
        (best.1 != u32::MAX).then_some((best.0, HitPrimitive::Triangle(best.1)))
    }

    /// The closest shape part in `(t_min, t_max)`.
    #[inline(never)]
    pub(super) fn closest_shape(
        &self,
        ray: &Ray,
        t_min: f32,
        t_max: f32,
        accept: &impl Fn(&Crossing) -> bool,
    ) -> Option<(f32, HitPrimitive)> {
        let (t, i) = match &self.shape_search {
            Search::Empty => (t_max, u32::MAX),
            Search::Scan(scan) => {
                let best = std::cell::Cell::new((t_max, u32::MAX));
                scan.for_each_candidate(
                    ray.origin,
                    ray.direction,
                    t_min,
                    || best.get().0,
                    |i| {
                        let t = self.accepted_shape_crossing(i, ray, t_min, best.get().0, accept);
                        if t < best.get().0 {
                            best.set((t, i as u32));
                        }
                        true
                    },
                );
                best.get()
            }
            Search::Bvh(bvh) => {
                let mut best = (t_max, u32::MAX);
                for_each_leaf_primitive::<true>(bvh, ray, t_min, t_max, |i, limit| {
                    let t = self.accepted_shape_crossing(i, ray, t_min, best.0, accept);
                    if t < best.0 {
                        best = (t, i as u32);
                        *limit = t * (1.0 + 1e-6);
                    }
                    true
                });
                best
            }
        };
        (i != u32::MAX).then_some((t, HitPrimitive::Shape(i)))
    }

    /// The nearest crossing of shape `i` in `(t_min, t_max)` that `accept` takes, or `t_max`:
    /// a shape may cross a ray twice (a sphere), so a rejected crossing moves the search on
    /// past it.
    #[inline]
    fn accepted_shape_crossing(
        &self,
        i: usize,
        ray: &Ray,
        t_min: f32,
        t_max: f32,
        accept: &impl Fn(&Crossing) -> bool,
    ) -> f32 {
        let shape = &self.shapes[i];
        let mut from = t_min;
        // A shape crosses a ray at most twice, and each round moves strictly on past the
        // last crossing; the bound only guards against a shape test that does not.
        for _ in 0..4 {
            let t = shape.intersect(ray.origin, ray.direction, from, t_max);
            if t.is_nan() || t >= t_max {
                return t_max;
            }
            let crossing = Crossing {
                surface: shape.part().surface,
                primitive: HitPrimitive::Shape(i as u32),
                t,
            };
            if accept(&crossing) {
                return t;
            }
            from = t;
        }
        t_max
    }
}
