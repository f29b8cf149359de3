//! The flood fill the crease-angle and contact partitions share: within each mesh, faces
//! join across the half-edges a rule allows; every analytic part stays alone.

use crate::part::PartId;
use crate::scene::Scene;
use pm_geom::{FaceId, HalfEdgeId, HalfEdgeMesh};

/// For each part of `scene`, the first part of its group (the seed the fill started from):
/// within each mesh, a face joins its neighbour across half-edge `he` when
/// `joins(mesh, he, face_part, neighbour_part)`; faces of different meshes never join here,
/// and every analytic part is a group of its own. Seeds are taken in part order, so groups
/// numbered in order of their roots are numbered in order of their first part.
pub(super) fn flood_fill(
    scene: &Scene,
    mut joins: impl FnMut(&HalfEdgeMesh, HalfEdgeId, PartId, PartId) -> bool,
) -> Vec<u32> {
    const UNSET: u32 = u32::MAX;
    let mut fill = vec![UNSET; scene.part_count()];
    let mut stack: Vec<FaceId> = Vec::new();
    for m in scene.meshes() {
        let mesh = m.half_edge_mesh();
        for seed in mesh.faces() {
            let seed_part = m.part_of_face(seed);
            if fill[seed_part.0 as usize] != UNSET {
                continue;
            }
            fill[seed_part.0 as usize] = seed_part.0;
            stack.push(seed);
            while let Some(face) = stack.pop() {
                let part = m.part_of_face(face);
                for (he, other) in mesh.neighbours(face) {
                    let other_part = m.part_of_face(other);
                    if fill[other_part.0 as usize] == UNSET && joins(mesh, he, part, other_part) {
                        fill[other_part.0 as usize] = seed_part.0;
                        stack.push(other);
                    }
                }
            }
        }
    }
    for (p, slot) in fill.iter_mut().enumerate() {
        if *slot == UNSET {
            *slot = p as u32; // analytic parts
        }
    }
    fill
}
