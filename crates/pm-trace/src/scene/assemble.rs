//! Turning a builder's inputs into a scene's parts: mesh faces and analytic shape sides are
//! numbered as parts, each with its surface (stored once) and its triangles for the BVH.

use super::SceneMesh;
use super::checks::{SurfaceTable, check_shape, check_surface};
use super::mesh_input::{FaceSurfaces, MeshInput};
use crate::bvh::shape::ShapePrimitive;
use crate::error::SceneError;
use crate::material::Surface;
use crate::part::{PartId, PartSource, PartSurface};
use crate::shape::Shape;
use crate::shape::ring::RingSide;
use glam::Vec3;
use pm_geom::{Aabb, HalfEdgeMesh, MeshError, MeshOptions};
use rayon::prelude::*;

/// Which triangles the built scene's ray queries search.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub(crate) enum RayTriangles {
    /// Its own meshes' triangles.
    #[default]
    Own,
    /// None yet: the caller puts others in (the contact partition's faces as given,
    /// `Scene::trace_faces_as_given`), so the split scene's own are never searched.
    Deferred,
}

/// The parts as they are numbered: each part's surface id (surfaces stored once), the
/// triangles with their part for the BVH, and the analytic shapes' primitives.
pub(super) struct PartTable {
    count: u32,
    /// Whether the triangles are kept for the ray queries.
    ray_triangles: RayTriangles,
    /// Triangles numbered, kept or not.
    triangle_count: usize,
    pub(super) surfaces: SurfaceTable,
    pub(super) surface_ids: Vec<u32>,
    pub(super) triangles: Vec<[Vec3; 3]>,
    pub(super) triangle_parts: Vec<PartSurface>,
    pub(super) shape_prims: Vec<ShapePrimitive>,
}

impl PartTable {
    /// A table with room for `parts` parts and, when `ray_triangles` keeps them, `triangles`
    /// triangles (a scene whose ray triangles are put in later holds none of its own).
    pub(super) fn with_capacity(parts: usize, triangles: usize, ray_triangles: RayTriangles) -> Self {
        let triangles = match ray_triangles {
            RayTriangles::Own => triangles,
            RayTriangles::Deferred => 0,
        };
        PartTable {
            count: 0,
            ray_triangles,
            triangle_count: 0,
            surfaces: SurfaceTable::default(),
            surface_ids: Vec::with_capacity(parts),
            triangles: Vec::with_capacity(triangles),
            triangle_parts: Vec::with_capacity(triangles),
            shape_prims: Vec::new(),
        }
    }

    /// Parts numbered so far.
    pub(super) fn count(&self) -> u32 {
        self.count
    }

    /// The next part, with `surface`.
    fn add(&mut self, surface: Surface) -> PartSurface {
        let part = PartSurface {
            part: PartId(self.count),
            surface: self.surfaces.id_of(surface),
        };
        self.count += 1;
        self.surface_ids.push(part.surface);
        part
    }

    /// Numbers the fan triangles of `polygon`, a face of `part`, and keeps them for the ray
    /// queries when the table does.
    fn add_fan(&mut self, polygon: &[Vec3], part: PartSurface) {
        let fan = polygon.len().saturating_sub(2);
        self.triangle_count += fan;
        if self.ray_triangles == RayTriangles::Own {
            for i in 1..=fan {
                self.triangles.push([polygon[0], polygon[i], polygon[i + 1]]);
                self.triangle_parts.push(part);
            }
        }
    }

    /// The table with its spare room (left by dropped, degenerate faces) given back; a scene
    /// without a triangle or a shape is refused.
    pub(super) fn finish(mut self) -> Result<Self, SceneError> {
        self.triangles.shrink_to_fit();
        self.triangle_parts.shrink_to_fit();
        self.surface_ids.shrink_to_fit();
        if self.triangle_count == 0 && self.shape_prims.is_empty() {
            return Err(SceneError::NoGeometry);
        }
        Ok(self)
    }
}

/// The scene's meshes, and whether any has vertex attributes or an emission texture.
pub(super) struct BuiltMeshes {
    pub(super) meshes: Vec<SceneMesh>,
    pub(super) has_shading: bool,
    pub(super) has_emission_textures: bool,
}

