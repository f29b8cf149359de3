//! Building a [`Scene`]: meshes, analytic shapes, lights and a camera checked and turned into
//! parts with surfaces and the ray-query structure.

use super::Scene;
use super::assemble::{PartTable, RayTriangles, add_shapes, build_meshes, scene_bounds};
use super::checks::{check_lights, default_camera};
use super::mesh_input::{FaceSurfaces, MAX_SCENE_TRIANGLES, MeshInput};
use super::shading::{MeshShading, VertexAttributes};
use crate::bvh::SceneBvh;
use crate::camera::Camera;
use crate::error::SceneError;
use crate::light::Light;
use crate::light::area::AreaLight;
use crate::material::{Material, Surface};
use crate::part::{PartId, PartSource};
use crate::shape::Shape;
use crate::shape::ring::{Ring, RingSide};
use crate::shape::sphere::Sphere;
use glam::{DVec3, Vec3};
use pm_geom::MeshOptions;
use std::sync::Arc;

impl Scene {
    /// A new, empty builder.
    pub fn builder() -> SceneBuilder {
        SceneBuilder::default()
    }

    /// A builder holding this scene's analytic shapes, lights, camera and mesh options but none
    /// of its meshes, for rebuilding the scene with re-meshed geometry (for example faces split
    /// along contact lines). Add every mesh again, including those of area-light quads.
    pub(crate) fn into_builder_without_meshes(self) -> SceneBuilder {
        let mut shapes = Vec::with_capacity(self.shapes.len());
        for (i, source) in self.shape_parts.iter().enumerate() {
            let surface = *self.part_surface(PartId(self.mesh_part_count + i as u32));
            match *source {
                PartSource::Sphere { shape }
                | PartSource::Ring {
                    shape,
                    side: RingSide::Top,
                } => shapes.push((self.shapes[shape as usize], surface)),
                _ => {}
            }
        }
        SceneBuilder {
            shapes,
            lights: self.lights,
            camera: Some(self.camera),
            mesh_options: self.mesh_options,
            origin_offset: self.origin_offset,
            ..SceneBuilder::default()
        }
    }
}

/// Builds a [`Scene`]; errors are reported by [`SceneBuilder::build`].
///
/// ```
/// use pm_trace::{Scene, Surface, PointLight, glam::Vec3};
/// let floor = [Vec3::new(-1.0, 0.0, -1.0), Vec3::new(-1.0, 0.0, 1.0), Vec3::new(1.0, 0.0, 1.0), Vec3::new(1.0, 0.0, -1.0)];
/// let scene = Scene::builder()
///     .mesh(&floor, &[[0u32, 1, 2, 3]], Surface::diffuse(Vec3::splat(0.5)))
///     .sphere(Vec3::new(0.0, 0.5, 0.0), 0.25, Surface::mirror(Vec3::ONE))
///     .light(PointLight::new(Vec3::new(0.0, 2.0, 0.0), Vec3::splat(100.0)))
///     .build()?;
/// assert_eq!(scene.part_count(), 2);
/// # Ok::<(), pm_trace::SceneError>(())
/// ```
#[derive(Clone, Default)]
pub struct SceneBuilder {
    pub(super) meshes: Vec<MeshInput>,
    pub(super) shapes: Vec<(Shape, Surface)>,
    pub(super) lights: Vec<Box<dyn Light>>,
    pub(super) camera: Option<Camera>,
    pub(super) mesh_options: MeshOptions,
    pub(super) max_triangles: Option<usize>,
    pub(super) origin_offset: DVec3,
    pub(super) ray_triangles: RayTriangles,
}

impl std::fmt::Debug for SceneBuilder {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("SceneBuilder")
            .field("meshes", &self.meshes.len())
            .field("shapes", &self.shapes.len())
            .field("lights", &self.lights)
            .field("camera", &self.camera)
            .finish()
    }
}

impl SceneBuilder {
    /// Adds a mesh of convex planar polygons (vertex index lists, counter-clockwise seen from
    /// the side the normal points to), all with `surface`.
    pub fn mesh<F: AsRef<[u32]>>(mut self, positions: &[Vec3], faces: &[F], surface: Surface) -> Self {
        self.meshes
            .push(MeshInput::new(positions, faces, FaceSurfaces::One(surface)));
        self
    }

