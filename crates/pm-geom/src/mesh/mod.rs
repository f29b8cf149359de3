//! A half-edge mesh built from polygon index lists: welding, twins, boundary and non-manifold
//! edges, crease angles, and `validate()`.

use crate::MeshError;
use glam::Vec3;

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
    /// Vertices closer than this (absolute, metres) are welded into one.
    pub weld_tolerance: f32,
}

impl Default for MeshOptions {
    fn default() -> Self {
        MeshOptions { weld_tolerance: 1e-6 }
    }
}

/// A polygon mesh with half-edge connectivity.
#[derive(Clone, Debug)]
pub struct HalfEdgeMesh {
    positions: Vec<Vec3>,
}

impl HalfEdgeMesh {
    /// Builds the mesh from `positions` and convex planar `faces` given as index lists.
    pub fn build<F: AsRef<[u32]>>(positions: &[Vec3], faces: &[F], options: &MeshOptions) -> Result<Self, MeshError> {
        let _ = (positions, faces, options);
        todo!("pm-geom issue")
    }

    /// Welded vertex positions.
    pub fn positions(&self) -> &[Vec3] {
        &self.positions
    }

    /// Number of faces kept.
    pub fn face_count(&self) -> usize {
        todo!("pm-geom issue")
    }

    /// All face ids in order.
    pub fn faces(&self) -> impl ExactSizeIterator<Item = FaceId> + '_ {
        (0..self.face_count() as u32).map(FaceId)
    }

    /// Index of `face` in the `faces` list given to [`HalfEdgeMesh::build`].
    pub fn source_face(&self, face: FaceId) -> usize {
        let _ = face;
        todo!("pm-geom issue")
    }

    /// Number of input faces dropped for zero area.
    pub fn dropped_face_count(&self) -> usize {
        todo!("pm-geom issue")
    }

    /// The face's vertex positions in order.
    pub fn face_polygon(&self, face: FaceId) -> impl Iterator<Item = Vec3> + '_ {
        let _ = face;
        self.positions.iter().copied().take(todo!("pm-geom issue"))
    }

    /// The face's unit normal (Newell).
    pub fn face_normal(&self, face: FaceId) -> Vec3 {
        let _ = face;
        todo!("pm-geom issue")
    }

    /// The face's area.
    pub fn face_area(&self, face: FaceId) -> f32 {
        let _ = face;
        todo!("pm-geom issue")
    }

    /// The half-edges around `face`, in vertex order.
    pub fn face_half_edges(&self, face: FaceId) -> impl Iterator<Item = HalfEdgeId> + '_ {
        let _ = face;
        (0..todo!("pm-geom issue")).map(HalfEdgeId)
    }

    /// The face a half-edge belongs to.
    pub fn half_edge_face(&self, he: HalfEdgeId) -> FaceId {
        let _ = he;
        todo!("pm-geom issue")
    }

    /// The opposite half-edge, `None` on boundary and non-manifold edges.
    pub fn twin(&self, he: HalfEdgeId) -> Option<HalfEdgeId> {
        let _ = he;
        todo!("pm-geom issue")
    }

    /// True when the edge is used by more than two faces (it never gets a twin).
    pub fn is_non_manifold(&self, he: HalfEdgeId) -> bool {
        let _ = he;
        todo!("pm-geom issue")
    }

    /// Angle in radians between the normals of the two faces on a twinned edge (0 = flat),
    /// `None` without a twin.
    pub fn crease_angle(&self, he: HalfEdgeId) -> Option<f32> {
        let _ = he;
        todo!("pm-geom issue")
    }

    /// Faces across the twinned edges of `face`, with the half-edge on `face`'s side.
    pub fn neighbours(&self, face: FaceId) -> impl Iterator<Item = (HalfEdgeId, FaceId)> + '_ {
        self.face_half_edges(face)
            .filter_map(|he| self.twin(he).map(|t| (he, self.half_edge_face(t))))
    }

    /// Number of edges with one face.
    pub fn boundary_edge_count(&self) -> usize {
        todo!("pm-geom issue")
    }

    /// Number of edges with more than two faces.
    pub fn non_manifold_edge_count(&self) -> usize {
        todo!("pm-geom issue")
    }

    /// Checks every invariant.
    pub fn validate(&self) -> Result<(), MeshError> {
        todo!("pm-geom issue")
    }
}
