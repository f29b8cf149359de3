//! The scene's ray-query structure: its triangles in an obvhs `CwBvh` (built by our own SAH
//! builder) or, in small scenes, a flat scan four at a time; its analytic shape parts (spheres,
//! ring sides) likewise, apart. Every triangle test is watertight (Woop, Benthin & Wald
//! 2013): no ray slips between the triangles of a closed mesh, which obvhs's own
//! Möller–Trumbore test allows.
//!
//! Triangles are stored once, as their three corners in the BVH's leaf order (36 bytes), with
//! their part and its surface beside them (8 bytes); the normal is computed when a ray hits. Shapes are few
//! and kept apart, so the triangle loop never branches on a primitive kind.

use crate::part::{PartId, PartSurface};
use crate::ray::Ray;
use glam::{Vec3, Vec3A};
use obvhs::cwbvh::CwBvh;
use obvhs::cwbvh::bvh2_to_cwbvh::bvh2_to_cwbvh;

mod batch;
pub(crate) mod closest;
mod pair;
pub(crate) mod pieces;
mod relabel;
mod sah;
mod scan;
pub(crate) mod shape;
pub(crate) mod traverse;
mod watertight;

use batch::TriangleBatches;
use pieces::{PIECES, PieceIndex};
use scan::BoundsScan;
pub(crate) use shape::ShapePrimitive;
use traverse::for_each_leaf_primitive;
pub(crate) use watertight::WatertightRay;

/// Triangle sets (and shape sets) of at most this many are searched by a flat scan instead
/// of a BVH. Measured on random rays inside the built-in scenes: the scan is about 10 %
/// faster at 12 triangles (`cornell-box`) and 25 % at 24 (`lit-unlit-rooms`), and even at 48
/// (`colored-rooms`).
const SCAN_MAX_PRIMITIVES: usize = 64;

/// Unit normal of a counter-clockwise triangle.
#[inline]
fn triangle_normal(v: &[Vec3; 3]) -> Vec3 {
    (v[1] - v[0]).cross(v[2] - v[0]).normalize()
}

/// How a set of primitives is searched.
enum Search<Scan> {
    /// Nothing to search.
    Empty,
    /// A flat scan (small sets).
    Scan(Scan),
    /// An obvhs 8-wide BVH; the primitives are stored in its leaf order.
    Bvh(CwBvh),
}

/// Which primitive a ray hit: a triangle, or a shape (by index in their own lists).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum HitPrimitive {
    Triangle(u32),
    Shape(u32),
}

/// The surface a ray leaves, which a query may skip: a triangle (by its index in the search's
/// order) or nothing (a ray from a shape, or not from a surface).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum Leaving {
    /// A triangle, never met again by a ray leaving its plane.
    Triangle(u32),
    /// Nothing skipped.
    Nothing,
}

/// A triangle as the ray queries read it: its corners, its part and its part's surface (an
/// index in the scene's surface table), in one 44-byte record, so that a hit needs no lookup
/// of its surface in a per-part table (in a scene of 10⁵ triangles, another cache miss). A
/// triangle of a face the contact partition cut into pieces of several parts carries
/// [`PIECES`] and its face's piece list in `part` instead ([`pieces`]).
#[derive(Clone, Copy, Debug)]
struct TriangleRecord {
    v: [Vec3; 3],
    part: PartId,
    surface: u32,
}

/// The scene's ray-query structure.
pub(crate) struct SceneBvh {
    /// Each triangle, in the search's order.
    triangles: Vec<TriangleRecord>,
    triangle_search: Search<TriangleBatches>,
    /// For a hierarchy, each record's index among the triangles it was built from (empty for
    /// a scan, whose records keep their order).
    input_index: Vec<u32>,
    /// Records that are never met ([`SceneBvh::with_parts_of`]).
    dropped: usize,
    shapes: Vec<ShapePrimitive>,
    shape_search: Search<BoundsScan>,
    /// The pieces of cut faces (empty unless the contact partition cut some).
    pieces: PieceIndex,
}

