//! A flat scan over padded bounds, for the analytic shapes (spheres, ring sides) of small
//! scenes (their triangles are tested four at a time without culling, see `batch`): a slab
//! test per shape (structure-of-arrays, eight at a time) culls before the exact test.
//!
//! The bounds are padded so that rounding in the slab test can never cull a primitive the
//! exact test would hit: the padding is 1e-4 of the scene's coordinate scale, far above the
//! slab test's relative error of a few ulps.

use glam::{Vec3, Vec4};

/// Primitives per slab-test batch.
const LANES: usize = 8;

/// Padded bounds of eight primitives, by coordinate (structure of arrays).
#[derive(Clone, Copy, Debug)]
struct Batch {
    min: [[f32; LANES]; 3],
    max: [[f32; LANES]; 3],
}

/// Padded bounds of the primitives in batches of [`LANES`]; the last batch's unused lanes
/// are masked off.
#[derive(Debug)]
pub(crate) struct BoundsScan {
    batches: Vec<Batch>,
    len: usize,
}

/// A ray prepared for slab tests: origin and clamped inverse direction.
struct SlabRay {
    origin: [f32; 3],
    inv: [f32; 3],
}

impl SlabRay {
    /// `direction` need not be normalised; zero components give a huge finite inverse, so
    /// `0 · inverse` stays 0 instead of NaN. With a finite ray no NaN arises in the slab test
    /// (the bounds are finite, or infinite in unused lanes, which are masked off), so SIMD
    /// min/max need no NaN handling; a NaN ray fails `near <= far` and is culled.
    #[inline]
    fn new(origin: Vec3, direction: Vec3) -> Self {
        // One vector division; `+ 0.0` turns −0.0 into +0.0.
        let d = Vec4::new(direction.x + 0.0, direction.y + 0.0, direction.z + 0.0, 1.0);
        let inv = (Vec4::ONE / d).clamp(Vec4::splat(-1e30), Vec4::splat(1e30));
        let inv = [inv.x, inv.y, inv.z];
        SlabRay {
            origin: origin.to_array(),
            inv,
        }
    }
}

impl BoundsScan {
    /// Bounds `(min, max)` of each primitive, padded by 1e-4 of the scene's coordinate scale.
    pub(crate) fn new(bounds: &[(Vec3, Vec3)]) -> Self {
        let scale = bounds.iter().fold(1.0f32, |s, (lo, hi)| {
            s.max(lo.abs().max_element()).max(hi.abs().max_element())
        });
        let pad = Vec3::splat(1e-4 * scale);
        let empty = Batch {
            min: [[f32::INFINITY; LANES]; 3],
            max: [[f32::NEG_INFINITY; LANES]; 3],
        };
        let mut batches = vec![empty; bounds.len().div_ceil(LANES)];
        for (i, (lo, hi)) in bounds.iter().enumerate() {
            let (lo, hi) = (*lo - pad, *hi + pad);
            let batch = &mut batches[i / LANES];
            for axis in 0..3 {
                batch.min[axis][i % LANES] = lo[axis];
                batch.max[axis][i % LANES] = hi[axis];
            }
        }
        BoundsScan {
            batches,
            len: bounds.len(),
        }
    }

    /// Heap bytes held.
    pub(crate) fn heap_bytes(&self) -> usize {
        self.batches.capacity() * size_of::<Batch>()
    }

