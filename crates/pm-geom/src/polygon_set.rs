//! A set of convex polygons with precomputed normals, areas and bounds, and a bounding-volume
//! index answering "which polygons overlap this box" (the per-map geometry of the estimator).

use crate::Aabb;
use glam::Vec3;

/// Convex planar polygons stored flat, with an overlap index built by [`PolygonSet::build_index`].
#[derive(Clone, Debug, Default)]
pub struct PolygonSet {
    vertices: Vec<Vec3>,
    starts: Vec<u32>,
    normals: Vec<Vec3>,
    areas: Vec<f32>,
}

impl PolygonSet {
    /// An empty set.
    pub fn new() -> Self {
        Self::default()
    }

    /// Adds a convex planar polygon; returns its index, or `None` (and adds nothing) when it
    /// is degenerate (fewer than 3 vertices, zero area, non-finite).
    pub fn push(&mut self, polygon: &[Vec3]) -> Option<u32> {
        let _ = (polygon, &self.vertices, &self.starts, &self.normals, &self.areas);
        todo!("pm-geom issue")
    }

    /// (Re)builds the overlap index; call after the last `push`.
    pub fn build_index(&mut self) {
        todo!("pm-geom issue")
    }

    /// Number of polygons.
    pub fn len(&self) -> usize {
        self.normals.len()
    }

    /// True when there are no polygons.
    pub fn is_empty(&self) -> bool {
        self.normals.is_empty()
    }

    /// Vertices of polygon `i`.
    pub fn polygon(&self, i: u32) -> &[Vec3] {
        let _ = i;
        todo!("pm-geom issue")
    }

    /// Unit normal of polygon `i`.
    pub fn normal(&self, i: u32) -> Vec3 {
        self.normals[i as usize]
    }

    /// Area of polygon `i`.
    pub fn area(&self, i: u32) -> f32 {
        self.areas[i as usize]
    }

    /// Sum of all areas.
    pub fn total_area(&self) -> f32 {
        self.areas.iter().sum()
    }

    /// Calls `f(index)` once for every polygon whose bounds overlap `aabb` (a superset of the
    /// polygons that really intersect it). Allocates nothing.
    pub fn for_each_overlapping(&self, aabb: &Aabb, f: impl FnMut(u32)) {
        let _ = (aabb, f);
        todo!("pm-geom issue")
    }
}
