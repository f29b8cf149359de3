//! The scene's BVH (obvhs `CwBvh`) over triangles and analytic shape parts, with our own
//! watertight ray–triangle test (Woop, Benthin & Wald 2013): no ray slips between the
//! triangles of a closed mesh, which obvhs's own Möller–Trumbore test allows.

use crate::shape::{Ring, RingSide, Sphere};
use crate::{PartId, Ray};
use glam::{Vec3, Vec3A};
use obvhs::cwbvh::CwBvh;
use obvhs::cwbvh::bvh2_to_cwbvh::bvh2_to_cwbvh;
use obvhs::ray::RayHit;

mod batch;
mod sah;
mod scan;

use batch::TriangleBatches;
use scan::BoundsScan;

/// Scenes with at most this many primitives are searched by a flat scan (every triangle four
/// at a time, analytic shapes behind padded bounds) instead of the BVH. Measured on random
/// rays inside the built-in scenes: the scan is about 10 % faster at 12 triangles
/// (`cornell-box`) and 25 % at 24 (`lit-unlit-rooms`), and even at 48 (`colored-rooms`).
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

/// How far (in ray parameter units) the obvhs traversal starts behind the true origin.
///
/// obvhs's node test raises every child box's entry distance to at least 1e-4 (an absolute
/// `EPSILON` in `cwbvh::node`), so a box the ray leaves before `t = 1e-4` was culled: a wall
/// within 0.1 mm of the origin (in metres) was never hit, and rays starting near a corner
/// passed through the adjacent wall. Traversing from `origin − BACKSTEP · direction` puts
/// every true distance `t ≥ 0` at `t + BACKSTEP > 1e-4`; the exact tests keep the true origin.
const BACKSTEP: f32 = 2e-4;

/// The obvhs ray for distances `(t_min, t_max)` of `ray`, started [`BACKSTEP`] behind it.
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
fn obvhs_ray(ray: &Ray, t_min: f32, t_max: f32) -> obvhs::ray::Ray {
    let direction = Vec3A::from(ray.direction + Vec3::ZERO);
    let origin = Vec3A::from(ray.origin) - direction * BACKSTEP;
    obvhs::ray::Ray {
        origin,
        direction,
        inv_direction: direction.recip().clamp(Vec3A::splat(-1e30), Vec3A::splat(1e30)),
        tmin: t_min + BACKSTEP,
        tmax: t_max + BACKSTEP,
    }
}

fn to_obvhs(b: pm_geom::Aabb) -> obvhs::aabb::Aabb {
    obvhs::aabb::Aabb::new(Vec3A::from(b.min), Vec3A::from(b.max))
}

impl SceneBvh {
    /// Builds the BVH, or the flat scan for at most [`SCAN_MAX_PRIMITIVES`] primitives;
    /// `prims` must not be empty.
    pub(crate) fn build(prims: Vec<Primitive>) -> Self {
        if prims.len() <= SCAN_MAX_PRIMITIVES {
            Self::build_scan(prims)
        } else {
            Self::build_bvh(prims)
        }
    }

    /// The flat scan: triangles first (tested four at a time), then the analytic shapes.
    fn build_scan(prims: Vec<Primitive>) -> Self {
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
        SceneBvh {
            search: Search::Scan {
                triangles,
                shapes: BoundsScan::new(&bounds),
            },
            prims,
        }
    }