    /// Adds a mesh with one surface per face (`surfaces.len() == faces.len()`).
    pub fn mesh_per_face<F: AsRef<[u32]>>(
        mut self,
        positions: &[Vec3],
        faces: &[F],
        surfaces: &[Surface],
    ) -> Self {
        self.meshes.push(MeshInput::new(
            positions,
            faces,
            FaceSurfaces::PerFace(surfaces.to_vec()),
        ));
        self
    }

    /// A mesh of polygons whose vertices are listed one polygon after another, each its own
    /// (polygon `f` is `positions[starts[f]..starts[f + 1]]`, `starts` rising from 0 to
    /// `positions.len()`), with one surface per polygon and the vertex attributes `shading`
    /// (already made for these polygons: see `SceneMesh::shading_for_pieces`). Takes the
    /// vectors without copying them: the contact split hands over its pieces this way, so
    /// that they are not held twice while the scene is built.
    pub(crate) fn mesh_of_listed_polygons(
        mut self,
        positions: Vec<Vec3>,
        starts: Vec<usize>,
        surfaces: Vec<Surface>,
        shading: Option<Box<MeshShading>>,
    ) -> Self {
        let indices = (0..positions.len() as u32).collect();
        let mut input = MeshInput::from_flat(positions, indices, starts, FaceSurfaces::PerFace(surfaces));
        input.shading = shading;
        self.meshes.push(input);
        self
    }

    /// Adds a triangle mesh whose vertices carry attributes (texture coordinates, colours, a
    /// base-colour texture), all with `surface`; [`Scene::albedo_at`] multiplies the surface's
    /// colour by them. Each attribute present must have one entry per vertex
    /// ([`SceneError::InvalidAttributes`] otherwise). Meshes without attributes cost nothing
    /// extra; these keep a copy of their positions, triangles and attributes.
    pub fn attributed_mesh(
        mut self,
        positions: &[Vec3],
        triangles: &[[u32; 3]],
        surface: Surface,
        attributes: VertexAttributes,
    ) -> Self {
        let mut input = MeshInput::new(positions, triangles, FaceSurfaces::One(surface));
        input.shading = Some(Box::new(MeshShading::new(positions, triangles, attributes)));
        self.meshes.push(input);
        self
    }

    /// Adds a sphere.
    pub fn sphere(mut self, center: Vec3, radius: f32, surface: Surface) -> Self {
        self.shapes
            .push((Shape::Sphere(Sphere { center, radius }), surface));
        self
    }

    /// Adds a ring (thick washer) whose bottom annulus is centred at `center`, extending
    /// `height` along `axis` (normalised here).
    pub fn ring(
        mut self,
        center: Vec3,
        axis: Vec3,
        inner_radius: f32,
        outer_radius: f32,
        height: f32,
        surface: Surface,
    ) -> Self {
        let axis = axis.try_normalize().unwrap_or(Vec3::ZERO);
        self.shapes.push((
            Shape::Ring(Ring {
                center,
                axis,
                inner_radius,
                outer_radius,
                height,
            }),
            surface,
        ));
        self
    }

    /// Adds a light.
    pub fn light(self, light: impl Light + 'static) -> Self {
        self.boxed_light(Box::new(light))
    }

    /// Adds a boxed light.
    pub fn boxed_light(mut self, light: Box<dyn Light>) -> Self {
        self.lights.push(light);
        self
    }