impl std::fmt::Debug for SceneBvh {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("SceneBvh")
            .field("triangles", &self.triangles.len())
            .field("shapes", &self.shapes.len())
            .finish()
    }
}

fn to_obvhs(b: pm_geom::Aabb) -> obvhs::aabb::Aabb {
    obvhs::aabb::Aabb::new(Vec3A::from(b.min), Vec3A::from(b.max))
}

/// An 8-wide BVH over `bounds` (not empty), and the order of its leaves.
fn build_cwbvh(bounds: Vec<obvhs::aabb::Aabb>) -> (CwBvh, Vec<u32>) {
    let bvh2 = sah::build_bvh2(&bounds);
    // Freed before the conversion, which needs about as much again as the binary tree.
    drop(bounds);
    let mut bvh = bvh2_to_cwbvh(&bvh2, 3, true, false);
    // Leaf index i will be primitive i once the caller reorders by this; obvhs's traversal
    // never reads the indices, so the caller keeps them instead.
    let order = std::mem::take(&mut bvh.primitive_indices);
    // The converter reserves nodes for the worst case (one per primitive).
    bvh.nodes.shrink_to_fit();
    (bvh, order)
}

impl SceneBvh {
    /// The search structure of `triangles` (corners, and part and surface of each) and
    /// `shapes`, with a flat scan for sets of at most [`SCAN_MAX_PRIMITIVES`] and a BVH for
    /// larger ones.
    pub(crate) fn build(
        triangles: Vec<[Vec3; 3]>,
        parts: Vec<PartSurface>,
        shapes: Vec<ShapePrimitive>,
    ) -> Self {
        Self::build_with(triangles, parts, shapes, SCAN_MAX_PRIMITIVES)
    }

    /// [`SceneBvh::build`] with sets above `scan_max` in a BVH (tests force either kind).
    fn build_with(
        triangles: Vec<[Vec3; 3]>,
        parts: Vec<PartSurface>,
        shapes: Vec<ShapePrimitive>,
        scan_max: usize,
    ) -> Self {
        let record = |i: usize| TriangleRecord {
            v: triangles[i],
            part: parts[i].part,
            surface: parts[i].surface,
        };
        let (triangles, triangle_search, input_index) = if triangles.is_empty() {
            (Vec::new(), Search::Empty, Vec::new())
        } else if triangles.len() <= scan_max {
            let records = (0..triangles.len()).map(record).collect();
            let scan = Search::Scan(TriangleBatches::new(triangles.clone()));
            (records, scan, Vec::new())
        } else {
            let bounds = triangles
                .iter()
                .map(|v| to_obvhs(pm_geom::Aabb::from_points(v)))
                .collect();
            let (bvh, order) = build_cwbvh(bounds);
            let records = order.iter().map(|&i| record(i as usize)).collect();
            (records, Search::Bvh(bvh), order)
        };
        let (shapes, shape_search) = if shapes.is_empty() {
            (shapes, Search::Empty)
        } else if shapes.len() <= scan_max {
            let boxes: Vec<(Vec3, Vec3)> = shapes
                .iter()
                .map(|s| s.bounds())
                .map(|b| (b.min, b.max))
                .collect();
            (shapes, Search::Scan(BoundsScan::new(&boxes)))
        } else {
            let (bvh, order) = build_cwbvh(shapes.iter().map(|s| to_obvhs(s.bounds())).collect());
            (
                order.iter().map(|&i| shapes[i as usize]).collect(),
                Search::Bvh(bvh),
            )
        };
        SceneBvh {
            triangles,
            triangle_search,
            input_index,
            dropped: 0,
            shapes,
            shape_search,
            pieces: PieceIndex::default(),
        }
    }

    /// A search of `triangles` with `parts`, where a part may be a list of `pieces`
    /// ([`PieceIndex::push`]), and of this one's shapes: the contact partition's faces as
    /// the user gave them, each hit located among its pieces.
    pub(crate) fn with_triangles(
        &self,
        triangles: Vec<[Vec3; 3]>,
        parts: Vec<PartSurface>,
        pieces: PieceIndex,
    ) -> Self {
        let mut bvh = Self::build(triangles, parts, self.shapes.clone());
        bvh.pieces = pieces;
        bvh
    }

