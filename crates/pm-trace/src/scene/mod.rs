//! The scene: meshes and analytic shapes split into parts, their surfaces, the lights, the
//! camera and the BVH; built with [`SceneBuilder`] and queried by rays.

mod appearance;
mod assemble;
pub(crate) mod builder;
mod checks;
mod faces_as_given;
pub(crate) mod material_texture;
pub(crate) mod material_textures;
mod mesh_input;
pub(crate) mod normal_texture;
pub mod offset;
mod parts;
mod queries;
pub(crate) mod shading;

pub use builder::SceneBuilder;
pub use material_texture::MaterialTexture;
pub use material_textures::MaterialTextures;
pub use mesh_input::MAX_SCENE_TRIANGLES;
use normal_texture::above_geometric;
pub use normal_texture::{MIN_MAPPED_COSINE, NormalTexture, mikktspace_tangents};
pub use queries::PAIRED_RAYS_MIN_TRIANGLES;
use shading::MeshShading;
pub use shading::VertexAttributes;

use crate::bsdf::Bsdf;
use crate::bsdf::shading_point::{ShadingPoint, TextureFactors};
use crate::bvh::{HitPrimitive, SceneBvh};
use crate::camera::Camera;
use crate::error::SceneError;
use crate::light::Light;
use crate::material::{Material, Surface};
use crate::part::{PartId, PartSource};
use crate::shape::Shape;
use glam::{DVec3, Vec3};
use pm_geom::{Aabb, FaceId, HalfEdgeMesh, MeshOptions};
use std::sync::Arc;

/// Which rays a query is for: camera rays skip surfaces hidden from the camera.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum RayKind {
    /// Primary or specular eye rays: surfaces with `camera_visible = false` are transparent.
    Camera,
    /// Photon, shadow and path rays: every surface counts.
    Other,
}

/// A ray–surface intersection.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Hit {
    /// Distance along the ray.
    pub t: f32,
    /// Hit point.
    pub position: Vec3,
    /// Unit geometric normal, flipped to face the incoming ray (`normal · direction ≤ 0`).
    pub normal: Vec3,
    /// True when the ray hit the side the surface's own normal points to (the emitting side
    /// of area lights, the outside of glass).
    pub front_face: bool,
    /// The part hit.
    pub part: PartId,
    /// Index of the part's surface in the scene's surface table (read with the triangle, so
    /// [`Scene::surface`] needs no per-part lookup).
    surface: u32,
    /// A bound on the distance of `position` from the true surface point (rounding).
    error: f32,
    /// The primitive hit (rays leaving a triangle skip it: [`Scene::occluded_from`]).
    primitive: HitPrimitive,
}

impl Hit {
    /// A bound on the distance of [`Hit::position`] from the surface point the ray really
    /// meets: its rounding error, which scales with the magnitudes it was computed from
    /// ([`offset::point_error`]). [`Scene::spawn_ray`] starts rays this far off the surface.
    pub fn error(&self) -> f32 {
        self.error
    }
}

/// A mesh of the scene and the parts of its faces.
#[derive(Clone, Debug)]
pub struct SceneMesh {
    mesh: HalfEdgeMesh,
    first_part: u32,
    /// Per-vertex attributes, only for meshes given some (untextured meshes pay nothing).
    shading: Option<Box<MeshShading>>,
}

impl SceneMesh {
    /// The half-edge mesh (faces after welding and dropping zero-area faces).
    pub fn half_edge_mesh(&self) -> &HalfEdgeMesh {
        &self.mesh
    }

    /// The part of face `face`.
    pub fn part_of_face(&self, face: FaceId) -> PartId {
        PartId(self.first_part + face.0)
    }

    /// This mesh's vertex attributes for a mesh re-made of pieces of its faces, piece `i`
    /// lying inside face `faces[i]` (see `MeshShading::for_pieces`); `None` for a mesh
    /// without attributes.
    pub(crate) fn shading_for_pieces(&self, faces: &[FaceId]) -> Option<Box<MeshShading>> {
        let shading = self.shading.as_ref()?;
        let sources: Vec<usize> = faces.iter().map(|&f| self.mesh.source_face(f)).collect();
        shading.for_pieces(&sources).map(Box::new)
    }
}

