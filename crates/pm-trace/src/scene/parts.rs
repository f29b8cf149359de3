//! The scene's parts: how many, where each comes from (a mesh face or an analytic shape's
//! side), the face the user gave that it belongs to, and its polygons.

use super::{Scene, SceneMesh};
use crate::part::{PartId, PartSource, SourceFace};
use crate::shape::Shape;
use glam::Vec3;
use pm_geom::FaceId;

/// Stacks of the sphere proxy polygons (`stacks × 2·stacks` cells = 512 polygons).
const SPHERE_PROXY_STACKS: u32 = 16;
/// Segments of each ring side's proxy (64 quads).
const RING_PROXY_SEGMENTS: u32 = 64;

impl Scene {
    /// Number of parts.
    pub fn part_count(&self) -> usize {
        self.part_surface_ids.len()
    }

    /// What part `part` is.
    pub fn part_source(&self, part: PartId) -> PartSource {
        if part.0 < self.mesh_part_count {
            // The last mesh whose first part is at or before `part`.
            let mesh = self.meshes.partition_point(|m| m.first_part <= part.0) - 1;
            PartSource::MeshFace {
                mesh: mesh as u32,
                face: FaceId(part.0 - self.meshes[mesh].first_part),
            }
        } else {
            self.shape_parts[(part.0 - self.mesh_part_count) as usize]
        }
    }

    /// The face the user gave for mesh part `part` (`None` for an analytic part). For a scene
    /// the contact partition has split, ask the [`Partitioned`](crate::partition::Partitioned)
    /// instead: its scene was rebuilt from pieces, and this would name the pieces.
    pub fn source_face(&self, part: PartId) -> Option<SourceFace> {
        match self.part_source(part) {
            PartSource::MeshFace { mesh, face } => Some(SourceFace {
                mesh,
                face: self.meshes[mesh as usize].mesh.source_face(face) as u32,
            }),
            PartSource::Sphere { .. } | PartSource::Ring { .. } => None,
        }
    }

    /// The meshes, in the order they were added.
    pub fn meshes(&self) -> &[SceneMesh] {
        &self.meshes
    }

    /// The analytic shapes, in the order they were added.
    pub fn shapes(&self) -> &[Shape] {
        &self.shapes
    }

    /// Calls `f` with each polygon of `part`: a mesh face as it is, analytic parts as a fine
    /// polygonal proxy (512 polygons per sphere, 64 per ring side). Polygons are wound
    /// counter-clockwise seen from the side the part's normal points to.
    pub fn for_each_part_polygon(&self, part: PartId, mut f: impl FnMut(&[Vec3])) {
        match self.part_source(part) {
            PartSource::MeshFace { mesh, face } => {
                let polygon: Vec<Vec3> = self.meshes[mesh as usize].mesh.face_polygon(face).collect();
                f(&polygon);
            }
            PartSource::Sphere { shape } => {
                if let Shape::Sphere(s) = self.shapes[shape as usize] {
                    s.for_each_proxy_polygon(SPHERE_PROXY_STACKS, f);
                }
            }
            PartSource::Ring { shape, side } => {
                if let Shape::Ring(r) = self.shapes[shape as usize] {
                    r.for_each_proxy_polygon(side, RING_PROXY_SEGMENTS, f);
                }
            }
        }
    }
}
