//! Contact-aware partition: the crease-angle partition, made to see faces that touch without
//! sharing an edge (a wall standing on a floor that runs under it), so that no photon map
//! spans both sides of such a contact. Ball & Stejko's future work ("light bleeding would still
//! occur if the floor were one rectangle across both boxes").

use super::{MapAssignment, PartitionError, Partitioner};
use crate::{PartId, PartSource, Scene, SceneError, Surface};
use glam::Vec3;
use pm_geom::{FaceId, HalfEdgeMesh, MeshOptions, split_polygons_at_contacts};

/// Crease-angle maps over all meshes of a scene welded together, after splitting faces along
/// their contacts.
///
/// Use it in two steps: [`Contact::split_scene`] (also [`Partitioner::prepare_scene`]) cuts
/// every face that another face stands on
/// (the floor under a wall) along the contact line into convex pieces, so that the contact
/// becomes an edge shared by three or more faces (floor left, floor right, wall); then
/// [`Partitioner::partition`] flood-fills across edges with a crease angle below `max_angle`
/// over one half-edge mesh of *all* mesh faces, where such an edge is non-manifold and never
/// joins two maps. Where the cut runs beyond the contact (a doorway, the floor around a box)
/// the pieces share ordinary edges and stay in one map, because light really passes there.
/// The renderers refuse a scene that has not been split ([`Partitioner::check_scene`]).
///
/// Unlike [`crate::CreaseAngle`], faces of different meshes join when they share a flat edge.
/// Analytic parts each get a map of their own, as with [`crate::CreaseAngle`].
///
/// Tolerances scale with the scene: a point counts as lying on a plane, a line or another point
/// within `relative_tolerance × scene diagonal` (default `1e-5`: 10 µm in a 1 m room).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Contact {
    /// Largest crease angle (between face normals, 0 = flat) that still joins, radians.
    pub max_angle: f32,
    /// Contact and welding tolerance as a fraction of the scene's bounding-box diagonal.
    pub relative_tolerance: f32,
}

impl Default for Contact {
    /// 30° and `1e-5`.
    fn default() -> Self {
        Contact {
            max_angle: 30f32.to_radians(),
            relative_tolerance: 1e-5,
        }
    }
}

impl Contact {
    /// The absolute tolerance (metres) for `scene`.
    pub fn tolerance(&self, scene: &Scene) -> f32 {
        (self.relative_tolerance * scene.bounds().diagonal()).max(f32::MIN_POSITIVE)
    }

    /// Rebuilds `scene` with every mesh face that another face touches split along the contact
    /// lines. Each piece keeps its face's surface and its vertex attributes (texture
    /// coordinates, colours and normals, interpolated over the original triangle, so
    /// [`Scene::albedo_at`] and [`Scene::shading_normal_at`] give what they gave before the
    /// split); lights, analytic shapes and the camera are unchanged, and so is the total area
    /// of every face.
    pub fn split_scene(&self, scene: Scene) -> Result<Scene, SceneError> {
        let tolerance = self.tolerance(&scene);
        let (polygons, surfaces, mesh_of) = mesh_faces(&scene);
        let split = split_polygons_at_contacts(&polygons, tolerance);
        // The face (within its mesh) of each polygon, in the same order as `mesh_faces`.
        let face_of: Vec<FaceId> = scene
            .meshes()
            .iter()
            .flat_map(|m| m.half_edge_mesh().faces())
            .collect();

        // One rebuilt mesh per original mesh, holding that mesh's pieces.
        let mesh_count = scene.meshes().len();
        let mut positions: Vec<Vec<Vec3>> = vec![Vec::new(); mesh_count];
        let mut faces: Vec<Vec<Vec<u32>>> = vec![Vec::new(); mesh_count];
        let mut face_surfaces: Vec<Vec<Surface>> = vec![Vec::new(); mesh_count];
        let mut piece_faces: Vec<Vec<FaceId>> = vec![Vec::new(); mesh_count];
        for (piece, &source) in split.polygons.iter().zip(&split.source) {
            let m = mesh_of[source];
            let start = positions[m].len() as u32;
            positions[m].extend_from_slice(piece);
            faces[m].push((start..start + piece.len() as u32).collect());
            face_surfaces[m].push(surfaces[source]);
            piece_faces[m].push(face_of[source]);
        }
        // Vertex attributes (texture coordinates, colours, normals) carry over: each piece is
        // shaded by interpolating over the whole original triangle it lies in.
        let shading: Vec<_> = scene
            .meshes()
            .iter()
            .zip(&piece_faces)
            .map(|(mesh, pieces)| mesh.shading_for_pieces(pieces))
            .collect();
        let weld = MeshOptions {
            weld_tolerance: tolerance,
        };
        let mut builder = scene
            .into_builder_without_meshes()
            .mesh_options(weld)
            .split_at_contacts();
        for (m, shading) in shading.into_iter().enumerate() {
            if !faces[m].is_empty() {
                builder = builder.mesh_per_face_shaded(&positions[m], &faces[m], &face_surfaces[m], shading);
            }
        }
        builder.build()
    }
}

