//! The scene's BVH (obvhs `CwBvh`) over triangles and analytic shape parts, with our own
//! watertight ray–triangle test (Woop, Benthin & Wald 2013): no ray slips between the
//! triangles of a closed mesh, which obvhs's own Möller–Trumbore test allows.

use crate::shape::{Ring, RingSide, Sphere};
use crate::{PartId, Ray};
use glam::{Vec3, Vec3A};
use obvhs::cwbvh::CwBvh;
use obvhs::ray::RayHit;
use obvhs::{Boundable, BvhBuildParams};
use std::time::Duration;

mod batch;
mod scan;

use batch::TriangleBatches;
use scan::{BoundsScan, SlabRay};

/// Scenes with at most this many primitives are searched by a flat scan (every triangle four
/// at a time, analytic shapes behind padded bounds) instead of the BVH.
const SCAN_MAX_PRIMITIVES: usize = 64;

/// One BVH leaf primitive; each belongs to exactly one part.
#[derive(Clone, Copy, Debug)]
pub(crate) enum Primitive {
    Triangle {
        v: [Vec3; 3],
        /// Unit geometric normal (counter-clockwise winding), computed once at build.
        normal: Vec3,
        part: PartId,
    },
    Sphere {
        sphere: Sphere,
        part: PartId,
    },
    RingSide {
        ring: Ring,
        side: RingSide,
        part: PartId,
    },
}

impl Primitive {
    /// A triangle with its unit normal (counter-clockwise winding).
    pub(crate) fn triangle(v: [Vec3; 3], part: PartId) -> Self {
        let normal = (v[1] - v[0]).cross(v[2] - v[0]).normalize();
        Primitive::Triangle { v, normal, part }
    }

    pub(crate) fn part(&self) -> PartId {
        match *self {
            Primitive::Triangle { part, .. }
            | Primitive::Sphere { part, .. }
            | Primitive::RingSide { part, .. } => part,
        }
    }

    fn bounds(&self) -> pm_geom::Aabb {
        match self {
            Primitive::Triangle { v, .. } => pm_geom::Aabb::from_points(v),
            Primitive::Sphere { sphere, .. } => sphere.bounds(),
            Primitive::RingSide { ring, side, .. } => ring.side_bounds(*side),
        }
    }

    /// Distance along the ray in `(t_min, t_max)`, or infinity.
    #[inline]
    fn intersect(&self, w: &WatertightRay, t_min: f32, t_max: f32) -> f32 {
        match self {
            Primitive::Triangle { v, .. } => w.intersect_triangle(v, t_min, t_max),
            Primitive::Sphere { sphere, .. } => sphere.intersect(w.origin, w.direction, t_min, t_max),
            Primitive::RingSide { ring, side, .. } => {
                ring.intersect_side(*side, w.origin, w.direction, t_min, t_max)
            }
        }
    }

    /// Unit geometric normal at `p` (triangles: counter-clockwise winding).
    pub(crate) fn normal_at(&self, p: Vec3) -> Vec3 {
        match self {
            Primitive::Triangle { normal, .. } => *normal,
            Primitive::Sphere { sphere, .. } => sphere.normal_at(p),
            Primitive::RingSide { ring, side, .. } => ring.side_normal(*side, p),
        }
    }
}

struct Bounded(obvhs::aabb::Aabb);

impl Boundable for Bounded {
    fn aabb(&self) -> obvhs::aabb::Aabb {
        self.0
    }
}

/// A ray prepared for the watertight test: the axis permutation and shear folded into three
/// row vectors, so a vertex `a` maps to `(a·x_row, a·y_row, a·z_row)` without indexing by a
/// per-ray axis (which compiled to unpredictable branches). Each row has one or two non-zero
/// entries (1 and −shear, or the z scale), so the dot products round exactly like the
/// permute-then-shear formulation.
pub(crate) struct WatertightRay {
    origin: Vec3,
    direction: Vec3,
    /// The permuted axes `(kx, ky, kz)`: `kz` is the direction's dominant axis.
    axes: (usize, usize, usize),
    /// The shear `(d[kx] / d[kz], d[ky] / d[kz], 1 / d[kz])` (each as `d · (1 / d[kz])`).
    shear: Vec3,
    x_row: Vec3,
    y_row: Vec3,
    z_row: Vec3,
}

