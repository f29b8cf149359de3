//! Rays in a scene rebuilt from pieces meet the faces as the user gave them. The contact
//! partition cuts faces into pieces so that photon maps can end where faces meet; searching
//! the pieces themselves would make rays depend on the cut (thin sliver pieces whose hit points
//! are less precise, coincident pieces, four times the triangles). Instead the rebuilt scene's
//! ray queries search the original triangles, and a hit on a face cut into pieces of several
//! parts is located among them ([`crate::bvh::pieces`]): the split decides maps, never what a
//! ray meets.

use super::Scene;
use crate::bvh::SceneBvh;
use crate::bvh::pieces::{Coverage, PieceIndex};
use crate::part::{PartId, PartSurface, SourceFace};
use glam::Vec3;
use std::sync::Arc;

impl Scene {
    /// Calls `visit` with each mesh face's polygon and the face's part and surface, mesh by
    /// mesh.
    fn for_each_mesh_polygon(&self, mut visit: impl FnMut(&[Vec3], PartSurface)) {
        let mut polygon = Vec::new();
        for mesh in &self.meshes {
            for face in mesh.mesh.faces() {
                let part = mesh.part_of_face(face);
                let surface = self.part_surface_ids[part.0 as usize];
                polygon.clear();
                polygon.extend(mesh.mesh.face_polygon(face));
                visit(&polygon, PartSurface { part, surface });
            }
        }
    }

    /// Calls `visit` with each mesh face's triangles (the fan of its polygon, as the ray
    /// queries take them) and the face's part and surface, mesh by mesh.
    fn for_each_mesh_triangle(&self, mut visit: impl FnMut([Vec3; 3], PartSurface)) {
        self.for_each_mesh_polygon(|polygon, part| {
            for i in 1..polygon.len().saturating_sub(1) {
                visit([polygon[0], polygon[i], polygon[i + 1]], part);
            }
        });
    }

    /// The mesh triangles `keep` gives an entry for, as it gives them, in a vector of exactly
    /// their number (counted first: these tables are large, and doubling growth would hold up
    /// to twice their size at the split's peak).
    fn collect_mesh_triangles<T>(&self, keep: impl Fn([Vec3; 3], PartSurface) -> Option<T>) -> Vec<T> {
        let mut count = 0;
        self.for_each_mesh_triangle(|v, part| count += usize::from(keep(v, part).is_some()));
        let mut out = Vec::with_capacity(count);
        self.for_each_mesh_triangle(|v, part| out.extend(keep(v, part)));
        out
    }

    /// Makes this scene's ray queries search `original` (the triangles of the scene it was
    /// rebuilt from, each with the face it belongs to) instead of its own pieces. This scene's
    /// part `p` is a piece of face `sources[p]`. A triangle whose face lies in one part keeps
    /// that part; one whose face was cut into pieces of several parts locates each hit among
    /// them (within `tolerance`, metres); one whose face has no piece left (a hidden copy of a
    /// coincident face, dropped) is not met. Built with
    /// [`SceneBuilder::defer_ray_triangles`](super::builder::SceneBuilder::defer_ray_triangles),
    /// so the pieces are never searched themselves. `loaded` is the ray search of the scene
    /// `original` came from: when it is a hierarchy over those triangles, it is taken over
    /// with the new parts ([`SceneBvh::with_parts_of`]) rather than built again.
    pub(crate) fn trace_faces_as_given(
        &mut self,
        original: &[([Vec3; 3], SourceFace)],
        sources: &[Option<SourceFace>],
        tolerance: f32,
        loaded: Arc<SceneBvh>,
    ) {
        let pieces = SourcePolygons::collect(self, sources);
        // A point rounded off a piece by the scene's own rounding still lies on it, where that
        // is coarser than the partition's tolerance (far from the origin).
        let mut index = PieceIndex::new(tolerance.max(4.0 * self.epsilon()));
        let mut parts = Vec::with_capacity(original.len());
        // Original triangles of one face come together: each run is one face, whose record
        // part is made once.
        let mut start = 0;
        while start < original.len() {
            let face = original[start].1;
            let end = start + original[start..].iter().take_while(|&&(_, f)| f == face).count();
            let run = &original[start..end];
            let from = pieces.outlines.partition_point(|o| o.face < face);
            let to = pieces.outlines.partition_point(|o| o.face <= face);
            let part = face_part(run, &pieces, from..to, &mut index);
            parts.extend(std::iter::repeat_n(part, run.len()));
            start = end;
        }
        index.shrink_to_fit();
        // The pieces' outlines are in the index now: not held while the search is made.
        drop(pieces);
        let bvh = match self.bvh.with_parts_of(loaded, |i| original[i].0, &parts, index) {
            Ok(bvh) => bvh,
            Err(index) => {
                let kept = |i: &usize| parts[*i].is_some();
                let triangles = (0..original.len()).filter(kept).map(|i| original[i].0).collect();
                let parts = parts.iter().flatten().copied().collect();
                self.bvh.with_triangles(triangles, parts, index)
            }
        };
        self.bvh = Arc::new(bvh);
    }

