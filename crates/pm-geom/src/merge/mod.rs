//! Merging coplanar, edge-connected convex polygons into fewer, larger convex polygons, so a
//! gather volume over a finely tessellated flat surface clips one polygon instead of hundreds.
//!
//! Polygons join only when they share an edge (identical endpoints, walked in opposite
//! directions, used by no third polygon) and lie in the plane of their region's first polygon
//! within a tolerance relative to the input's size. A coplanar region whose outline is one
//! convex loop becomes that loop; any other region is merged greedily, neighbour by
//! neighbour, while each union stays convex. Every merge keeps the area (checked), so the
//! area of the set inside any volume is unchanged up to rounding.

mod greedy;
mod outline;

use crate::aabb::Aabb;
use crate::fast_hash::{FastHashMap, fast_map_with_capacity};
use crate::polygon::polygon_vector_area;
use glam::{DVec3, Vec3};
use greedy::SharedEdge;
use outline::{VertexKey, accepts, simplify_outline};
use std::collections::HashMap;

/// Tolerances of [`CoplanarMerger`].
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct MergeOptions {
    /// Largest distance of a vertex from its region's plane, and of a dropped collinear vertex
    /// from the line of its neighbours, as a fraction of the input's bounding-box diagonal
    /// (plus four `f32` roundings of the largest coordinate).
    pub relative_distance: f32,
    /// Largest angle between the normals of polygons merged together, in radians.
    pub max_angle: f32,
}

impl MergeOptions {
    /// Tight tolerances: `1e-6` of the scene's size and `2e-3` rad (about 0.1°), above the
    /// rounding of `f32` meshes and far below any modelled crease.
    pub const DEFAULT: MergeOptions = MergeOptions {
        relative_distance: 1e-6,
        max_angle: 2e-3,
    };
}

impl Default for CoplanarMerger {
    fn default() -> Self {
        Self::new(MergeOptions::DEFAULT)
    }
}

impl Default for MergeOptions {
    fn default() -> Self {
        Self::DEFAULT
    }
}

/// Collects convex planar polygons, then hands back the same surface as fewer convex polygons
/// ([`CoplanarMerger::merge`]). Runs in about linear time in the polygon count.
///
/// ```
/// use pm_geom::{CoplanarMerger, MergeOptions};
/// use pm_geom::glam::vec3;
///
/// // A 4 × 4 grid of unit quads on the floor becomes one quad.
/// let mut merger = CoplanarMerger::new(MergeOptions::DEFAULT);
/// for i in 0..4 {
///     for j in 0..4 {
///         let (x, z) = (i as f32, j as f32);
///         merger.push(&[vec3(x, 0., z), vec3(x, 0., z + 1.), vec3(x + 1., 0., z + 1.), vec3(x + 1., 0., z)]);
///     }
/// }
/// let mut merged = Vec::new();
/// merger.merge(|polygon| merged.push(polygon.to_vec()));
/// assert_eq!(merged.len(), 1);
/// assert_eq!(merged[0].len(), 4);
/// ```
#[derive(Clone, Debug)]
pub struct CoplanarMerger {
    options: MergeOptions,
    vertices: Vec<Vec3>,
    /// Polygon `i` is `vertices[starts[i]..starts[i + 1]]`; one more entry than polygons.
    starts: Vec<usize>,
    normals: Vec<Vec3>,
    areas: Vec<f64>,
    bounds: Aabb,
}

/// Marks a directed edge used by more than one polygon: it joins nothing.
const AMBIGUOUS: u32 = u32::MAX;
/// No polygon across an edge.
const NONE: u32 = u32::MAX;
/// A polygon not yet given a region.
const UNASSIGNED: u32 = u32::MAX;

/// The plane a region grows in: through the first vertex of the region's first polygon,
/// holding polygons whose normals are within the angle tolerance (`min_cos`) of its normal.
#[derive(Clone, Copy)]
struct RegionPlane {
    origin: DVec3,
    min_cos: f64,
}

impl CoplanarMerger {
    /// An empty merger with these tolerances.
    pub fn new(options: MergeOptions) -> Self {
        CoplanarMerger {
            options,
            vertices: Vec::new(),
            starts: vec![0],
            normals: Vec::new(),
            areas: Vec::new(),
            bounds: Aabb::EMPTY,
        }
    }

    /// Adds a convex planar polygon. Returns false (and adds nothing) when it is degenerate:
    /// fewer than 3 vertices, zero area or non-finite, as [`crate::PolygonSet::push`] rejects.
    pub fn push(&mut self, polygon: &[Vec3]) -> bool {
        if polygon.len() < 3 || !polygon.iter().all(|p| p.is_finite()) {
            return false;
        }
        let vector_area = polygon_vector_area(polygon);
        let area = vector_area.length();
        let Some(normal) = vector_area.try_normalize() else {
            return false;
        };
        if !area.is_finite() || area <= 0.0 || self.normals.len() >= AMBIGUOUS as usize - 1 {
            return false;
        }
        self.vertices.extend_from_slice(polygon);
        self.starts.push(self.vertices.len());
        self.normals.push(normal);
        self.areas.push(f64::from(area));
        self.bounds = self.bounds.union(Aabb::from_points(polygon));
        true
    }