/// A scene ready for ray queries: parts with surfaces, lights, a camera and a BVH.
///
/// Cloning shares the BVH and copies the rest, so a second viewpoint
/// ([`Scene::with_camera`]) or a second partition of the same scene needs no rebuild.
#[derive(Clone, Debug)]
pub struct Scene {
    meshes: Vec<SceneMesh>,
    shapes: Vec<Shape>,
    /// Mesh faces are parts `0..mesh_part_count`, mesh by mesh (see `SceneMesh::first_part`).
    mesh_part_count: u32,
    /// What each later part is (the analytic shapes' parts).
    shape_parts: Vec<PartSource>,
    /// Index in `surfaces` of each part's surface.
    part_surface_ids: Vec<u32>,
    /// The distinct surfaces.
    surfaces: Vec<Surface>,
    lights: Vec<Box<dyn Light>>,
    camera: Camera,
    bounds: Aabb,
    epsilon: f32,
    mesh_options: MeshOptions,
    bvh: Arc<SceneBvh>,
    /// True when some mesh has vertex attributes (else [`Scene::albedo_at`] skips the lookup).
    has_shading: bool,
    /// True when some mesh has an emission texture (else [`Scene::emission`] skips the lookup).
    has_emission_textures: bool,
    /// True when some surface is [`crate::Sides::Single`] (else camera rays cull nothing).
    has_culling: bool,
    /// The world point the scene's coordinates are relative to ([`Scene::origin_offset`]).
    origin_offset: DVec3,
}

impl Scene {
    /// The ray-query structure, shared (the contact partition takes it over for the scene it
    /// rebuilds).
    pub(crate) fn ray_search(&self) -> Arc<SceneBvh> {
        Arc::clone(&self.bvh)
    }

    /// The ray-query structure (for tests that compare its two kinds of search).
    #[cfg(test)]
    pub(crate) fn search(&self) -> &SceneBvh {
        &self.bvh
    }

    /// A bound on the rounding error of any hit point in this scene: [`offset::point_error`]
    /// for a ray from the scene's farthest coordinate across its whole diagonal. Tolerances
    /// that are not about one hit (the short cast that finds a stored photon's surface, the
    /// match of a ray's hit with a light's surface) use it; rays leaving a hit use the hit's
    /// own, tighter [`Hit::error`].
    pub fn epsilon(&self) -> f32 {
        self.epsilon
    }

    /// The lights.
    pub fn lights(&self) -> &[Box<dyn Light>] {
        &self.lights
    }

    /// The camera.
    pub fn camera(&self) -> &Camera {
        &self.camera
    }

    /// The same scene seen through `camera` (checked as [`SceneBuilder::camera`]'s is); clone
    /// the scene first to keep both viewpoints.
    pub fn with_camera(mut self, camera: Camera) -> Result<Self, SceneError> {
        camera
            .validate()
            .map_err(|reason| SceneError::InvalidCamera { reason })?;
        self.camera = camera;
        Ok(self)
    }

    /// The world point, in metres and f64, that this scene's origin stands for: a position `p`
    /// in the scene is `origin_offset + p` in the world its geometry was given in. Zero unless
    /// the scene was re-centred, as the glTF loader does for a model far from its origin
    /// (see `gltf`'s module documentation), so f32 keeps the model's detail; add it to map a
    /// point of the scene (a hit, a photon, the camera) back to the file's coordinates.
    pub fn origin_offset(&self) -> DVec3 {
        self.origin_offset
    }

    /// Bounds of all geometry.
    pub fn bounds(&self) -> Aabb {
        self.bounds
    }

    /// Surface of the part that was hit.
    #[inline]
    pub fn surface(&self, hit: &Hit) -> &Surface {
        &self.surfaces[hit.surface as usize]
    }

    /// Surface of a part.
    #[inline]
    pub fn part_surface(&self, part: PartId) -> &Surface {
        &self.surfaces[self.part_surface_ids[part.0 as usize] as usize]
    }

    /// Material of the part that was hit.
    #[inline]
    pub fn material(&self, hit: &Hit) -> &Material {
        &self.surface(hit).material
    }