/// Builds each input mesh's half-edge mesh and numbers its faces as parts. Each input mesh is
/// dropped once built, so the input and the scene are not held twice.
pub(super) fn build_meshes(
    inputs: Vec<MeshInput>,
    mesh_options: &MeshOptions,
    parts: &mut PartTable,
) -> Result<BuiltMeshes, SceneError> {
    let mut out = BuiltMeshes {
        meshes: Vec::with_capacity(inputs.len()),
        has_shading: false,
        has_emission_textures: false,
    };
    let mut inputs = inputs.into_iter().enumerate();
    loop {
        let wave: Vec<(usize, MeshInput)> = inputs.by_ref().take(MESH_WAVE).collect();
        if wave.is_empty() {
            break;
        }
        // The wave's half-edge meshes are built on the caller's rayon pool; what is checked
        // and numbered below stays in mesh order, so errors and parts are as on one thread.
        let built: Vec<_> = wave
            .par_iter()
            .map(|(_, input)| HalfEdgeMesh::build(&input.positions, &input.faces(), mesh_options))
            .collect();
        for ((mi, input), mesh) in wave.into_iter().zip(built) {
            add_mesh(mi, input, mesh, parts, &mut out)?;
        }
    }
    Ok(out)
}

/// Meshes whose half-edge meshes are built together: enough to keep the threads busy on a
/// scene of many meshes, few enough that the built meshes and their inputs are not all held
/// at once.
const MESH_WAVE: usize = 16;

/// Checks input mesh `mi` against its built half-edge mesh (or the error building it gave),
/// numbers its faces as parts and adds it to `out`.
fn add_mesh(
    mi: usize,
    input: MeshInput,
    mesh: Result<HalfEdgeMesh, MeshError>,
    parts: &mut PartTable,
    out: &mut BuiltMeshes,
) -> Result<(), SceneError> {
    if let FaceSurfaces::PerFace(s) = &input.surfaces
        && s.len() != input.face_count()
    {
        return Err(SceneError::SurfaceCount {
            mesh: mi,
            surfaces: s.len(),
            faces: input.face_count(),
        });
    }
    if let Some(shading) = &input.shading {
        shading
            .validate()
            .map_err(|reason| SceneError::InvalidAttributes { mesh: mi, reason })?;
        out.has_shading = true;
        out.has_emission_textures |= shading.has_emission_texture();
    }
    let mesh = mesh.map_err(|source| SceneError::Mesh { mesh: mi, source })?;
    let first_part = parts.count();
    let mut polygon = Vec::new();
    for face in mesh.faces() {
        let surface = match &input.surfaces {
            FaceSurfaces::One(s) => *s,
            FaceSurfaces::PerFace(s) => s[mesh.source_face(face)],
        };
        check_surface(&surface, || format!("mesh {mi} face {}", mesh.source_face(face)))?;
        let part = parts.add(surface);
        polygon.clear();
        polygon.extend(mesh.face_polygon(face));
        parts.add_fan(&polygon, part);
    }
    out.meshes.push(SceneMesh {
        mesh,
        first_part,
        shading: input.shading,
    });
    Ok(())
}

/// Checks the analytic shapes and numbers their parts (a sphere is one, a ring four): the
/// shapes, and what each of their parts is.
pub(super) fn add_shapes(
    inputs: &[(Shape, Surface)],
    parts: &mut PartTable,
) -> Result<(Vec<Shape>, Vec<PartSource>), SceneError> {
    let mut shape_parts = Vec::new();
    let mut shapes = Vec::with_capacity(inputs.len());
    for (si, (shape, surface)) in inputs.iter().enumerate() {
        check_shape(shape).map_err(|reason| SceneError::InvalidShape { shape: si, reason })?;
        check_surface(surface, || format!("shape {si}"))?;
        match *shape {
            Shape::Sphere(sphere) => {
                let part = parts.add(*surface);
                shape_parts.push(PartSource::Sphere { shape: si as u32 });
                parts.shape_prims.push(ShapePrimitive::Sphere { sphere, part });
            }
            Shape::Ring(ring) => {
                for side in RingSide::ALL {
                    let part = parts.add(*surface);
                    shape_parts.push(PartSource::Ring {
                        shape: si as u32,
                        side,
                    });
                    parts
                        .shape_prims
                        .push(ShapePrimitive::RingSide { ring, side, part });
                }
            }
        }
        shapes.push(*shape);
    }
    Ok((shapes, shape_parts))
}

/// The bounds of the meshes and shapes, refused when beyond the photon kd-tree's coordinate
/// range.
pub(super) fn scene_bounds(meshes: &[SceneMesh], shapes: &[Shape]) -> Result<Aabb, SceneError> {
    let bounds = meshes
        .iter()
        .flat_map(|m| m.mesh.positions().iter())
        .fold(Aabb::EMPTY, |b, &p| b.grow(p));
    let bounds = shapes.iter().fold(bounds, |b, s| b.union(s.bounds()));
    let reach = bounds.min.abs().max(bounds.max.abs()).max_element();
    // NaN bounds cannot occur (positions are checked finite), but are refused all the same.
    if reach.is_nan() || reach >= pm_kdtree::MAX_COORDINATE {
        return Err(SceneError::GeometryOutOfRange {
            min: bounds.min.to_array(),
            max: bounds.max.to_array(),
        });
    }
    Ok(bounds)
}
