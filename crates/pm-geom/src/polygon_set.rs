//! A set of convex polygons with precomputed normals, areas and bounds, and a bounding-volume
//! index answering "which polygons overlap this box" (the per-map geometry of the estimator).

use crate::aabb::Aabb;
use crate::bounds_bvh::{BoundsBvh, MAX_LEAF};
use crate::polygon::polygon_vector_area;
use glam::Vec3;

/// Convex planar polygons stored flat, with an overlap index built by [`PolygonSet::build_index`].
///
/// `Send + Sync`: build it once per photon map and share it between render threads.
#[derive(Clone, Debug, Default)]
pub struct PolygonSet {
    vertices: Vec<Vec3>,
    /// Each polygon's record, in one table: a scene's maps hold tens of thousands of sets,
    /// most of a few polygons, where every separate table is an allocation of its own.
    polygons: Vec<PolygonRecord>,
    index: BoundsBvh,
    /// Number of polygons the index covers; polygons pushed later are scanned linearly.
    indexed: usize,
}

/// One polygon: where its vertices start, its area, unit normal and bounds.
#[derive(Clone, Copy, Debug)]
struct PolygonRecord {
    start: u32,
    area: f32,
    normal: Vec3,
    bounds: Aabb,
}

/// Sets of at most this many polygons are scanned rather than indexed: an index over them
/// would be one leaf, tested in the same order.
const SCANNED: usize = MAX_LEAF;

impl PolygonSet {
    /// An empty set.
    pub fn new() -> Self {
        Self::default()
    }

    /// Adds a convex planar polygon; returns its index, or `None` (and adds nothing) when it
    /// is degenerate (fewer than 3 vertices, zero area, non-finite).
    pub fn push(&mut self, polygon: &[Vec3]) -> Option<u32> {
        if polygon.len() < 3 || !polygon.iter().all(|p| p.is_finite()) {
            return None;
        }
        let vector_area = polygon_vector_area(polygon);
        let area = vector_area.length();
        let normal = vector_area.try_normalize()?;
        if !area.is_finite() || area <= 0.0 {
            return None;
        }
        let id = u32::try_from(self.polygons.len()).ok()?;
        let start = u32::try_from(self.vertices.len()).ok()?;
        u32::try_from(self.vertices.len() + polygon.len()).ok()?;
        self.vertices.extend_from_slice(polygon);
        self.polygons.push(PolygonRecord {
            start,
            area,
            normal,
            bounds: Aabb::from_points(polygon),
        });
        Some(id)
    }

    /// (Re)builds the overlap index; call after the last `push`. Until then queries still
    /// answer correctly, by scanning the polygons not yet indexed. Gives back the room the
    /// tables grew into (most sets hold a few polygons, where growth would leave three times
    /// what they use); a set of at most four polygons is scanned, as one leaf would be.
    pub fn build_index(&mut self) {
        self.vertices.shrink_to_fit();
        self.polygons.shrink_to_fit();
        if self.polygons.len() <= SCANNED {
            self.index = BoundsBvh::default();
            self.indexed = 0;
            return;
        }
        let polygons = &self.polygons;
        self.index = BoundsBvh::build_by(polygons.len(), |i| polygons[i as usize].bounds, MAX_LEAF);
        self.indexed = self.polygons.len();
    }

    /// Number of polygons.
    pub fn len(&self) -> usize {
        self.polygons.len()
    }

    /// True when there are no polygons.
    pub fn is_empty(&self) -> bool {
        self.polygons.is_empty()
    }

    /// Vertices of polygon `i`. Panics when `i >= len()`, like slice indexing.
    pub fn polygon(&self, i: u32) -> &[Vec3] {
        let i = i as usize;
        let start = self.polygons[i].start as usize;
        let end = self
            .polygons
            .get(i + 1)
            .map_or(self.vertices.len(), |p| p.start as usize);
        &self.vertices[start..end]
    }

    /// Unit normal of polygon `i`.
    pub fn normal(&self, i: u32) -> Vec3 {
        self.polygons[i as usize].normal
    }

    /// Area of polygon `i`.
    pub fn area(&self, i: u32) -> f32 {
        self.polygons[i as usize].area
    }

    /// Bounding box of polygon `i`.
    pub fn polygon_bounds(&self, i: u32) -> Aabb {
        self.polygons[i as usize].bounds
    }

    /// Bounding box of all polygons ([`Aabb::EMPTY`] for none).
    pub fn bounds(&self) -> Aabb {
        self.polygons.iter().fold(Aabb::EMPTY, |a, p| a.union(p.bounds))
    }

    /// Sum of all areas.
    pub fn total_area(&self) -> f32 {
        self.polygons.iter().map(|p| p.area).sum()
    }

    /// Calls `f(index)` once for every polygon whose bounds overlap `aabb` (a superset of the
    /// polygons that really intersect it). Allocates nothing.
    pub fn for_each_overlapping(&self, aabb: &Aabb, mut f: impl FnMut(u32)) {
        let polygons = &self.polygons;
        self.index.for_each_candidate(aabb, |i| {
            if polygons[i as usize].bounds.overlaps(aabb) {
                f(i)
            }
        });
        for (i, p) in polygons.iter().enumerate().skip(self.indexed) {
            if p.bounds.overlaps(aabb) {
                f(i as u32);
            }
        }
    }
}
