//! `HalfEdgeMesh::validate`: every structural invariant, checked from scratch, so tests can
//! call it after each build and later mesh edits cannot silently break connectivity.

use super::build::face_normal_and_area;
use super::{FaceId, HalfEdgeId, HalfEdgeMesh};
use crate::error::MeshError;
use crate::fast_hash::FastHashMap;
use glam::Vec3;

impl HalfEdgeMesh {
    /// Checks every invariant: table sizes agree; each face has ≥ 3 half-edges whose face is
    /// it, valid distinct vertices, a unit normal and positive area matching its polygon;
    /// `source_face` is non-decreasing (a face pinched by welding keeps several faces) below
    /// the input face count; twins are mutual,
    /// run the opposite way on another half-edge, and exist exactly on edges with two
    /// opposite half-edges; non-manifold flags and the edge counts match a recount.
    pub fn validate(&self) -> Result<(), MeshError> {
        let fail = |msg: String| Err(MeshError::Invalid(msg));
        let faces = self.source_faces.len();
        let hes = self.he_origin.len();
        if self.face_starts.len() != faces + 1
            || self.he_twin.len() != hes
            || self.face_starts.first() != Some(&0)
            || self.face_starts.last().map(|&s| s as usize) != Some(hes)
        {
            return fail("table sizes disagree".into());
        }
        // A pinched face is kept as several faces with one source.
        let sources = self.source_faces.chunk_by(|a, b| a == b).count();
        if sources + self.dropped_faces != self.input_face_count {
            return fail(format!(
                "{sources} kept + {} dropped != {} input faces",
                self.dropped_faces, self.input_face_count
            ));
        }
        if self.source_faces.windows(2).any(|w| w[0] > w[1])
            || self
                .source_faces
                .last()
                .is_some_and(|&s| s as usize >= self.input_face_count)
        {
            return fail("source faces not increasing within the input".into());
        }
        let mut polygon = Vec::new();
        for face in self.faces() {
            self.validate_face(face, &mut polygon)?;
        }
        self.validate_edges()
    }

    fn validate_face(&self, face: FaceId, polygon: &mut Vec<Vec3>) -> Result<(), MeshError> {
        let f = face.0 as usize;
        let (start, end) = (self.face_starts[f] as usize, self.face_starts[f + 1] as usize);
        if start > end || end - start < 3 {
            return Err(MeshError::Invalid(format!("face {f}: fewer than 3 half-edges")));
        }
        for he in start..end {
            let v = self.he_origin[he] as usize;
            if self.half_edge_face(HalfEdgeId(he as u32)).0 as usize != f || v >= self.positions.len() {
                return Err(MeshError::Invalid(format!(
                    "half-edge {he}: wrong face or vertex"
                )));
            }
            if self.he_origin[start..he].contains(&(v as u32)) {
                return Err(MeshError::Invalid(format!("face {f}: vertex {v} repeated")));
            }
        }
        polygon.clear();
        polygon.extend(self.face_polygon(face));
        let Some((normal, area)) = face_normal_and_area(polygon) else {
            return Err(MeshError::Invalid(format!("face {f}: degenerate")));
        };
        if self.face_normal(face) != normal || self.face_area(face) != area {
            return Err(MeshError::Invalid(format!(
                "face {f}: normal or area differs from its polygon's"
            )));
        }
        Ok(())
    }

    fn validate_edges(&self) -> Result<(), MeshError> {
        let mut uses: FastHashMap<(u32, u32), Vec<u32>> = FastHashMap::default();
        for he in 0..self.he_origin.len() as u32 {
            let (a, b) = self.endpoints(he);
            uses.entry((a.min(b), a.max(b))).or_default().push(he);
        }
        let (mut boundary, mut non_manifold) = (0, 0);
        for list in uses.values() {
            let opposite =
                list.len() == 2 && self.he_origin[list[0] as usize] != self.he_origin[list[1] as usize];
            match list.len() {
                1 => boundary += 1,
                2 if opposite => {}
                _ => non_manifold += 1,
            }
            for &he in list {
                let twin = self.he_twin[he as usize];
                let expected = if opposite {
                    list.iter().copied().find(|&o| o != he)
                } else {
                    None
                };
                if self.twin(HalfEdgeId(he)).map(|t| t.0) != expected {
                    return Err(MeshError::Invalid(format!(
                        "half-edge {he}: twin {twin} expected {expected:?}"
                    )));
                }
                if self.is_non_manifold(HalfEdgeId(he)) != (list.len() >= 2 && !opposite) {
                    return Err(MeshError::Invalid(format!(
                        "half-edge {he}: wrong non-manifold flag"
                    )));
                }
            }
        }
        if boundary != self.boundary_edges || non_manifold != self.non_manifold_edges {
            return Err(MeshError::Invalid(format!(
                "edge counts: boundary {} (recount {boundary}), non-manifold {} (recount {non_manifold})",
                self.boundary_edges, self.non_manifold_edges
            )));
        }
        Ok(())
    }
}