    /// The part and surface of triangle record `record` at `p`: its own, or the piece's that
    /// `p` lies in when its face was cut; `None` when `p` lies in no piece (where the
    /// partition dropped a hidden copy of a coincident face: a ray passes there).
    #[inline(always)]
    fn record_part(&self, record: &TriangleRecord, p: Vec3) -> Option<PartSurface> {
        if record.part.0 & PIECES == 0 {
            return Some(PartSurface {
                part: record.part,
                surface: record.surface,
            });
        }
        self.piece_part(record, p)
    }

    #[cold]
    #[inline(never)]
    fn piece_part(&self, record: &TriangleRecord, p: Vec3) -> Option<PartSurface> {
        self.pieces.locate(record.part.0 & !PIECES, p)
    }

    /// The part and surface, and the unit geometric normal at `p`, of a primitive that was
    /// hit (triangles: counter-clockwise winding); `None` where a ray passes a cut face
    /// ([`SceneBvh::record_part`]). The closest-hit searches do not ask, so the few pieces of
    /// a cut face are looked through once per hit, not at every crossing on the way.
    #[inline]
    pub(crate) fn part_and_normal(&self, hit: HitPrimitive, p: Vec3) -> Option<(PartSurface, Vec3)> {
        match hit {
            HitPrimitive::Triangle(i) => {
                let record = &self.triangles[i as usize];
                Some((self.record_part(record, p)?, triangle_normal(&record.v)))
            }
            HitPrimitive::Shape(i) => {
                let s = &self.shapes[i as usize];
                Some((s.part(), s.normal_at(p)))
            }
        }
    }

    /// The unit geometric normal at `p` of a primitive that was hit.
    #[inline]
    pub(crate) fn normal_at(&self, hit: HitPrimitive, p: Vec3) -> Vec3 {
        match hit {
            HitPrimitive::Triangle(i) => triangle_normal(&self.triangles[i as usize].v),
            HitPrimitive::Shape(i) => self.shapes[i as usize].normal_at(p),
        }
    }

    /// Where `ray` meets triangle `hit` at distance `t`, moved onto the triangle's plane: the
    /// ray's point `o + t·d` written in the triangle's own coordinates, `v₀ + b₁ e₁ + b₂ e₂`
    /// (its weights by projection along the face normal), with the magnitude that point's
    /// rounding scales with (the largest coordinate of `|v₀| + |b₁ e₁| + |b₂ e₂|`) and the
    /// triangle's condition `L² / 2A`. However thin
    /// the triangle, the point lies on its plane within a few units in the last place of that
    /// magnitude (where it lies within the plane matters little), while `o + t·d` carries t's
    /// error, which a sliver magnifies. `None` for shapes, and for triangles whose squared normal leaves f32's range.
    #[inline]
    pub(crate) fn interpolated_point(
        &self,
        ray: &Ray,
        hit: HitPrimitive,
        t: f32,
    ) -> Option<(Vec3, f32, f32)> {
        let HitPrimitive::Triangle(i) = hit else {
            return None;
        };
        let v = &self.triangles[i as usize].v;
        let (e1, e2) = (v[1] - v[0], v[2] - v[0]);
        let n = e1.cross(e2);
        let q = ray.at(t) - v[0];
        let inverse = 1.0 / n.length_squared();
        // |n|² overflows for edges past about 4·10⁹ m and underflows below about 10⁻¹⁰ m: the
        // ray's own point then (a zero inverse would put every hit on the first corner).
        if !(inverse.is_finite() && inverse > 0.0) {
            return None;
        }
        let (b1, b2) = (q.cross(e2).dot(n) * inverse, e1.cross(q).dot(n) * inverse);
        let (p1, p2) = (e1 * b1, e2 * b2);
        let point = v[0] + p1 + p2;
        let magnitude = (v[0].abs() + p1.abs() + p2.abs()).max_element();
        // The triangle's condition, longest edge squared over twice the area: how much the
        // watertight test's distance, and so `o + t·d`, may be off for a thin triangle.
        let longest = e1
            .length_squared()
            .max(e2.length_squared())
            .max((e2 - e1).length_squared());
        let condition = longest * inverse.sqrt();
        (point.is_finite() && magnitude.is_finite() && condition.is_finite())
            .then_some((point, magnitude, condition))
    }

