//! The flood fill the crease-angle and contact partitions share: within each mesh, faces
//! join across the half-edges a rule allows; every analytic part stays alone.

use crate::part::PartId;
use crate::scene::{Scene, SceneMesh};
use pm_geom::{FaceId, HalfEdgeId, HalfEdgeMesh};
use rayon::prelude::*;

/// For each part of `scene`, the first part of its group (the seed the fill started from):
/// within each mesh, a face joins its neighbour across half-edge `he` when
/// `joins(mesh, he, face_part, neighbour_part)`; faces of different meshes never join here,
/// and every analytic part is a group of its own. Seeds are taken in part order, so groups
/// numbered in order of their roots are numbered in order of their first part. The meshes are
/// filled in parallel on the caller's rayon pool (each mesh's parts are its own), with the
/// same result on any number of threads.
pub(super) fn flood_fill(
    scene: &Scene,
    joins: impl Fn(&HalfEdgeMesh, HalfEdgeId, PartId, PartId) -> bool + Sync,
) -> Vec<u32> {
    let mut fill: Vec<u32> = (0..scene.part_count() as u32).collect(); // analytic parts
    let meshes: Vec<Vec<u32>> = scene.meshes().par_iter().map(|m| fill_mesh(m, &joins)).collect();
    for (m, seeds) in scene.meshes().iter().zip(meshes) {
        let first = m.part_of_face(FaceId(0)).0 as usize;
        fill[first..first + seeds.len()].copy_from_slice(&seeds);
    }
    fill
}

/// For each face of mesh `m`, in face order, the part of the seed its fill started from.
fn fill_mesh(m: &SceneMesh, joins: &impl Fn(&HalfEdgeMesh, HalfEdgeId, PartId, PartId) -> bool) -> Vec<u32> {
    const UNSET: u32 = u32::MAX;
    let mesh = m.half_edge_mesh();
    let mut fill = vec![UNSET; mesh.face_count()];
    let mut stack: Vec<FaceId> = Vec::new();
    for seed in mesh.faces() {
        if fill[seed.0 as usize] != UNSET {
            continue;
        }
        let seed_part = m.part_of_face(seed);
        fill[seed.0 as usize] = seed_part.0;
        stack.push(seed);
        while let Some(face) = stack.pop() {
            let part = m.part_of_face(face);
            for (he, other) in mesh.neighbours(face) {
                if fill[other.0 as usize] == UNSET && joins(mesh, he, part, m.part_of_face(other)) {
                    fill[other.0 as usize] = seed_part.0;
                    stack.push(other);
                }
            }
        }
    }
    fill
}
