//! A half-edge mesh built from polygon index lists: welding, twins, boundary and non-manifold
//! edges, crease angles, and `validate()`.
//!
//! Half-edges of a face are stored contiguously in vertex order, so `next` and `prev` are
//! index arithmetic and a face is a range. Each half-edge runs from its origin vertex to the
//! origin of the next half-edge of its face.

mod build;
mod validate;
mod weld;

use glam::Vec3;

/// "No twin" in the twin table.
const NO_TWIN: u32 = u32::MAX;
/// `he_twin` of a half-edge on a non-manifold edge.
const NON_MANIFOLD: u32 = u32::MAX - 1;

/// Index of a vertex (after welding).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub struct VertexId(pub u32);
/// Index of a face (after zero-area faces are dropped).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub struct FaceId(pub u32);
/// Index of a half-edge.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub struct HalfEdgeId(pub u32);

/// Build options.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct MeshOptions {
    /// Vertices within this distance (metres) are welded into one: each position joins the
    /// first earlier vertex within reach (a greedy clustering through a hash grid, so a chain
    /// of points each just within reach of the next is not merged end to end). Capped at
    /// [`MeshOptions::MAX_RELATIVE_WELD`] of the mesh's bounding-box diagonal, so that a mesh
    /// a micrometre across is not welded into a point. Zero, negative or NaN welds only
    /// identical positions.
    pub weld_tolerance: f32,
}

impl MeshOptions {
    /// The largest weld distance as a share of a mesh's bounding-box diagonal (10⁻⁶: the
    /// default 1 µm for a mesh 1 m across, 1 pm for one 1 µm across).
    pub const MAX_RELATIVE_WELD: f32 = 1e-6;

    /// The weld distance for a mesh of `positions`: [`MeshOptions::weld_tolerance`], capped at
    /// [`MeshOptions::MAX_RELATIVE_WELD`] of their bounding-box diagonal.
    pub fn tolerance_for(&self, positions: &[Vec3]) -> f32 {
        let (lo, hi) = positions
            .iter()
            .fold((Vec3::INFINITY, Vec3::NEG_INFINITY), |(lo, hi), p| {
                (lo.min(*p), hi.max(*p))
            });
        let diagonal = (hi - lo).length();
        if diagonal.is_finite() {
            self.weld_tolerance.min(Self::MAX_RELATIVE_WELD * diagonal)
        } else {
            self.weld_tolerance
        }
    }
}

impl Default for MeshOptions {
    fn default() -> Self {
        MeshOptions { weld_tolerance: 1e-6 }
    }
}

/// A polygon mesh with half-edge connectivity.
///
/// Ids are only meaningful for the mesh that issued them; passing an id out of range panics
/// like slice indexing (ids never come from user data).
///
/// ```
/// use pm_geom::{HalfEdgeMesh, MeshOptions, glam::vec3};
/// // Two triangles folded 90° along their shared edge (0,0,0)–(1,0,0).
/// let positions = [vec3(0., 0., 0.), vec3(1., 0., 0.), vec3(0., 0., -1.), vec3(0., 1., 0.)];
/// let mesh = HalfEdgeMesh::build(&positions, &[[0u32, 1, 2], [1, 0, 3]], &MeshOptions::default())?;
/// mesh.validate()?;
/// let shared = mesh.face_half_edges(mesh.faces().next().unwrap()).next().unwrap();
/// let angle = mesh.crease_angle(shared).unwrap();
/// assert!((angle - std::f32::consts::FRAC_PI_2).abs() < 1e-6);
/// assert_eq!(mesh.boundary_edge_count(), 4);
/// # Ok::<(), pm_geom::MeshError>(())
/// ```
#[derive(Clone, Debug)]
pub struct HalfEdgeMesh {
    positions: Vec<Vec3>,
    /// Half-edges of face `f` are `face_starts[f]..face_starts[f + 1]`.
    face_starts: Vec<u32>,
    he_origin: Vec<u32>,
    /// The twin of each half-edge, or [`NO_TWIN`] / [`NON_MANIFOLD`].
    he_twin: Vec<u32>,
    /// Index in the input of each kept face. Normals and areas are not stored: they are
    /// recomputed from the vertices (bit-identical to the values checked at build), which
    /// keeps a triangle mesh near 50 bytes per triangle.
    source_faces: Vec<u32>,
    input_face_count: usize,
    dropped_faces: usize,
    boundary_edges: usize,
    non_manifold_edges: usize,
}

impl HalfEdgeMesh {
    /// Welded vertex positions.
    pub fn positions(&self) -> &[Vec3] {
        &self.positions
    }

    /// Bytes this mesh holds on the heap (its tables' capacity).
    pub fn heap_bytes(&self) -> usize {
        self.positions.capacity() * size_of::<Vec3>()
            + (self.face_starts.capacity()
                + self.he_origin.capacity()
                + self.he_twin.capacity()
                + self.source_faces.capacity())
                * size_of::<u32>()
    }

    /// Number of welded vertices.
    pub fn vertex_count(&self) -> usize {
        self.positions.len()
    }

    /// Number of faces kept.
    pub fn face_count(&self) -> usize {
        self.face_starts.len() - 1
    }

    /// Number of half-edges.
    pub fn half_edge_count(&self) -> usize {
        self.he_origin.len()
    }