impl WatertightRay {
    pub(crate) fn new(origin: Vec3, direction: Vec3) -> Self {
        /// Unit vectors by axis, so a per-ray axis becomes a table load rather than a branch
        /// or a store-then-load through a stack array (which stalls store forwarding).
        const AXES: [Vec3; 3] = [Vec3::X, Vec3::Y, Vec3::Z];
        /// `(kx, ky)` by `2·kz + (d[kz] < 0)`: the next two axes in cyclic order, swapped
        /// for a negative `d[kz]` to keep the triangles' winding.
        const OTHER_AXES: [(usize, usize); 6] = [(1, 2), (2, 1), (2, 0), (0, 2), (0, 1), (1, 0)];
        let abs = direction.abs();
        // The dominant axis without branches (ray directions are random, so branches here
        // mispredict): x when it beats both, else y when it beats z, else z.
        let x_major = (abs.x > abs.y) & (abs.x > abs.z);
        let y_major = (abs.x <= abs.y) & (abs.y > abs.z);
        let kz = 2 - 2 * x_major as usize - y_major as usize;
        let ez = AXES[kz];
        // Dot products with unit vectors select a component exactly (the direction is finite).
        let dz = direction.dot(ez);
        let (kx, ky) = OTHER_AXES[2 * kz + (dz < 0.0) as usize];
        let (ex, ey) = (AXES[kx], AXES[ky]);
        // One division: the shear only has to be the same for every triangle of a ray.
        let sz = 1.0 / dz;
        let (sx, sy) = (direction.dot(ex) * sz, direction.dot(ey) * sz);
        WatertightRay {
            origin,
            direction,
            axes: (kx, ky, kz),
            shear: Vec3::new(sx, sy, sz),
            x_row: ex - sx * ez,
            y_row: ey - sy * ez,
            z_row: sz * ez,
        }
    }

    /// Woop–Benthin–Wald watertight ray–triangle intersection (no backface culling).
    #[inline]
    pub(crate) fn intersect_triangle(&self, v: &[Vec3; 3], t_min: f32, t_max: f32) -> f32 {
        let a = v[0] - self.origin;
        let b = v[1] - self.origin;
        let c = v[2] - self.origin;
        let (ax, ay) = (a.dot(self.x_row), a.dot(self.y_row));
        let (bx, by) = (b.dot(self.x_row), b.dot(self.y_row));
        let (cx, cy) = (c.dot(self.x_row), c.dot(self.y_row));
        let mut u = cx * by - cy * bx;
        let mut vv = ax * cy - ay * cx;
        let mut w = bx * ay - by * ax;
        if u == 0.0 || vv == 0.0 || w == 0.0 {
            // Exactly on an edge in single precision: decide in double precision.
            u = (cx as f64 * by as f64 - cy as f64 * bx as f64) as f32;
            vv = (ax as f64 * cy as f64 - ay as f64 * cx as f64) as f32;
            w = (bx as f64 * ay as f64 - by as f64 * ax as f64) as f32;
        }
        if (u < 0.0 || vv < 0.0 || w < 0.0) && (u > 0.0 || vv > 0.0 || w > 0.0) {
            return f32::INFINITY;
        }
        let det = u + vv + w;
        if det == 0.0 {
            return f32::INFINITY;
        }
        let az = a.dot(self.z_row);
        let bz = b.dot(self.z_row);
        let cz = c.dot(self.z_row);
        let t = (u * az + vv * bz + w * cz) / det;
        if t > t_min && t < t_max { t } else { f32::INFINITY }
    }
}