    /// Adds a parallelogram area light `corner + s·edge_u + t·edge_v` emitting `radiance`
    /// towards `edge_u × edge_v`: both its (black, emissive) geometry, as a mesh of its own,
    /// and the [`AreaLight`].
    ///
    /// The order of the edges is its orientation (right-handed): a ceiling light facing down
    /// (−y) takes `edge_u` along +x and `edge_v` along +z, since x × z = −y. Swapped, the
    /// light faces the ceiling it hangs under, its power lands on the ceiling within a
    /// millimetre, and the room comes out many times darker; the tracing statistics say so
    /// ([`crate::TraceStats::near_light_fraction`], also in the renderer's statistics and the
    /// render example's summary).
    ///
    /// ```
    /// use pm_trace::glam::{Vec3, vec3};
    /// use pm_trace::{CreaseAngle, Partitioner, Scene, Surface, TraceOptions, trace_photons};
    ///
    /// // A 2 m room, open at the front, with a 0.5 m light 0.5 mm under its ceiling.
    /// let room = |edge_u: Vec3, edge_v: Vec3| {
    ///     let c = [
    ///         vec3(0.0, 0.0, 0.0), vec3(2.0, 0.0, 0.0), vec3(2.0, 0.0, 2.0), vec3(0.0, 0.0, 2.0),
    ///         vec3(0.0, 2.0, 0.0), vec3(2.0, 2.0, 0.0), vec3(2.0, 2.0, 2.0), vec3(0.0, 2.0, 2.0),
    ///     ];
    ///     let walls = [[0u32, 1, 2, 3], [4, 7, 6, 5], [0, 3, 7, 4], [1, 5, 6, 2], [3, 2, 6, 7]];
    ///     Scene::builder()
    ///         .mesh(&c, &walls, Surface::diffuse(Vec3::splat(0.7)))
    ///         .area_light_quad(vec3(0.75, 1.9995, 0.75), edge_u, edge_v, Vec3::splat(10.0))
    ///         .build()
    /// };
    /// let (x, z) = (vec3(0.5, 0.0, 0.0), vec3(0.0, 0.0, 0.5));
    /// assert_eq!(x.cross(z).normalize(), Vec3::NEG_Y);
    /// for (edges, near) in [((x, z), 0.0..0.01), ((z, x), 0.99..1.01)] {
    ///     let partitioned = CreaseAngle::default().partition(room(edges.0, edges.1)?)?;
    ///     let options = TraceOptions { photons: 2_000, ..TraceOptions::default() };
    ///     let traced = trace_photons(partitioned.scene(), partitioned.assignment(), &options)?;
    ///     // Facing down: nothing lands within 1 mm of the light. Facing up: everything does.
    ///     assert!(near.contains(&traced.stats().near_light_fraction));
    /// }
    /// # Ok::<(), Box<dyn std::error::Error>>(())
    /// ```
    pub fn area_light_quad(self, corner: Vec3, edge_u: Vec3, edge_v: Vec3, radiance: Vec3) -> Self {
        let quad = [corner, corner + edge_u, corner + edge_u + edge_v, corner + edge_v];
        let surface = Surface {
            material: Material::Lambertian { albedo: Vec3::ZERO },
            emission: radiance,
            camera_visible: true,
            sides: crate::sides::Sides::Front,
        };
        self.mesh(&quad, &[[0u32, 1, 2, 3]], surface)
            .light(AreaLight::quad(corner, edge_u, edge_v, radiance))
    }

    /// Sets the camera (default: looking at the scene along +z from in front of its bounds).
    pub fn camera(mut self, camera: Camera) -> Self {
        self.camera = Some(camera);
        self
    }

    /// Refuses to build a scene of more than `limit` triangles (faces fan-triangulated) with
    /// [`SceneError::TooManyTriangles`], before allocating for them; the default and the
    /// largest limit is [`MAX_SCENE_TRIANGLES`]. At 80–94 bytes per built triangle and a peak
    /// near 400 while building, this bounds a scene's memory.
    pub fn max_triangles(mut self, limit: usize) -> Self {
        self.max_triangles = Some(limit);
        self
    }

    /// Records that the scene's coordinates are relative to the world point `offset` (in
    /// metres, f64): a position `p` in the scene stands for `offset + p` in the world the
    /// geometry came from. Only recorded ([`Scene::origin_offset`]); nothing is moved. The glTF
    /// loader sets it when it re-centres a scene far from its origin. A non-finite offset is
    /// [`SceneError::InvalidParameter`].
    pub fn origin_offset(mut self, offset: DVec3) -> Self {
        self.origin_offset = offset;
        self
    }

    /// Builds the scene without searching its meshes' triangles: the caller puts the triangles
    /// rays meet in afterwards (`Scene::trace_faces_as_given`).
    pub(crate) fn defer_ray_triangles(mut self) -> Self {
        self.ray_triangles = RayTriangles::Deferred;
        self
    }

    /// Sets the mesh options (weld tolerance) used for meshes.
    pub fn mesh_options(mut self, options: MeshOptions) -> Self {
        self.mesh_options = options;
        self
    }

