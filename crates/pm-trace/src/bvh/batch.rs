//! Triangles in structure-of-arrays batches of four, tested against a ray four at a time with
//! the same watertight test as [`WatertightRay::intersect_triangle`]: the same operations in
//! the same order, lane by lane, so a lane's result is bit-identical to the scalar test's.
//! Lanes whose edge functions round to exactly zero are re-decided by the scalar test (which
//! falls back to double precision there).
//!
//! Small scenes test every triangle this way, with no culling: nothing is ever culled that
//! the exact test would hit, and a ray leaving a wall costs no more than any other.

use super::watertight::WatertightRay;
use glam::{Vec3, Vec4};

/// Triangles per batch.
const LANES: usize = 4;

/// Four triangles: `corners[axis][vertex]` holds that coordinate of that vertex for each lane.
/// Unused lanes hold NaN, which no test ever reports as a hit.
#[derive(Clone, Copy, Debug)]
struct Batch {
    corners: [[Vec4; 3]; 3],
}

/// All triangles of a small scene in batches of [`LANES`].
#[derive(Debug)]
pub(crate) struct TriangleBatches {
    batches: Vec<Batch>,
    /// The same triangles, for the lanes the scalar test decides.
    triangles: Vec<[Vec3; 3]>,
}

impl TriangleBatches {
    /// Batches of the triangles in order (triangle `i` is lane `i % 4` of batch `i / 4`).
    pub(crate) fn new(triangles: Vec<[Vec3; 3]>) -> Self {
        let empty = Batch {
            corners: [[Vec4::NAN; 3]; 3],
        };
        let mut batches = vec![empty; triangles.len().div_ceil(LANES)];
        for (i, v) in triangles.iter().enumerate() {
            let batch = &mut batches[i / LANES];
            for axis in 0..3 {
                for (vertex, p) in v.iter().enumerate() {
                    batch.corners[axis][vertex][i % LANES] = p[axis];
                }
            }
        }
        TriangleBatches { batches, triangles }
    }

    /// Heap bytes held.
    pub(crate) fn heap_bytes(&self) -> usize {
        self.batches.capacity() * size_of::<Batch>() + self.triangles.capacity() * size_of::<[Vec3; 3]>()
    }

