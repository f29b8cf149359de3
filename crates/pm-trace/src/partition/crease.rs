//! Crease-angle partition (Larsen & Christensen 2003): mesh faces join a map across twinned
//! edges whose crease angle is below a threshold; every analytic part is its own map.

use super::{MapAssignment, Partitioner};
use crate::part::{PartId, PartSource};
use crate::scene::Scene;
use pm_geom::FaceId;

/// Flood fill over half-edge twins with crease angle `< max_angle` (radians). Boundary and
/// non-manifold edges (no twin) never join; faces of different meshes never share a map; a
/// sphere is one map and each of a ring's four sides is one map.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct CreaseAngle {
    /// Largest dihedral angle (between face normals, 0 = flat) that still joins, radians.
    pub max_angle: f32,
}

impl Default for CreaseAngle {
    /// 30°.
    fn default() -> Self {
        CreaseAngle {
            max_angle: 30f32.to_radians(),
        }
    }
}

impl Partitioner for CreaseAngle {
    fn partition(&self, scene: &Scene) -> MapAssignment {
        const UNSET: u32 = u32::MAX;
        let mut map_of_part = vec![UNSET; scene.part_count()];
        let mut next = 0u32;
        let mut stack: Vec<FaceId> = Vec::new();
        for m in scene.meshes() {
            let mesh = m.half_edge_mesh();
            for seed in mesh.faces() {
                if map_of_part[m.part_of_face(seed).0 as usize] != UNSET {
                    continue;
                }
                map_of_part[m.part_of_face(seed).0 as usize] = next;
                stack.push(seed);
                while let Some(face) = stack.pop() {
                    for (he, other) in mesh.neighbours(face) {
                        let slot = &mut map_of_part[m.part_of_face(other).0 as usize];
                        if *slot == UNSET && mesh.crease_angle(he).is_some_and(|a| a < self.max_angle) {
                            *slot = next;
                            stack.push(other);
                        }
                    }
                }
                next += 1;
            }
        }
        for (p, slot) in map_of_part.iter_mut().enumerate() {
            if *slot == UNSET {
                debug_assert!(!matches!(
                    scene.part_source(PartId(p as u32)),
                    PartSource::MeshFace { .. }
                ));
                *slot = next;
                next += 1;
            }
        }
        MapAssignment {
            map_of_part,
            map_count: next,
        }
    }
}