impl Partitioner for Contact {
    /// Splits the scene along its contacts ([`Contact::split_scene`]); a scene split already is
    /// returned as it is.
    fn prepare_scene(&self, scene: Scene) -> Result<Scene, SceneError> {
        if scene.is_split_at_contacts() {
            Ok(scene)
        } else {
            self.split_scene(scene)
        }
    }

    /// Refuses a scene not split along its contacts: its maps would silently be the
    /// crease-angle ones.
    fn check_scene(&self, scene: &Scene) -> Result<(), PartitionError> {
        if scene.is_split_at_contacts() {
            Ok(())
        } else {
            Err(PartitionError::NotSplitAtContacts)
        }
    }

    fn partition(&self, scene: &Scene) -> MapAssignment {
        const UNSET: u32 = u32::MAX;
        let (polygons, _, _) = mesh_faces(scene);
        let mut part_of_input = Vec::with_capacity(polygons.len());
        for mesh in scene.meshes() {
            part_of_input.extend(mesh.half_edge_mesh().faces().map(|f| mesh.part_of_face(f)));
        }
        let mut positions = Vec::new();
        let mut faces = Vec::with_capacity(polygons.len());
        for polygon in &polygons {
            let start = positions.len() as u32;
            positions.extend_from_slice(polygon);
            faces.push((start..start + polygon.len() as u32).collect::<Vec<u32>>());
        }
        let options = MeshOptions {
            weld_tolerance: self.tolerance(scene),
        };
        let mut map_of_part = vec![UNSET; scene.part_count()];
        let mut next = 0u32;
        // The scene's meshes were built from the same polygons, so welding them again cannot
        // fail; if it ever did, every face would fall through to a map of its own below.
        if let Ok(welded) = HalfEdgeMesh::build(&positions, &faces, &options) {
            let part = |f: FaceId| part_of_input[welded.source_face(f)];
            let mut stack: Vec<FaceId> = Vec::new();
            for seed in welded.faces() {
                if map_of_part[part(seed).0 as usize] != UNSET {
                    continue;
                }
                map_of_part[part(seed).0 as usize] = next;
                stack.push(seed);
                while let Some(face) = stack.pop() {
                    for (he, other) in welded.neighbours(face) {
                        let slot = &mut map_of_part[part(other).0 as usize];
                        if *slot == UNSET && welded.crease_angle(he).is_some_and(|a| a < self.max_angle) {
                            *slot = next;
                            stack.push(other);
                        }
                    }
                }
                next += 1;
            }
        }
        for slot in map_of_part.iter_mut().filter(|s| **s == UNSET) {
            *slot = next;
            next += 1;
        }
        MapAssignment {
            map_of_part,
            map_count: next,
        }
    }
}

/// Every mesh face of the scene as a polygon, with its surface and the index of its mesh, in
/// part order.
fn mesh_faces(scene: &Scene) -> (Vec<Vec<Vec3>>, Vec<Surface>, Vec<usize>) {
    let mut polygons = Vec::new();
    let mut surfaces = Vec::new();
    let mut mesh_of = Vec::new();
    for (m, mesh) in scene.meshes().iter().enumerate() {
        let half_edges = mesh.half_edge_mesh();
        for face in half_edges.faces() {
            polygons.push(half_edges.face_polygon(face).collect());
            surfaces.push(*scene.part_surface(mesh.part_of_face(face)));
            mesh_of.push(m);
        }
    }
    debug_assert!(
        (0..scene.part_count() as u32)
            .filter(|&p| matches!(scene.part_source(PartId(p)), PartSource::MeshFace { .. }))
            .count()
            == polygons.len()
    );
    (polygons, surfaces, mesh_of)
}