    /// Calls `visit(i, t)` for every triangle `i` (in index order) that the ray meets at a
    /// distance `t` in `(t_min, limit())`, where `limit` is re-read for each batch so a
    /// closest-hit search can shrink it. `visit` returns false to stop.
    #[inline]
    pub(crate) fn for_each_hit(
        &self,
        ray: &WatertightRay,
        t_min: f32,
        mut limit: impl FnMut() -> f32,
        mut visit: impl FnMut(usize, f32) -> bool,
    ) {
        let (kx, ky, kz) = ray.axes;
        let origin = ray.origin.to_array();
        let (ox, oy, oz) = (
            Vec4::splat(origin[kx]),
            Vec4::splat(origin[ky]),
            Vec4::splat(origin[kz]),
        );
        let (sx, sy, sz) = (
            Vec4::splat(ray.shear.x),
            Vec4::splat(ray.shear.y),
            Vec4::splat(ray.shear.z),
        );
        let t_min4 = Vec4::splat(t_min);
        for (b, batch) in self.batches.iter().enumerate() {
            let t_max = limit();
            let (cx, cy, cz) = (&batch.corners[kx], &batch.corners[ky], &batch.corners[kz]);
            // Sheared, origin-relative vertices; `x − s·z` rounds like the scalar test's dot
            // product with its row (the other terms are exact zeros).
            let z = [cz[0] - oz, cz[1] - oz, cz[2] - oz];
            let x = [
                cx[0] - ox - sx * z[0],
                cx[1] - ox - sx * z[1],
                cx[2] - ox - sx * z[2],
            ];
            let y = [
                cy[0] - oy - sy * z[0],
                cy[1] - oy - sy * z[1],
                cy[2] - oy - sy * z[2],
            ];
            let u = x[2] * y[1] - y[2] * x[1];
            let v = x[0] * y[2] - y[0] * x[2];
            let w = x[1] * y[0] - y[1] * x[0];
            let zero = Vec4::ZERO;
            let on_edge = u.cmpeq(zero) | v.cmpeq(zero) | w.cmpeq(zero);
            let outside = (u.cmplt(zero) | v.cmplt(zero) | w.cmplt(zero))
                & (u.cmpgt(zero) | v.cmpgt(zero) | w.cmpgt(zero));
            let det = u + v + w;
            let t = (u * (sz * z[0]) + v * (sz * z[1]) + w * (sz * z[2])) / det;
            let inside = t.cmpgt(t_min4) & t.cmplt(Vec4::splat(t_max)) & !outside & det.cmpne(zero);
            // Unused (NaN) lanes set no bit: every comparison with NaN is false.
            let hits = inside.bitmask() & !on_edge.bitmask();
            let edges = on_edge.bitmask();
            let t = t.to_array();
            let mut lanes = hits | edges;
            while lanes != 0 {
                let l = lanes.trailing_zeros() as usize;
                lanes &= lanes - 1;
                let i = b * LANES + l;
                let t = if edges & (1 << l) != 0 {
                    ray.intersect_triangle(&self.triangles[i], t_min, limit())
                } else {
                    t[l]
                };
                if t < limit() && !visit(i, t) {
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
    use crate::sampling::uniform_sphere;
    use glam::Vec2;

    /// Every lane agrees bit for bit with the scalar test, including rays aimed exactly at
    /// shared edges and vertices (where the double-precision fallback decides).
    #[test]
    fn batches_agree_with_the_scalar_test_bit_for_bit() {
        let mut rng = Rng::new(11, 0);
        let mut r = || rng.next_f32();
        // A fan of triangles around a vertex plus random ones: 9, so the last batch is partial.
        let hub = Vec3::new(0.25, 0.5, 0.0);
        let rim: Vec<Vec3> = (0..6)
            .map(|k| {
                let a = k as f32 * std::f32::consts::TAU / 6.0;
                hub + Vec3::new(a.cos(), a.sin(), 0.1 * (k % 2) as f32)
            })
            .collect();
        let mut tris: Vec<[Vec3; 3]> = (0..6).map(|k| [hub, rim[k], rim[(k + 1) % 6]]).collect();
        for _ in 0..3 {
            tris.push([(); 3].map(|_| Vec3::new(r(), r(), r()) * 2.0 - 1.0));
        }
        let batches = TriangleBatches::new(tris.clone());
        let mut checked_edges = 0;
        for k in 0..20_000 {
            let origin = Vec3::new(r(), r(), r()) * 4.0 - 2.0 + Vec3::Z * 2.0;
            // Every fourth ray is aimed exactly at a vertex or the middle of a shared edge.
            let target = match k % 4 {
                0 => hub,
                1 => 0.5 * (hub + rim[k % 6]),
                _ => Vec3::new(r(), r(), 0.0) * 2.0 - 1.0,
            };
            let d = if k % 7 == 6 {
                uniform_sphere(Vec2::new(r(), r()))
            } else {
                (target - origin).normalize()
            };
            let ray = WatertightRay::new(origin, d);
            let mut batched = vec![f32::INFINITY; tris.len()];
            batches.for_each_hit(
                &ray,
                0.0,
                || f32::INFINITY,
                |i, t| {
                    batched[i] = t;
                    true
                },
            );
            for (i, tri) in tris.iter().enumerate() {
                let scalar = ray.intersect_triangle(tri, 0.0, f32::INFINITY);
                assert_eq!(batched[i].to_bits(), scalar.to_bits(), "triangle {i}, ray {k}");
                checked_edges += (k % 4 < 2 && scalar.is_finite()) as u32;
            }
        }
        assert!(
            checked_edges > 5_000,
            "only {checked_edges} vertex/edge hits checked"
        );
    }

    #[test]
    fn the_limit_shrinks_and_visit_can_stop() {
        // Three parallel triangles at z = 1, 2, 3 in front of the origin.
        let tri = |z: f32| {
            [
                Vec3::new(-1.0, -1.0, z),
                Vec3::new(1.0, -1.0, z),
                Vec3::new(0.0, 1.0, z),
            ]
        };
        let batches = TriangleBatches::new(vec![tri(3.0), tri(1.0), tri(2.0)]);
        let ray = WatertightRay::new(Vec3::ZERO, Vec3::Z);
        let best = std::cell::Cell::new(f32::INFINITY);
        let mut visited = Vec::new();
        batches.for_each_hit(
            &ray,
            0.0,
            || best.get(),
            |i, t| {
                visited.push(i);
                best.set(best.get().min(t));
                true
            },
        );
        assert_eq!((visited, best.get()), (vec![0, 1], 1.0));
        let mut visited = Vec::new();
        batches.for_each_hit(
            &ray,
            1.5,
            || f32::INFINITY,
            |i, _| {
                visited.push(i);
                false
            },
        );
        assert_eq!(visited, vec![0]);
    }
}