    /// All face ids in order.
    pub fn faces(&self) -> impl ExactSizeIterator<Item = FaceId> + '_ {
        (0..self.face_count() as u32).map(FaceId)
    }

    /// Index of `face` in the `faces` list given to [`HalfEdgeMesh::build`].
    pub fn source_face(&self, face: FaceId) -> usize {
        self.source_faces[face.0 as usize] as usize
    }

    /// Number of input faces dropped as degenerate: fewer than 3 distinct vertices or zero
    /// area after welding (a face pinched by welding keeps its loops that have area).
    pub fn dropped_face_count(&self) -> usize {
        self.dropped_faces
    }

    /// The face's vertex positions in order.
    pub fn face_polygon(&self, face: FaceId) -> impl Iterator<Item = Vec3> + '_ {
        self.face_vertices(face).map(|v| self.positions[v.0 as usize])
    }

    /// The face's vertices in order.
    pub fn face_vertices(&self, face: FaceId) -> impl ExactSizeIterator<Item = VertexId> + '_ {
        self.he_origin[self.face_range(face)].iter().map(|&v| VertexId(v))
    }

    /// The face's unit normal (Newell).
    pub fn face_normal(&self, face: FaceId) -> Vec3 {
        self.face_vector_area(face).normalize()
    }

    /// The face's area.
    pub fn face_area(&self, face: FaceId) -> f32 {
        self.face_vector_area(face).length()
    }

    /// The face's vector area, by the same operations as [`crate::polygon_vector_area`] on
    /// its polygon (so bit-identical to it), without collecting the polygon.
    fn face_vector_area(&self, face: FaceId) -> Vec3 {
        let mut vertices = self.face_polygon(face);
        let (Some(first), Some(second)) = (vertices.next(), vertices.next()) else {
            return Vec3::ZERO;
        };
        let mut sum = Vec3::ZERO;
        let mut prev = second - first;
        for v in vertices {
            let cur = v - first;
            sum += prev.cross(cur);
            prev = cur;
        }
        sum * 0.5
    }

    /// The half-edges around `face`, in vertex order.
    pub fn face_half_edges(&self, face: FaceId) -> impl Iterator<Item = HalfEdgeId> + '_ {
        let range = self.face_range(face);
        (range.start as u32..range.end as u32).map(HalfEdgeId)
    }

    /// The face a half-edge belongs to.
    pub fn half_edge_face(&self, he: HalfEdgeId) -> FaceId {
        self.face_of_half_edge(he.0)
    }

    /// The vertex a half-edge starts at.
    pub fn origin(&self, he: HalfEdgeId) -> VertexId {
        VertexId(self.he_origin[he.0 as usize])
    }

    /// The vertex a half-edge ends at (the origin of [`HalfEdgeMesh::next`]).
    pub fn target(&self, he: HalfEdgeId) -> VertexId {
        VertexId(self.he_origin[self.next_index(he.0) as usize])
    }

    /// The next half-edge around the same face.
    pub fn next(&self, he: HalfEdgeId) -> HalfEdgeId {
        HalfEdgeId(self.next_index(he.0))
    }

    /// The previous half-edge around the same face.
    pub fn prev(&self, he: HalfEdgeId) -> HalfEdgeId {
        let range = self.face_range(self.half_edge_face(he));
        let i = he.0 as usize;
        HalfEdgeId(if i == range.start { range.end - 1 } else { i - 1 } as u32)
    }

    /// The opposite half-edge, `None` on boundary and non-manifold edges.
    pub fn twin(&self, he: HalfEdgeId) -> Option<HalfEdgeId> {
        let t = self.he_twin[he.0 as usize];
        (t < NON_MANIFOLD).then_some(HalfEdgeId(t))
    }

    /// True when the edge is non-manifold: used by more than two half-edges, or by two that
    /// run the same direction (inconsistent winding). Such edges never get a twin, so they
    /// never join photon maps.
    pub fn is_non_manifold(&self, he: HalfEdgeId) -> bool {
        self.he_twin[he.0 as usize] == NON_MANIFOLD
    }

    /// Angle in radians between the normals of the two faces on a twinned edge (0 = flat
    /// continuation, π/2 on a cube edge), `None` without a twin.
    pub fn crease_angle(&self, he: HalfEdgeId) -> Option<f32> {
        let twin = self.twin(he)?;
        let a = self.face_normal(self.half_edge_face(he));
        let b = self.face_normal(self.half_edge_face(twin));
        Some(a.cross(b).length().atan2(a.dot(b)))
    }

    /// Faces across the twinned edges of `face`, with the half-edge on `face`'s side.
    pub fn neighbours(&self, face: FaceId) -> impl Iterator<Item = (HalfEdgeId, FaceId)> + '_ {
        self.face_half_edges(face)
            .filter_map(|he| self.twin(he).map(|t| (he, self.half_edge_face(t))))
    }

    /// Number of edges with one face.
    pub fn boundary_edge_count(&self) -> usize {
        self.boundary_edges
    }

    /// Number of non-manifold edges (see [`HalfEdgeMesh::is_non_manifold`]).
    pub fn non_manifold_edge_count(&self) -> usize {
        self.non_manifold_edges
    }

    /// The face whose half-edge range holds `he`: a binary search of the face starts (not
    /// stored per half-edge, to keep the mesh small).
    #[inline]
    fn face_of_half_edge(&self, he: u32) -> FaceId {
        FaceId(self.face_starts.partition_point(|&s| s <= he) as u32 - 1)
    }

    fn face_range(&self, face: FaceId) -> std::ops::Range<usize> {
        let f = face.0 as usize;
        self.face_starts[f] as usize..self.face_starts[f + 1] as usize
    }

    fn next_index(&self, he: u32) -> u32 {
        let range = self.face_range(self.face_of_half_edge(he));
        if he as usize + 1 == range.end {
            range.start as u32
        } else {
            he + 1
        }
    }
}