    /// Builds the meshes, the parts and the BVH. Zero-area mesh faces are dropped (see
    /// [`HalfEdgeMesh::dropped_face_count`](pm_geom::HalfEdgeMesh::dropped_face_count)); everything else invalid is an error.
    pub fn build(self) -> Result<Scene, SceneError> {
        let triangle_count = self
            .meshes
            .iter()
            .fold(0usize, |n, m| n.saturating_add(m.triangle_count()));
        // Checked before anything is allocated for them (the BVH's node indices are u32).
        let limit = self
            .max_triangles
            .unwrap_or(MAX_SCENE_TRIANGLES)
            .min(MAX_SCENE_TRIANGLES);
        if triangle_count > limit {
            return Err(SceneError::TooManyTriangles {
                triangles: triangle_count,
                limit,
            });
        }
        if !self.origin_offset.is_finite() {
            return Err(SceneError::InvalidParameter {
                what: "origin offset".into(),
                reason: format!("{} is not finite", self.origin_offset),
            });
        }
        // Kept faces have at least one triangle each, so this is within the limit too.
        let face_count: usize = self.meshes.iter().map(|m| m.starts.len() - 1).sum();
        let mut parts = PartTable::with_capacity(
            face_count + RingSide::ALL.len() * self.shapes.len(),
            triangle_count,
            self.ray_triangles,
        );
        let meshes = build_meshes(self.meshes, &self.mesh_options, &mut parts)?;
        let mesh_part_count = parts.count();
        let (shapes, shape_parts) = add_shapes(&self.shapes, &mut parts)?;
        let PartTable {
            surfaces,
            surface_ids: part_surface_ids,
            triangles,
            triangle_parts,
            shape_prims,
            ..
        } = parts.finish()?;
        let bounds = scene_bounds(&meshes.meshes, &shapes)?;
        let mut lights = self.lights;
        for light in &mut lights {
            light.attach(&bounds);
        }
        check_lights(&lights)?;
        let camera = self.camera.unwrap_or_else(|| default_camera(&bounds));
        camera
            .validate()
            .map_err(|reason| SceneError::InvalidCamera { reason })?;
        // The scene-wide rounding bound: a ray from the farthest corner across the diagonal.
        let far = bounds.min.abs().max(bounds.max.abs());
        let epsilon = super::offset::point_error(far, far, bounds.diagonal());
        let has_culling = surfaces.surfaces.iter().any(|s| s.sides.culls_back());
        Ok(Scene {
            meshes: meshes.meshes,
            shapes,
            mesh_part_count,
            shape_parts,
            part_surface_ids,
            surfaces: surfaces.surfaces,
            lights,
            camera,
            bounds,
            epsilon,
            mesh_options: self.mesh_options,
            bvh: Arc::new(match self.ray_triangles {
                RayTriangles::Own => SceneBvh::build(triangles, triangle_parts, shape_prims),
                RayTriangles::Deferred => SceneBvh::build(Vec::new(), Vec::new(), shape_prims),
            }),
            has_shading: meshes.has_shading,
            has_emission_textures: meshes.has_emission_textures,
            has_culling,
            origin_offset: self.origin_offset,
        })
    }
}

#[cfg(test)]
mod tests {
    use crate::ray::Ray;
    use crate::scene::RayKind;
    use crate::scenes;
    use glam::Vec3;

    /// The builder the contact split rebuilds a scene with keeps its shapes, lights and camera.
    #[test]
    fn a_scene_rebuilds_from_its_own_meshes_with_the_same_parts_and_hits() {
        let scene = scenes::build("cornell-box").unwrap();
        // Collect every mesh as polygons with their surfaces, then rebuild.
        let mut meshes = Vec::new();
        for m in scene.meshes() {
            let mesh = m.half_edge_mesh();
            let mut positions = Vec::new();
            let mut faces = Vec::new();
            let mut surfaces = Vec::new();
            for f in mesh.faces() {
                let start = positions.len() as u32;
                positions.extend(mesh.face_polygon(f));
                faces.push((start..positions.len() as u32).collect::<Vec<u32>>());
                surfaces.push(*scene.part_surface(m.part_of_face(f)));
            }
            meshes.push((positions, faces, surfaces));
        }
        let parts = scene.part_count();
        let probe = Ray::new(Vec3::new(0.1, 0.2, 0.3), Vec3::new(0.3, -0.2, 0.5));
        let before = scene.intersect(&probe, f32::INFINITY, RayKind::Other).unwrap();
        let mut builder = scene.into_builder_without_meshes();
        for (p, f, s) in &meshes {
            builder = builder.mesh_per_face(p, f, s);
        }
        let rebuilt = builder.build().unwrap();
        assert_eq!(rebuilt.part_count(), parts);
        assert_eq!(rebuilt.lights().len(), 1);
        let after = rebuilt.intersect(&probe, f32::INFINITY, RayKind::Other).unwrap();
        assert_eq!(before.part, after.part);
        assert!((before.t - after.t).abs() < 1e-6);
    }
}