    /// Calls `visit(i)` for each primitive `i` (in index order) whose padded box the ray
    /// `origin + t · direction` meets at some `t` in `[t_min, limit()]`, where `limit` is
    /// re-read before each call so a closest-hit search can shrink it. `visit` returns false
    /// to stop the scan. A scene without shapes costs nothing here (not even the inverse).
    #[inline]
    pub(crate) fn for_each_candidate(
        &self,
        origin: Vec3,
        direction: Vec3,
        t_min: f32,
        mut limit: impl FnMut() -> f32,
        mut visit: impl FnMut(usize) -> bool,
    ) {
        if self.batches.is_empty() {
            return;
        }
        let ray = SlabRay::new(origin, direction);
        let [ox, oy, oz] = ray.origin.map(Vec4::splat);
        let [ix, iy, iz] = ray.inv.map(Vec4::splat);
        let t_min = Vec4::splat(t_min);
        for (b, batch) in self.batches.iter().enumerate() {
            let [x0, y0, z0] = &batch.min;
            let [x1, y1, z1] = &batch.max;
            let t_max = Vec4::splat(limit());
            let mut near = [0.0f32; LANES];
            let mut mask = 0u32;
            // Two groups of four lanes in SIMD registers; one bit per candidate lane, so the
            // visit loop below branches once per candidate.
            for half in [0, 4] {
                let load = |a: &[f32; LANES]| Vec4::from_slice(&a[half..half + 4]);
                let (ax, bx) = ((load(x0) - ox) * ix, (load(x1) - ox) * ix);
                let (ay, by) = ((load(y0) - oy) * iy, (load(y1) - oy) * iy);
                let (az, bz) = ((load(z0) - oz) * iz, (load(z1) - oz) * iz);
                let n = ax.min(bx).max(ay.min(by)).max(az.min(bz).max(t_min));
                let f = ax.max(bx).min(ay.max(by)).min(az.max(bz));
                near[half..half + 4].copy_from_slice(&n.to_array());
                mask |= ((n.cmple(f) & n.cmple(t_max)).bitmask()) << half;
            }
            let used = self.len - b * LANES;
            if used < LANES {
                mask &= (1u32 << used) - 1;
            }
            while mask != 0 {
                let l = mask.trailing_zeros() as usize;
                mask &= mask - 1;
                if near[l] <= limit() && !visit(b * LANES + l) {
                    return;
                }
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::rng::Rng;

    /// Brute-force reference: does the segment `[t_min, t_max]` of the ray meet the box?
    /// Sampled densely along the ray, so it can only miss grazing hits, never invent one.
    fn segment_meets_box(o: Vec3, d: Vec3, lo: Vec3, hi: Vec3, t_max: f32) -> bool {
        (0..=4000).any(|k| {
            let p = o + d * (t_max * k as f32 / 4000.0);
            p.cmpge(lo).all() && p.cmple(hi).all()
        })
    }

    #[test]
    fn every_box_the_ray_passes_through_is_a_candidate_including_flat_ones() {
        let mut rng = Rng::new(7, 0);
        let mut r = || rng.next_f32();
        for _ in 0..300 {
            // 19 boxes (not a whole batch), some flat along one axis like axis-aligned walls.
            let boxes: Vec<(Vec3, Vec3)> = (0..19)
                .map(|k| {
                    let lo = Vec3::new(r(), r(), r()) * 2.0 - 1.0;
                    let mut size = Vec3::new(r(), r(), r()) * 0.5;
                    size[k % 3] *= if k % 2 == 0 { 0.0 } else { 1.0 };
                    (lo, lo + size)
                })
                .collect();
            let scan = BoundsScan::new(&boxes);
            let o = Vec3::new(r(), r(), r()) * 2.0 - 1.0;
            let mut d = Vec3::new(r(), r(), r()) * 2.0 - 1.0;
            d[(r() * 3.0) as usize % 3] = if r() < 0.5 { 0.0 } else { -0.0 };
            let d = d.normalize();
            let mut found = Vec::new();
            scan.for_each_candidate(
                o,
                d,
                0.0,
                || 4.0,
                |i| {
                    found.push(i);
                    true
                },
            );
            for (i, &(lo, hi)) in boxes.iter().enumerate() {
                if segment_meets_box(o, d, lo, hi, 4.0) {
                    assert!(found.contains(&i), "box {i} {lo} {hi} culled for ray {o} {d}");
                }
            }
            // Culling works: boxes far off the ray are not candidates.
            for &i in &found {
                let (lo, hi) = boxes[i];
                let grown = (lo - 0.01, hi + 0.01);
                assert!(
                    segment_meets_box(o, d, grown.0, grown.1, 4.0),
                    "box {i} is no candidate"
                );
            }
        }
    }
}