    /// The obvhs BVH over any number of primitives.
    fn build_bvh(prims: Vec<Primitive>) -> Self {
        // Bounds are finite: scene positions and shapes are checked when the scene is built.
        let bounds: Vec<obvhs::aabb::Aabb> = prims.iter().map(|p| to_obvhs(p.bounds())).collect();
        let bvh = bvh2_to_cwbvh(&sah::build_bvh2(&bounds), 3, true, false);
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
            Search::Bvh(bvh) => self.closest_in_bvh(bvh, ray, &w, t_min, t_max, accept),
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
                    ray.origin,
                    ray.direction,
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

    /// [`SceneBvh::closest`] through the BVH. Not inlined: the BVH serves large scenes,
    /// where a call is nothing beside the traversal, and keeping it out of line keeps the
    /// small scenes' scan tight.
    #[inline(never)]
    fn closest_in_bvh(
        &self,
        bvh: &CwBvh,
        ray: &Ray,
        w: &WatertightRay,
        t_min: f32,
        t_max: f32,
        accept: impl Fn(PartId) -> bool,
    ) -> Option<(f32, u32)> {
        // The exact closest hit is kept here; obvhs only gets a distance to prune by
        // (shifted by BACKSTEP and rounded up a little, so pruning stays conservative).
        let mut best = (t_max, u32::MAX);
        bvh.ray_traverse(obvhs_ray(ray, t_min, t_max), &mut RayHit::none(), |_, i| {
            let p = &self.prims[i];
            if !accept(p.part()) {
                return f32::INFINITY;
            }
            let t = p.intersect(w, t_min, best.0);
            if t < best.0 {
                best = (t, i as u32);
                (t + BACKSTEP) * (1.0 + 1e-6)
            } else {
                f32::INFINITY
            }
        });
        (best.1 != u32::MAX).then_some(best)
    }

    /// True when any primitive lies on the ray in `(t_min, t_max)`.
    #[inline]
    pub(crate) fn any_hit(&self, ray: &Ray, t_min: f32, t_max: f32) -> bool {
        let w = WatertightRay::new(ray.origin, ray.direction);
        match &self.search {
            Search::Bvh(bvh) => !bvh.ray_traverse_miss(obvhs_ray(ray, t_min, t_max), |_, i| {
                // Any distance below obvhs's (shifted) t_max reports the hit.
                if self.prims[i].intersect(&w, t_min, t_max).is_finite() {
                    f32::NEG_INFINITY
                } else {
                    f32::INFINITY
                }
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
                    ray.origin,
                    ray.direction,
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
    use crate::Rng;
    use crate::sampling::uniform_sphere;
    use glam::Vec2;

    /// The flat scan tests every triangle, so it is the brute-force reference for the BVH:
    /// both must find the same closest distance (bit for bit) and the same any-hit answer,
    /// also for rays starting within 1e-6…1e-4 of a surface (near corners these hit the
    /// adjacent wall almost at once; obvhs's node test used to cull such hits).
    #[test]
    fn the_bvh_finds_exactly_the_hits_of_the_flat_scan() {
        for name in ["lit-unlit-rooms", "touching-rooms", "cornell-box"] {
            let scene = crate::scenes::build(name).unwrap();
            let prims = scene.search().prims.clone();
            let triangles: Vec<([Vec3; 3], Vec3)> = prims
                .iter()
                .filter_map(|p| match *p {
                    Primitive::Triangle { v, normal, .. } => Some((v, normal)),
                    _ => None,
                })
                .collect();
            let (scan, bvh) = (SceneBvh::build_scan(prims.clone()), SceneBvh::build_bvh(prims));
            assert!(matches!(scan.search, Search::Scan { .. }) && matches!(bvh.search, Search::Bvh(_)));
            let bounds = scene.bounds();
            let mut rng = Rng::new(17, 3);
            let mut near_hits = 0;
            for k in 0..100_000 {
                let mut u = || rng.next_f32();
                let origin = if k % 2 == 0 {
                    bounds.min + (bounds.max - bounds.min) * Vec3::new(u(), u(), u())
                } else {
                    let (v, normal) = triangles[(u() * triangles.len() as f32) as usize % triangles.len()];
                    let (a, b) = (u(), u());
                    let (a, b) = if a + b > 1.0 { (1.0 - a, 1.0 - b) } else { (a, b) };
                    let offset = 1e-6 * 100f32.powf(u()) * if u() < 0.5 { -1.0 } else { 1.0 };
                    v[0] + (v[1] - v[0]) * a + (v[2] - v[0]) * b + normal * offset
                };
                // Every fifth ray runs exactly along an axis, or nearly so (a component below
                // obvhs's inverse-direction cut-off of f32::EPSILON).
                let direction = match k % 5 {
                    0 => {
                        let mut d = Vec3::ZERO;
                        d[(u() * 3.0) as usize % 3] = if u() < 0.5 { -1.0 } else { 1.0 };
                        if k % 10 == 0 {
                            d[(u() * 3.0) as usize % 3] += 1e-8;
                        }
                        d.normalize()
                    }
                    _ => uniform_sphere(Vec2::new(u(), u())),
                };
                let ray = Ray { origin, direction };
                let t_max = if k % 3 == 0 { 0.05 } else { f32::INFINITY };
                let expected = scan.closest(&ray, 0.0, t_max, |_| true).map(|(t, _)| t.to_bits());
                let found = bvh.closest(&ray, 0.0, t_max, |_| true).map(|(t, _)| t.to_bits());
                assert_eq!(
                    found, expected,
                    "{name}: closest, ray {k} from {origin} along {direction}"
                );
                assert_eq!(
                    bvh.any_hit(&ray, 0.0, t_max),
                    expected.is_some(),
                    "{name}: any hit, ray {k}"
                );
                near_hits += expected.is_some_and(|t| f32::from_bits(t) < 1e-4) as u32;
            }
            assert!(near_hits > 100, "{name}: only {near_hits} hits closer than 1e-4");
        }
    }

    #[test]
    fn rays_along_an_axis_find_walls_far_away_just_inside_their_edge() {
        // A wall at x = 10 spanning y, z ∈ [0, 1]; rays along +x at heights just below its top
        // edge. obvhs inverts a zero direction component to 1/f32::EPSILON, not infinity, so
        // its node test would see the slab in y end after t = (1 − y) / f32::EPSILON.
        let wall = |x: f32| {
            [
                Primitive::triangle(
                    [
                        Vec3::new(x, 0.0, 0.0),
                        Vec3::new(x, 1.0, 0.0),
                        Vec3::new(x, 1.0, 1.0),
                    ],
                    PartId(0),
                ),
                Primitive::triangle(
                    [
                        Vec3::new(x, 0.0, 0.0),
                        Vec3::new(x, 1.0, 1.0),
                        Vec3::new(x, 0.0, 1.0),
                    ],
                    PartId(0),
                ),
            ]
        };
        let prims: Vec<Primitive> = (0..40).flat_map(|i| wall(10.0 + i as f32)).collect();
        let (scan, bvh) = (SceneBvh::build_scan(prims.clone()), SceneBvh::build_bvh(prims));
        for below in [1e-7f32, 1e-6, 1e-5, 1e-3] {
            for direction in [Vec3::X, Vec3::new(1.0, 1e-9, 0.0)] {
                let ray = Ray {
                    origin: Vec3::new(0.0, 1.0 - below, 0.5),
                    direction,
                };
                let expected = scan.closest(&ray, 0.0, f32::INFINITY, |_| true).map(|(t, _)| t);
                assert_eq!(expected, Some(10.0), "{below}");
                let found = bvh.closest(&ray, 0.0, f32::INFINITY, |_| true).map(|(t, _)| t);
                assert_eq!(found, expected, "{below} below the edge along {direction}");
                assert!(bvh.any_hit(&ray, 0.0, f32::INFINITY));
            }
        }
    }

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