    /// The reflectance at a hit: a Lambertian surface's albedo or a mirror's reflectance (one
    /// for glass, a custom or metallic-roughness BSDF's [`crate::bsdf::Bsdf::diffuse_albedo`]), times the mesh's base-colour
    /// texture at the hit's texture coordinates and its interpolated vertex colours where the
    /// mesh has them. Use this, not the material's factor, wherever a hit's colour matters;
    /// the photon-map estimators read radiance `albedo_at/π · E` with it.
    #[inline]
    pub fn albedo_at(&self, hit: &Hit) -> Vec3 {
        self.albedo_over(hit, 0.0)
    }

    /// [`Scene::albedo_at`] with the texture averaged over a footprint `footprint` metres
    /// across around the hit (its mip chain, [`crate::Sampler::sample_footprint`]): what a
    /// camera pixel covering that much of the surface sees, without the aliasing of a point
    /// lookup when many texels fall in one pixel. Zero is a point lookup.
    #[inline]
    pub fn albedo_over(&self, hit: &Hit, footprint: f32) -> Vec3 {
        let base = match self.surface(hit).material {
            Material::Lambertian { albedo } => albedo,
            Material::Mirror { reflectance } => reflectance,
            Material::Glass { .. } => Vec3::ONE,
            Material::Custom(bsdf) => {
                let at = self.shading_point_about(hit, self.shading_normal_at(hit), footprint);
                return bsdf.diffuse_albedo(&at);
            }
            Material::MetallicRoughness(m) => {
                let at = self.shading_point_about(hit, self.shading_normal_at(hit), footprint);
                return m.diffuse_albedo(&at);
            }
        };
        match self.tint(hit, footprint) {
            Some(tint) => base * tint,
            None => base,
        }
    }

    /// The base-colour texture times the vertex colours at `hit`, averaged over `footprint`
    /// metres (see [`Scene::albedo_over`]); one where the mesh has neither.
    #[inline]
    pub fn tint_over(&self, hit: &Hit, footprint: f32) -> Vec3 {
        self.tint(hit, footprint).unwrap_or(Vec3::ONE)
    }

    /// The tint at `hit`, `None` where the mesh has no texture or vertex colours.
    #[inline]
    fn tint(&self, hit: &Hit, footprint: f32) -> Option<Vec3> {
        let (shading, face) = self.mesh_shading(hit)?;
        Some(shading.colour_at(face, hit.position, footprint))
    }

    /// The metallic-roughness texture's factors at `hit` averaged over `footprint` metres
    /// (see [`Scene::albedo_over`]); [`TextureFactors::ONE`] where the mesh has no such
    /// texture.
    #[inline]
    pub fn factors_over(&self, hit: &Hit, footprint: f32) -> TextureFactors {
        self.mesh_shading(hit)
            .and_then(|(shading, face)| shading.factors_at(face, hit.position, footprint))
            .unwrap_or(TextureFactors::ONE)
    }

    /// The vertex attributes of `hit`'s mesh and the source triangle hit, `None` for an
    /// analytic part or a mesh without attributes.
    #[inline]
    fn mesh_shading(&self, hit: &Hit) -> Option<(&MeshShading, usize)> {
        if !self.has_shading || hit.part.0 >= self.mesh_part_count {
            return None;
        }
        let mesh = &self.meshes[self.meshes.partition_point(|m| m.first_part <= hit.part.0) - 1];
        let shading = mesh.shading.as_ref()?;
        let face = mesh.mesh.source_face(FaceId(hit.part.0 - mesh.first_part));
        Some((shading, face))
    }

    /// Where `hit`'s surface scatters ([`crate::bsdf::Bsdf`]'s argument): the shading normal
    /// ([`Scene::shading_normal_at`]), the tint at the point ([`Scene::tint_over`]) and the
    /// material's textured factors there ([`Scene::factors_over`]).
    #[inline]
    pub fn shading_point(&self, hit: &Hit) -> ShadingPoint {
        self.shading_point_about(hit, self.shading_normal_at(hit), 0.0)
    }

    /// [`Scene::shading_point`] shaded about the unit normal `shading` (on the geometric
    /// normal's side; the photon tracer scatters diffusely about the geometric normal) with
    /// the tint and factors averaged over `footprint` metres.
    #[inline]
    pub fn shading_point_about(&self, hit: &Hit, shading: Vec3, footprint: f32) -> ShadingPoint {
        ShadingPoint {
            position: hit.position,
            geometric: hit.normal,
            shading,
            front_face: hit.front_face,
            tint: self.tint_over(hit, footprint),
            factors: self.factors_over(hit, footprint),
        }
    }

