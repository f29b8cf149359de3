//! Rays in a scene rebuilt from pieces meet the faces as the user gave them. The contact
//! partition cuts faces into pieces so that photon maps can end where faces meet; searching
//! the pieces themselves would make rays depend on the cut (thin sliver pieces whose hit points
//! are less precise, coincident pieces, four times the triangles). Instead the rebuilt scene's
//! ray queries search the original triangles, and a hit on a face cut into pieces of several
//! parts is located among them ([`crate::bvh::pieces`]): the split decides maps, never what a
//! ray meets.

use super::Scene;
use crate::bvh::pieces::{Coverage, PieceIndex};
use crate::part::{PartId, PartSurface, SourceFace};
use glam::Vec3;
use std::sync::Arc;

impl Scene {
    /// Each mesh face's triangles (the fan of its polygon, as the ray queries take them) with
    /// the face's part and surface, mesh by mesh.
    pub(crate) fn mesh_triangles(&self) -> Vec<([Vec3; 3], PartSurface)> {
        let mut out = Vec::new();
        let mut polygon = Vec::new();
        for mesh in &self.meshes {
            for face in mesh.mesh.faces() {
                let part = mesh.part_of_face(face);
                let surface = self.part_surface_ids[part.0 as usize];
                polygon.clear();
                polygon.extend(mesh.mesh.face_polygon(face));
                for i in 1..polygon.len().saturating_sub(1) {
                    out.push((
                        [polygon[0], polygon[i], polygon[i + 1]],
                        PartSurface { part, surface },
                    ));
                }
            }
        }
        out
    }

    /// Makes this scene's ray queries search `original` (the triangles of the scene it was
    /// rebuilt from, each with the face it belongs to) instead of its own pieces. This scene's
    /// part `p` is a piece of face `sources[p]`. A triangle whose face lies in one part keeps
    /// that part; one whose face was cut into pieces of several parts locates each hit among
    /// them (within `tolerance`, metres); one whose face has no piece left (a hidden copy of a
    /// coincident face, dropped) is not searched. Built with
    /// [`SceneBuilder::defer_ray_triangles`](super::builder::SceneBuilder::defer_ray_triangles),
    /// so the pieces are never searched themselves.
    pub(crate) fn trace_faces_as_given(
        &mut self,
        original: &[([Vec3; 3], SourceFace)],
        sources: &[Option<SourceFace>],
        tolerance: f32,
    ) {
        // The pieces' triangles, grouped by their face (stable: in part order within one).
        let mut pieces: Vec<(SourceFace, [Vec3; 3], PartSurface)> = self
            .mesh_triangles()
            .into_iter()
            .filter_map(|(v, part)| Some((sources.get(part.part.0 as usize).copied().flatten()?, v, part)))
            .collect();
        pieces.sort_by_key(|&(face, _, _)| face);
        // A point rounded off a piece by the scene's own rounding still lies on it, where that
        // is coarser than the partition's tolerance (far from the origin).
        let mut index = PieceIndex::new(tolerance.max(4.0 * self.epsilon()));
        let mut triangles = Vec::with_capacity(original.len());
        let mut parts = Vec::with_capacity(original.len());
        // Original triangles of one face come together: each run is one face, whose record
        // part is made once.
        let mut start = 0;
        while start < original.len() {
            let face = original[start].1;
            let end = start + original[start..].iter().take_while(|&&(_, f)| f == face).count();
            let run = &original[start..end];
            let from = pieces.partition_point(|&(f, _, _)| f < face);
            let to = pieces.partition_point(|&(f, _, _)| f <= face);
            if let Some(part) = face_part(run, &pieces[from..to], &mut index) {
                triangles.extend(run.iter().map(|&(v, _)| v));
                parts.extend(std::iter::repeat_n(part, run.len()));
            }
            start = end;
        }
        self.bvh = Arc::new(self.bvh.with_triangles(triangles, parts, index));
    }

    /// Each mesh triangle of this scene with the face the user gave it belongs to
    /// ([`Scene::source_face`]).
    pub(crate) fn mesh_triangle_sources(&self) -> Vec<([Vec3; 3], SourceFace)> {
        self.mesh_triangles()
            .into_iter()
            .filter_map(|(v, part)| Some((v, self.source_face(PartId(part.part.0))?)))
            .collect()
    }
}

/// Pieces cover their face when their area is within this fraction of the face's (the
/// split's welding moves corners by a millionth of the scene; a hidden copy's dropped part
/// is far more).
const COVERED: f64 = 1e-4;

/// The record part of a face's triangles `run` with its `pieces`: the one part when one piece
/// part covers the whole face, a piece list when several parts share it or part of it was
/// dropped (a ray passes there), `None` when nothing of it is left.
fn face_part(
    run: &[([Vec3; 3], SourceFace)],
    pieces: &[(SourceFace, [Vec3; 3], PartSurface)],
    index: &mut PieceIndex,
) -> Option<PartSurface> {
    let &(_, _, first) = pieces.first()?;
    let area = |v: &[Vec3; 3]| f64::from((v[1] - v[0]).cross(v[2] - v[0]).length()) * 0.5;
    let face_area: f64 = run.iter().map(|(v, _)| area(v)).sum();
    let piece_area: f64 = pieces.iter().map(|(_, v, _)| area(v)).sum();
    let one_part = pieces.iter().all(|&(_, _, p)| p.part == first.part);
    let coverage = if piece_area >= face_area * (1.0 - COVERED) {
        Coverage::Whole
    } else {
        Coverage::Dropped
    };
    if one_part && coverage == Coverage::Whole {
        return Some(first);
    }
    // The face's normal from its largest triangle (its pieces lie in its plane).
    let normal = run
        .iter()
        .map(|(v, _)| (v[1] - v[0]).cross(v[2] - v[0]))
        .fold(Vec3::ZERO, |best, n| {
            if n.length_squared() > best.length_squared() {
                n
            } else {
                best
            }
        })
        .try_normalize()?;
    index
        .push(normal, coverage, pieces.iter().map(|&(_, v, p)| (v, p)))
        .map(|list| PartSurface {
            part: list,
            surface: first.surface,
        })
}