    /// Number of polygons pushed.
    pub fn len(&self) -> usize {
        self.normals.len()
    }

    /// True when no polygon was pushed.
    pub fn is_empty(&self) -> bool {
        self.normals.is_empty()
    }

    /// Bounds of the polygons pushed ([`Aabb::EMPTY`] for none).
    pub fn bounds(&self) -> Aabb {
        self.bounds
    }

    fn vector_area(&self, i: u32) -> DVec3 {
        self.normals[i as usize].as_dvec3() * self.areas[i as usize]
    }

    fn polygon(&self, i: u32) -> &[Vec3] {
        &self.vertices[self.starts[i as usize]..self.starts[i as usize + 1]]
    }

    /// The directed edges `(from, to)` of polygon `i`.
    fn edges(&self, i: u32) -> impl Iterator<Item = (Vec3, Vec3)> + '_ {
        let p = self.polygon(i);
        p.iter().zip(p.iter().cycle().skip(1)).map(|(&a, &b)| (a, b))
    }

    /// Calls `emit` once for every merged convex polygon. Together they cover exactly the
    /// pushed polygons (up to rounding); polygons with no coplanar neighbour come back as they
    /// were pushed, in the order of their regions' first polygons.
    pub fn merge(&self, mut emit: impl FnMut(&[Vec3])) {
        let n = self.len() as u32;
        let tol = self.plane_tolerance();
        let min_cos = f64::from(self.options.max_angle).cos();
        let across = self.edge_neighbours();
        let mut region = vec![UNASSIGNED; n as usize];
        let mut members = Vec::new();
        let mut simplified = Vec::new();
        for seed in 0..n {
            if region[seed as usize] != UNASSIGNED {
                continue;
            }
            let plane = RegionPlane {
                origin: self.polygon(seed)[0].as_dvec3(),
                min_cos,
            };
            let normal = self
                .grow_region(seed, plane, tol, &across, &mut region, &mut members)
                .normalize();
            // Each member was within the tolerance of the plane as it stood when it joined;
            // all must be within twice of the final one, or the region stays as it was.
            if members.len() == 1
                || !members
                    .iter()
                    .all(|&m| self.lies_in_plane(m, plane, normal, 2.0 * f64::from(tol)))
            {
                for &m in &members {
                    emit(self.polygon(m));
                }
                continue;
            }
            let normal = normal.as_vec3();
            let area: f64 = members.iter().map(|&m| self.areas[m as usize]).sum();
            if let Some(outline) = self.region_outline(seed, &members, &across, &region) {
                simplify_outline(&outline, tol, &mut simplified);
                if accepts(&simplified, normal, area) {
                    emit(&simplified);
                    continue;
                }
            }
            let shared = self.shared_edges(&members, &across);
            let polygons = members.iter().map(|&m| self.polygon(m).to_vec()).collect();
            let areas: Vec<f64> = members.iter().map(|&m| self.areas[m as usize]).collect();
            greedy::merge_region(polygons, &areas, &shared, normal, tol, &mut emit);
        }
    }

    /// The distance tolerance of the pushed polygons: relative to the input's size, and never
    /// below the rounding of its coordinates (zero when the input's size is not finite).
    fn plane_tolerance(&self) -> f32 {
        let magnitude = self.bounds.min.abs().max(self.bounds.max.abs()).max_element();
        let tol = self.options.relative_distance * self.bounds.diagonal() + 4.0 * f32::EPSILON * magnitude;
        if tol.is_finite() { tol } else { 0.0 }
    }

    /// The polygon across each directed edge (`across[starts[i] + k]` for edge k of polygon
    /// i), when exactly one polygon walks it the other way and no other polygon walks it this
    /// way; [`NONE`] otherwise.
    fn edge_neighbours(&self) -> Vec<u32> {
        let n = self.len() as u32;
        let mut owner: FastHashMap<(VertexKey, VertexKey), u32> = fast_map_with_capacity(self.vertices.len());
        for i in 0..n {
            for (a, b) in self.edges(i) {
                owner
                    .entry((VertexKey::of(a), VertexKey::of(b)))
                    .and_modify(|o| *o = AMBIGUOUS)
                    .or_insert(i);
            }
        }
        let mut across = vec![NONE; self.vertices.len()];
        for i in 0..n {
            let start = self.starts[i as usize];
            for (k, (a, b)) in self.edges(i).enumerate() {
                let (ka, kb) = (VertexKey::of(a), VertexKey::of(b));
                if owner.get(&(ka, kb)) == Some(&i)
                    && let Some(&q) = owner.get(&(kb, ka))
                    && q != AMBIGUOUS
                    && q != i
                {
                    across[start + k] = q;
                }
            }
        }
        across
    }

    /// The polygon across each edge of polygon `i` (or [`NONE`]), with the edge.
    fn neighbours<'a>(&'a self, across: &'a [u32], i: u32) -> impl Iterator<Item = (u32, (Vec3, Vec3))> + 'a {
        let (start, end) = (self.starts[i as usize], self.starts[i as usize + 1]);
        across[start..end].iter().copied().zip(self.edges(i))
    }

    /// True when polygon `q`'s normal is within the angle tolerance of `normal` and all its
    /// vertices within `tol` of the plane through `plane.origin` normal to `normal`.
    fn lies_in_plane(&self, q: u32, plane: RegionPlane, normal: DVec3, tol: f64) -> bool {
        self.normals[q as usize].as_dvec3().dot(normal) >= plane.min_cos
            && self
                .polygon(q)
                .iter()
                .all(|&v| (v.as_dvec3() - plane.origin).dot(normal).abs() <= tol)
    }

    /// Grows the region of `seed` breadth-first across shared edges into `members`, marking
    /// each member's `region` with `seed`, and returns the sum of the members' vector areas.
    ///
    /// A neighbour joins when it lies in the region's plane as it stands: normal to the sum so
    /// far, which sharpens as the region grows (one small polygon's normal is too rough to hold
    /// a whole wall within the tolerance).
    fn grow_region(
        &self,
        seed: u32,
        plane: RegionPlane,
        tol: f32,
        across: &[u32],
        region: &mut [u32],
        members: &mut Vec<u32>,
    ) -> DVec3 {
        let mut vector_area = self.vector_area(seed);
        region[seed as usize] = seed;
        members.clear();
        members.push(seed);
        let mut next = 0;
        while next < members.len() {
            let p = members[next];
            next += 1;
            for (q, _) in self.neighbours(across, p) {
                if q != NONE
                    && region[q as usize] == UNASSIGNED
                    && self.lies_in_plane(q, plane, vector_area.normalize(), f64::from(tol))
                {
                    region[q as usize] = seed;
                    members.push(q);
                    vector_area += self.vector_area(q);
                }
            }
        }
        vector_area
    }

    /// The outline of the region of `seed` (its `members`' edges with no neighbour in the
    /// region) as one loop, when it forms exactly one ([`Self::single_outline`]).
    fn region_outline(
        &self,
        seed: u32,
        members: &[u32],
        across: &[u32],
        region: &[u32],
    ) -> Option<Vec<Vec3>> {
        let in_region = |q: u32| q != NONE && region[q as usize] == seed;
        Self::single_outline(members, |p| {
            self.neighbours(across, p)
                .filter(move |&(q, _)| !in_region(q))
                .map(|(_, edge)| edge)
        })
    }

    /// The edges the region's `members` share with one another, once each, numbered by the
    /// members' positions in `members`.
    fn shared_edges(&self, members: &[u32], across: &[u32]) -> Vec<SharedEdge> {
        let local: HashMap<u32, u32> = members.iter().enumerate().map(|(l, &m)| (m, l as u32)).collect();
        let mut shared = Vec::new();
        for &p in members {
            for (q, (a, b)) in self.neighbours(across, p) {
                if q != NONE
                    && p < q
                    && let Some(&lq) = local.get(&q)
                {
                    shared.push(SharedEdge {
                        p: local[&p],
                        q: lq,
                        a,
                        b,
                    });
                }
            }
        }
        shared
    }

    /// The region's boundary (edges without a neighbour in it) chained into a loop, when it
    /// forms exactly one loop that touches itself nowhere.
    fn single_outline<I: Iterator<Item = (Vec3, Vec3)>>(
        members: &[u32],
        boundary_of: impl Fn(u32) -> I,
    ) -> Option<Vec<Vec3>> {
        let mut boundary: Vec<(Vec3, Vec3)> = Vec::new();
        for &p in members {
            boundary.extend(boundary_of(p));
        }
        let mut from: FastHashMap<VertexKey, usize> = fast_map_with_capacity(boundary.len());
        for (e, &(a, _)) in boundary.iter().enumerate() {
            if from.insert(VertexKey::of(a), e).is_some() {
                return None;
            }
        }
        let mut outline = Vec::with_capacity(boundary.len());
        let mut e = 0;
        loop {
            let (a, b) = *boundary.get(e)?;
            outline.push(a);
            e = *from.get(&VertexKey::of(b))?;
            if e == 0 || outline.len() > boundary.len() {
                break;
            }
        }
        (outline.len() == boundary.len()).then_some(outline)
    }
}

/// Merges `polygons` (convex, planar) with [`CoplanarMerger`] and returns the merged ones.
pub fn merge_coplanar_polygons<'a>(
    polygons: impl IntoIterator<Item = &'a [Vec3]>,
    options: MergeOptions,
) -> Vec<Vec<Vec3>> {
    let mut merger = CoplanarMerger::new(options);
    for p in polygons {
        merger.push(p);
    }
    let mut merged = Vec::new();
    merger.merge(|p| merged.push(p.to_vec()));
    merged
}