/// How the primitives are searched.
enum Search {
    /// An obvhs 8-wide BVH; primitives are stored in its leaf order.
    Bvh(CwBvh),
    /// A flat scan (small scenes): the triangles come first in the primitive order, tested
    /// four at a time; the analytic shapes follow, culled by their padded bounds.
    Scan {
        triangles: TriangleBatches,
        shapes: BoundsScan,
    },
}

/// The scene's ray-query structure: a BVH, or a flat scan for small scenes.
pub(crate) struct SceneBvh {
    search: Search,
    prims: Vec<Primitive>,
}

impl std::fmt::Debug for SceneBvh {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("SceneBvh")
            .field("primitives", &self.prims.len())
            .finish()
    }
}

/// The obvhs ray. Its node test picks slab sides by `direction < 0` but inverts −0.0 to a
/// large *negative* number, so an axis-aligned ray with a −0.0 component missed every node
/// (found by the watertightness test); adding +0.0 turns −0.0 into +0.0.
#[inline]
fn obvhs_ray(ray: &Ray, t_min: f32, t_max: f32) -> obvhs::ray::Ray {
    let direction = ray.direction + Vec3::ZERO;
    obvhs::ray::Ray::new(Vec3A::from(ray.origin), Vec3A::from(direction), t_min, t_max)
}

fn to_obvhs(b: pm_geom::Aabb) -> obvhs::aabb::Aabb {
    obvhs::aabb::Aabb::new(Vec3A::from(b.min), Vec3A::from(b.max))
}

impl SceneBvh {
    /// Builds the BVH, or the flat scan for at most [`SCAN_MAX_PRIMITIVES`] primitives;
    /// `prims` must not be empty.
    pub(crate) fn build(prims: Vec<Primitive>) -> Self {
        if prims.len() <= SCAN_MAX_PRIMITIVES {
            let (mut prims, shapes): (Vec<Primitive>, Vec<Primitive>) = prims
                .into_iter()
                .partition(|p| matches!(p, Primitive::Triangle { .. }));
            let triangles = TriangleBatches::new(
                prims
                    .iter()
                    .filter_map(|p| match p {
                        Primitive::Triangle { v, .. } => Some(*v),
                        _ => None,
                    })
                    .collect(),
            );
            let bounds: Vec<(Vec3, Vec3)> = shapes
                .iter()
                .map(|p| {
                    let b = p.bounds();
                    (b.min, b.max)
                })
                .collect();
            prims.extend(shapes);
            return SceneBvh {
                search: Search::Scan {
                    triangles,
                    shapes: BoundsScan::new(&bounds),
                },
                prims,
            };
        }
        let bounds: Vec<Bounded> = prims.iter().map(|p| Bounded(to_obvhs(p.bounds()))).collect();
        let bvh = obvhs::cwbvh::builder::build_cwbvh(
            &bounds,
            BvhBuildParams::medium_build(),
            &mut Duration::default(),
        );
        // Reorder once so that leaf index i is primitive i (see API-NOTES, index convention).
        let ordered = bvh.primitive_indices.iter().map(|&i| prims[i as usize]).collect();
        SceneBvh {
            search: Search::Bvh(bvh),
            prims: ordered,
        }
    }

    pub(crate) fn primitive(&self, index: u32) -> &Primitive {
        &self.prims[index as usize]
    }

