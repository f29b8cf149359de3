//! One glTF mesh primitive placed in the world: positions, triangles, material and the
//! optional per-vertex attributes and textures, as the loader hands them to the scene builder.

use std::sync::Arc;

use glam::{Vec2, Vec3};

use super::material::GltfMaterial;
use crate::emission::EmissionTexture;
use crate::sampler::Sampler;
use crate::scene::material_textures::MaterialTextures;
use crate::texture::Texture;

/// One mesh primitive placed in the world.
#[derive(Clone, Debug, PartialEq)]
pub struct GltfMesh {
    /// Index of the node that placed it.
    pub node: usize,
    /// Index of the mesh in `meshes`.
    pub mesh: usize,
    /// Index of the primitive within the mesh.
    pub primitive: usize,
    /// Index of the material in `materials`, `None` for the default material.
    pub material_index: Option<usize>,
    /// World-space vertex positions in metres, relative to
    /// [`GltfContent::origin_offset`](super::GltfContent::origin_offset).
    pub positions: Vec<Vec3>,
    /// Triangles as indices into `positions` (each checked in range), counter-clockwise
    /// seen from the front.
    pub triangles: Vec<[u32; 3]>,
    /// The material as this loader reads it.
    pub material: GltfMaterial,
    /// Texture coordinates per vertex, from the `TEXCOORD_n` set the material's base-colour
    /// texture names (read only when it has one), with its `KHR_texture_transform` applied.
    pub uvs: Option<Vec<Vec2>>,
    /// Linear vertex colours (`COLOR_0`, alpha dropped), multiplying the base colour.
    pub colors: Option<Vec<Vec3>>,
    /// World-space unit vertex normals (`NORMAL`, by the inverse transpose of the node's
    /// transform) for smooth shading; a non-finite or zero normal is stored as zero (the
    /// geometric normal is used there).
    pub normals: Option<Vec<Vec3>>,
    /// The decoded base-colour texture and its sampler, shared by every mesh that uses it.
    pub base_color_texture: Option<(Arc<Texture>, Sampler)>,
    /// The decoded emissive texture with its own texture coordinates per vertex (read only
    /// when the material has one and a non-zero emission factor); it multiplies
    /// [`GltfMaterial::emission`].
    pub emission_texture: Option<EmissionTexture>,
    /// The decoded material textures, each with its own texture coordinates per vertex: the
    /// metallic-roughness, specular and specular-colour textures (read only when the material
    /// is [`Material::MetallicRoughness`](crate::material::Material::MetallicRoughness) and has
    /// them), multiplying its factors at each point, and the normal map with world-space
    /// tangents (`TANGENT` or MikkTSpace's).
    pub material_textures: MaterialTextures,
}