    /// Each mesh triangle of this scene with the face the user gave it belongs to
    /// ([`Scene::source_face`]).
    pub(crate) fn mesh_triangle_sources(&self) -> Vec<([Vec3; 3], SourceFace)> {
        self.collect_mesh_triangles(|v, part| Some((v, self.source_face(PartId(part.part.0))?)))
    }
}

/// One mesh face of a rebuilt scene: the face as given it is a piece of, its outline's range
/// in [`SourcePolygons::vertices`], and its part.
#[derive(Clone, Copy, Debug)]
struct PieceOutline {
    face: SourceFace,
    start: usize,
    end: usize,
    part: PartSurface,
}

/// A rebuilt scene's mesh faces (the pieces), grouped by the face as given they are pieces of
/// (stable: in mesh order within one), their outlines in one vertex table.
struct SourcePolygons {
    vertices: Vec<Vec3>,
    outlines: Vec<PieceOutline>,
}

impl SourcePolygons {
    /// The pieces of `scene` whose part `p` has a face as given `sources[p]`, in tables of
    /// exactly their size (counted first: they are large, and doubling growth would hold up to
    /// twice their size at the split's peak).
    fn collect(scene: &Scene, sources: &[Option<SourceFace>]) -> Self {
        let source = |part: PartSurface| sources.get(part.part.0 as usize).copied().flatten();
        let (mut vertex_count, mut outline_count) = (0, 0);
        scene.for_each_mesh_polygon(|polygon, part| {
            if polygon.len() >= 3 && source(part).is_some() {
                vertex_count += polygon.len();
                outline_count += 1;
            }
        });
        let mut vertices = Vec::with_capacity(vertex_count);
        let mut outlines = Vec::with_capacity(outline_count);
        scene.for_each_mesh_polygon(|polygon, part| {
            let Some(face) = source(part).filter(|_| polygon.len() >= 3) else {
                return;
            };
            let start = vertices.len();
            vertices.extend_from_slice(polygon);
            outlines.push(PieceOutline {
                face,
                start,
                end: vertices.len(),
                part,
            });
        });
        outlines.sort_by_key(|o| o.face);
        SourcePolygons { vertices, outlines }
    }

    /// The outline of `piece`.
    fn outline(&self, piece: &PieceOutline) -> &[Vec3] {
        &self.vertices[piece.start..piece.end]
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
    pieces: &SourcePolygons,
    range: std::ops::Range<usize>,
    index: &mut PieceIndex,
) -> Option<PartSurface> {
    let outlines = &pieces.outlines[range];
    let first = outlines.first()?.part;
    let area = |v: &[Vec3; 3]| f64::from((v[1] - v[0]).cross(v[2] - v[0]).length()) * 0.5;
    let face_area: f64 = run.iter().map(|(v, _)| area(v)).sum();
    // Over the outlines' fan triangles in order, as the rays take them.
    let piece_area: f64 = outlines
        .iter()
        .flat_map(|o| {
            let v = pieces.outline(o);
            (1..v.len() - 1).map(move |i| [v[0], v[i], v[i + 1]])
        })
        .map(|v| area(&v))
        .sum();
    let one_part = outlines.iter().all(|o| o.part.part == first.part);
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
        .push(
            normal,
            coverage,
            outlines.iter().map(|o| (pieces.outline(o), o.part)),
        )
        .map(|list| PartSurface {
            part: list,
            surface: first.surface,
        })
}