    /// Number of triangles a ray may meet.
    pub(crate) fn triangle_count(&self) -> usize {
        self.triangles.len() - self.dropped
    }

    /// Heap bytes held (for memory accounting).
    pub(crate) fn heap_bytes(&self) -> usize {
        fn search_bytes<S>(search: &Search<S>, scan_bytes: impl Fn(&S) -> usize) -> usize {
            match search {
                Search::Empty => 0,
                Search::Scan(s) => scan_bytes(s),
                Search::Bvh(b) => b.nodes.capacity() * size_of::<obvhs::cwbvh::node::CwBvhNode>(),
            }
        }
        self.triangles.capacity() * size_of::<TriangleRecord>()
            + self.input_index.capacity() * size_of::<u32>()
            + self.shapes.capacity() * size_of::<ShapePrimitive>()
            + search_bytes(&self.triangle_search, TriangleBatches::heap_bytes)
            + search_bytes(&self.shape_search, BoundsScan::heap_bytes)
            + self.pieces.heap_bytes()
    }

    /// True when any primitive lies on the ray in `(t_min, t_max)`.
    #[inline]
    pub(crate) fn any_hit(&self, ray: &Ray, t_min: f32, t_max: f32) -> bool {
        self.any_hit_leaving(ray, t_min, t_max, Leaving::Nothing)
    }

    /// [`SceneBvh::any_hit`] for a ray that leaves the surface of `leaving`: a ray leaving a
    /// triangle's plane never meets that triangle again, so it is not tested. (Tested, a
    /// sliver's own triangle is found again now and then: the watertight test's distance
    /// errs by its condition `L² / 2A` times the rounding of its corners, more than the
    /// offset off a sliver, and the ray's own surface would shadow it.)
    #[inline]
    pub(crate) fn any_hit_leaving(&self, ray: &Ray, t_min: f32, t_max: f32, leaving: Leaving) -> bool {
        let skipped = match leaving {
            Leaving::Triangle(i) => i as usize,
            Leaving::Nothing => usize::MAX,
        };
        let w = WatertightRay::new(ray.origin, ray.direction);
        let triangle_hit = match &self.triangle_search {
            Search::Empty => false,
            Search::Scan(batches) => {
                let mut hit = false;
                batches.for_each_hit(
                    &w,
                    t_min,
                    || t_max,
                    |i, _| {
                        hit = i != skipped;
                        !hit
                    },
                );
                hit
            }
            Search::Bvh(bvh) => {
                let mut hit = false;
                for_each_leaf_primitive::<false>(bvh, ray, t_min, t_max, |i, _| {
                    hit = i != skipped
                        && w.intersect_triangle(&self.triangles[i].v, t_min, t_max)
                            .is_finite();
                    !hit
                });
                hit
            }
        };
        triangle_hit || self.any_shape_hit(ray, t_min, t_max)
    }

    fn any_shape_hit(&self, ray: &Ray, t_min: f32, t_max: f32) -> bool {
        let hits = |i: usize| {
            self.shapes[i]
                .intersect(ray.origin, ray.direction, t_min, t_max)
                .is_finite()
        };
        match &self.shape_search {
            Search::Empty => false,
            Search::Scan(scan) => {
                let mut hit = false;
                scan.for_each_candidate(
                    ray.origin,
                    ray.direction,
                    t_min,
                    || t_max,
                    |i| {
                        hit = hits(i);
                        !hit
                    },
                );
                hit
            }
            Search::Bvh(bvh) => {
                let mut hit = false;
                for_each_leaf_primitive::<false>(bvh, ray, t_min, t_max, |i, _| {
                    hit = hits(i);
                    !hit
                });
                hit
            }
        }
    }
}

#[cfg(test)]
mod tests;