    /// The unit normal to shade `hit` with: the mesh's interpolated vertex normals (glTF
    /// `NORMAL`) where it has them, else the geometric [`Hit::normal`]; where the mesh has a
    /// normal map ([`NormalTexture`]) that normal bent by it, and then kept at least
    /// [`MIN_MAPPED_COSINE`] above the geometric surface (tilted towards the geometric normal,
    /// within the plane of the two, where the map leans it further).
    ///
    /// The result is always on the geometric normal's side (the side the ray came from): an
    /// interpolated normal pointing into the surface is flipped (negated). Geometric normals
    /// stay the reference for ray offsets and for deciding sides; the render modes count a
    /// light direction or a bounce only when it is above *both* the shading and the geometric
    /// surface, so near the shadow terminator of a coarse mesh, where the two disagree, light
    /// does not leak through the surface (it is lost, a slight darkening, instead).
    ///
    /// Mirrors and glass (the photon tracer's and the render modes' specular bounces) reflect
    /// and refract about this normal, so a smooth glass mesh focuses light like the surface it
    /// approximates. Where it faces away from the incoming ray, or the direction it gives lies
    /// on the wrong side of the geometric surface (a reflection into it, a refraction back out
    /// of it, near a coarse mesh's silhouette), that bounce is made about the geometric normal
    /// instead, so no specular path crosses a surface it should not.
    #[inline]
    pub fn shading_normal_at(&self, hit: &Hit) -> Vec3 {
        if !self.has_shading || hit.part.0 >= self.mesh_part_count {
            return hit.normal;
        }
        let mesh = &self.meshes[self.meshes.partition_point(|m| m.first_part <= hit.part.0) - 1];
        let Some(shading) = mesh.shading.as_ref().filter(|s| s.has_normals()) else {
            return hit.normal;
        };
        let face = mesh.mesh.source_face(FaceId(hit.part.0 - mesh.first_part));
        let front = if hit.front_face { hit.normal } else { -hit.normal };
        let Some((smooth, mapped)) = shading.normals_at(face, hit.position, front) else {
            return hit.normal;
        };
        let n = smooth.try_normalize().unwrap_or(hit.normal);
        let flip = n.dot(hit.normal) < 0.0;
        match mapped {
            None if flip => -n,
            None => n,
            Some(m) => above_geometric(if flip { -m } else { m }, hit.normal),
        }
    }

    /// Radiance emitted towards the ray that made `hit`: the surface's emission, times its
    /// mesh's emission texture at the hit where it has one; zero on the back of emitters
    /// unless their surface is [`crate::Sides::Double`].
    #[inline]
    pub fn emission(&self, hit: &Hit) -> Vec3 {
        let surface = self.surface(hit);
        if !(hit.front_face || surface.sides.emits_back()) {
            return Vec3::ZERO;
        }
        if !self.has_emission_textures || hit.part.0 >= self.mesh_part_count || surface.emission == Vec3::ZERO
        {
            return surface.emission;
        }
        let mesh = &self.meshes[self.meshes.partition_point(|m| m.first_part <= hit.part.0) - 1];
        let face = mesh.mesh.source_face(FaceId(hit.part.0 - mesh.first_part));
        match mesh
            .shading
            .as_ref()
            .and_then(|s| s.emission_texture_at(face, hit.position))
        {
            Some(texture) => surface.emission * texture,
            None => surface.emission,
        }
    }

    /// Bytes this scene holds on the heap: its meshes, the ray-query structure (triangles, BVH
    /// nodes), the per-part tables and the surfaces. Lights are not counted.
    pub fn heap_bytes(&self) -> usize {
        self.meshes
            .iter()
            .map(|m| size_of::<SceneMesh>() + m.mesh.heap_bytes())
            .sum::<usize>()
            + self.bvh.heap_bytes()
            + self.part_surface_ids.capacity() * size_of::<u32>()
            + self.surfaces.capacity() * size_of::<Surface>()
            + self.shape_parts.capacity() * size_of::<PartSource>()
            + self.shapes.capacity() * size_of::<Shape>()
            + self
                .meshes
                .iter()
                .filter_map(|m| m.shading.as_ref())
                .map(|s| s.heap_bytes())
                .sum::<usize>()
    }
}
