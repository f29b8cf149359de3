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
    /// Calls `visit` with each mesh face's triangles (the fan of its polygon, as the ray
    /// queries take them) and the face's part and surface, mesh by mesh.
    fn for_each_mesh_triangle(&self, mut visit: impl FnMut([Vec3; 3], PartSurface)) {
        let mut polygon = Vec::new();
        for mesh in &self.meshes {
            for face in mesh.mesh.faces() {
                let part = mesh.part_of_face(face);
                let surface = self.part_surface_ids[part.0 as usize];
                polygon.clear();
                polygon.extend(mesh.mesh.face_polygon(face));
                for i in 1..polygon.len().saturating_sub(1) {
                    visit(
                        [polygon[0], polygon[i], polygon[i + 1]],
                        PartSurface { part, surface },
                    );
                }
            }
        }
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
        let mut pieces: Vec<(SourceFace, [Vec3; 3], PartSurface)> = self.collect_mesh_triangles(|v, part| {
            Some((sources.get(part.part.0 as usize).copied().flatten()?, v, part))
        });
        // Sorted through their indices (a stable sort of the triangles themselves would hold
        // half as many again in its buffer).
        let mut order: Vec<u32> = (0..pieces.len() as u32).collect();
        order.sort_by_key(|&i| pieces[i as usize].0);
        gather_in_place(&mut pieces, order);
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
        index.shrink_to_fit();
        self.bvh = Arc::new(self.bvh.with_triangles(triangles, parts, index));
    }

    /// Each mesh triangle of this scene with the face the user gave it belongs to
    /// ([`Scene::source_face`]).
    pub(crate) fn mesh_triangle_sources(&self) -> Vec<([Vec3; 3], SourceFace)> {
        self.collect_mesh_triangles(|v, part| Some((v, self.source_face(PartId(part.part.0))?)))
    }
}

/// Reorders `items` so that item `i` becomes the one at `order[i]` (`order` a permutation of
/// the indices), following the permutation's cycles without a second copy of the items.
fn gather_in_place<T>(items: &mut [T], mut order: Vec<u32>) {
    debug_assert_eq!(items.len(), order.len());
    const DONE: u32 = u32::MAX;
    for start in 0..items.len() {
        let mut i = start;
        // Each step moves one item into its place, so a cycle ends within `items.len()` steps.
        while order[i] != DONE {
            let j = order[i] as usize;
            order[i] = DONE;
            if j == start {
                break;
            }
            items.swap(i, j);
            i = j;
        }
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

#[cfg(test)]
mod tests {
    use super::gather_in_place;
    use proptest::prelude::*;

    proptest! {
        /// Against the copy it replaces: item `i` becomes the one at `order[i]`.
        #[test]
        fn gather_in_place_matches_a_gathering_copy(keys in proptest::collection::vec(0u32..1000, 0..200)) {
            let items: Vec<(u32, usize)> = keys.iter().copied().zip(0..).collect();
            let mut order: Vec<u32> = (0..items.len() as u32).collect();
            order.sort_by_key(|&i| items[i as usize].0);
            let copied: Vec<(u32, usize)> = order.iter().map(|&i| items[i as usize]).collect();
            let mut in_place = items.clone();
            gather_in_place(&mut in_place, order);
            prop_assert_eq!(in_place, copied);
        }
    }
}
