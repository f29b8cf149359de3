//! A set of convex polygons with precomputed normals, areas and bounds, and a bounding-volume
//! index answering "which polygons overlap this box" (the per-map geometry of the estimator).

use crate::aabb::Aabb;
use crate::bounds_bvh::BoundsBvh;
use crate::polygon::polygon_vector_area;
use glam::Vec3;

/// Convex planar polygons stored flat, with an overlap index built by [`PolygonSet::build_index`].
///
/// `Send + Sync`: build it once per photon map and share it between render threads.
#[derive(Clone, Debug, Default)]
pub struct PolygonSet {
    vertices: Vec<Vec3>,
    starts: Vec<u32>,
    normals: Vec<Vec3>,
    areas: Vec<f32>,
    bounds: Vec<Aabb>,
    index: BoundsBvh,
    /// Number of polygons the index covers; polygons pushed later are scanned linearly.
    indexed: usize,
}

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
        let id = u32::try_from(self.normals.len()).ok()?;
        let start = u32::try_from(self.vertices.len()).ok()?;
        u32::try_from(self.vertices.len() + polygon.len()).ok()?;
        self.starts.push(start);
        self.vertices.extend_from_slice(polygon);
        self.normals.push(normal);
        self.areas.push(area);
        self.bounds.push(Aabb::from_points(polygon));
        Some(id)
    }

    /// (Re)builds the overlap index; call after the last `push`. Until then queries still
    /// answer correctly, by scanning the polygons not yet indexed. Gives back the room the
    /// tables grew into (a scene's maps hold tens of thousands of sets, most of a few
    /// polygons, where growth would leave three times what they use).
    pub fn build_index(&mut self) {
        self.vertices.shrink_to_fit();
        self.starts.shrink_to_fit();
        self.normals.shrink_to_fit();
        self.areas.shrink_to_fit();
        self.bounds.shrink_to_fit();
        self.index = BoundsBvh::build(&self.bounds);
        self.indexed = self.bounds.len();
    }

    /// Number of polygons.
    pub fn len(&self) -> usize {
        self.normals.len()
    }

    /// True when there are no polygons.
    pub fn is_empty(&self) -> bool {
        self.normals.is_empty()
    }

    /// Vertices of polygon `i`. Panics when `i >= len()`, like slice indexing.
    pub fn polygon(&self, i: u32) -> &[Vec3] {
        let i = i as usize;
        let start = self.starts[i] as usize;
        let end = self
            .starts
            .get(i + 1)
            .map_or(self.vertices.len(), |&s| s as usize);
        &self.vertices[start..end]
    }

    /// Unit normal of polygon `i`.
    pub fn normal(&self, i: u32) -> Vec3 {
        self.normals[i as usize]
    }

    /// Area of polygon `i`.
    pub fn area(&self, i: u32) -> f32 {
        self.areas[i as usize]
    }

    /// Bounding box of polygon `i`.
    pub fn polygon_bounds(&self, i: u32) -> Aabb {
        self.bounds[i as usize]
    }

    /// Bounding box of all polygons ([`Aabb::EMPTY`] for none).
    pub fn bounds(&self) -> Aabb {
        self.bounds.iter().fold(Aabb::EMPTY, |a, &b| a.union(b))
    }

    /// Sum of all areas.
    pub fn total_area(&self) -> f32 {
        self.areas.iter().sum()
    }

    /// Calls `f(index)` once for every polygon whose bounds overlap `aabb` (a superset of the
    /// polygons that really intersect it). Allocates nothing.
    pub fn for_each_overlapping(&self, aabb: &Aabb, mut f: impl FnMut(u32)) {
        let bounds = &self.bounds;
        self.index.for_each_candidate(aabb, |i| {
            if bounds[i as usize].overlaps(aabb) {
                f(i)
            }
        });
        for (i, b) in bounds.iter().enumerate().skip(self.indexed) {
            if b.overlaps(aabb) {
                f(i as u32);
            }
        }
    }
}