    /// Closest hit in `(t_min, t_max)` among primitives accepted by `accept`: (t, primitive).
    #[inline]
    pub(crate) fn closest(
        &self,
        ray: &Ray,
        t_min: f32,
        t_max: f32,
        accept: impl Fn(PartId) -> bool,
    ) -> Option<(f32, u32)> {
        let w = WatertightRay::new(ray.origin, ray.direction);
        match &self.search {
            Search::Bvh(bvh) => {
                let mut hit = RayHit::none();
                let found = bvh.ray_traverse(obvhs_ray(ray, t_min, t_max), &mut hit, |r, i| {
                    let p = &self.prims[i];
                    if !accept(p.part()) {
                        return f32::INFINITY;
                    }
                    p.intersect(&w, r.tmin, r.tmax)
                });
                found.then_some((hit.t, hit.primitive_id))
            }
            Search::Scan { triangles, shapes } => {
                let best = std::cell::Cell::new((t_max, u32::MAX));
                triangles.for_each_hit(
                    &w,
                    t_min,
                    || best.get().0,
                    |i, t| {
                        if accept(self.prims[i].part()) {
                            best.set((t, i as u32));
                        }
                        true
                    },
                );
                let first = triangles.len();
                shapes.for_each_candidate(
                    &SlabRay::new(ray.origin, ray.direction),
                    t_min,
                    || best.get().0,
                    |i| {
                        let p = &self.prims[first + i];
                        if accept(p.part()) {
                            let t = p.intersect(&w, t_min, best.get().0);
                            if t < best.get().0 {
                                best.set((t, (first + i) as u32));
                            }
                        }
                        true
                    },
                );
                let (t, i) = best.get();
                (i != u32::MAX).then_some((t, i))
            }
        }
    }

    /// True when any primitive lies on the ray in `(t_min, t_max)`.
    #[inline]
    pub(crate) fn any_hit(&self, ray: &Ray, t_min: f32, t_max: f32) -> bool {
        let w = WatertightRay::new(ray.origin, ray.direction);
        match &self.search {
            Search::Bvh(bvh) => !bvh.ray_traverse_miss(obvhs_ray(ray, t_min, t_max), |r, i| {
                self.prims[i].intersect(&w, r.tmin, r.tmax)
            }),
            Search::Scan { triangles, shapes } => {
                let mut hit = false;
                triangles.for_each_hit(
                    &w,
                    t_min,
                    || t_max,
                    |_, _| {
                        hit = true;
                        false
                    },
                );
                if hit {
                    return true;
                }
                let first = triangles.len();
                shapes.for_each_candidate(
                    &SlabRay::new(ray.origin, ray.direction),
                    t_min,
                    || t_max,
                    |i| {
                        hit = self.prims[first + i].intersect(&w, t_min, t_max).is_finite();
                        !hit
                    },
                );
                hit
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn watertight_test_hits_the_shared_edge_of_two_triangles_exactly_once_or_twice_never_zero() {
        // A quad split along its diagonal; rays aimed exactly at the diagonal must hit.
        let q = [
            Vec3::new(0.0, 0.0, 0.0),
            Vec3::new(1.0, 0.0, 0.0),
            Vec3::new(1.0, 1.0, 0.0),
            Vec3::new(0.0, 1.0, 0.0),
        ];
        let t1 = [q[0], q[1], q[2]];
        let t2 = [q[0], q[2], q[3]];
        for i in 0..=100 {
            let s = i as f32 / 100.0;
            let target = Vec3::new(s, s, 0.0);
            let origin = Vec3::new(0.3, 0.7, 1.0);
            let w = WatertightRay::new(origin, (target - origin).normalize());
            let hits = [t1, t2]
                .iter()
                .filter(|t| w.intersect_triangle(t, 0.0, f32::INFINITY).is_finite())
                .count();
            assert!(hits >= 1, "ray to the diagonal at {s} slipped through");
        }
    }

    #[test]
    fn triangle_distance_matches_the_plane_distance() {
        let tri = [
            Vec3::new(-1.0, -1.0, 2.0),
            Vec3::new(1.0, -1.0, 2.0),
            Vec3::new(0.0, 1.0, 2.0),
        ];
        let d = Vec3::new(0.1, 0.05, 1.0).normalize();
        let w = WatertightRay::new(Vec3::ZERO, d);
        let t = w.intersect_triangle(&tri, 0.0, f32::INFINITY);
        assert!((t - 2.0 / d.z).abs() < 1e-5);
        let w = WatertightRay::new(Vec3::ZERO, -d);
        assert_eq!(w.intersect_triangle(&tri, 0.0, f32::INFINITY), f32::INFINITY);
    }
}
