//! glTF metallic-roughness textures: a material's `metallicRoughnessTexture` decoded through the
//! shared texture cache as linear data (not sRGB colour) and read at its own `TEXCOORD_n`, with
//! `KHR_texture_transform` applied.

use gltf::json;

use super::emissive::{TextureCache, TextureSources, cached_texture};
use super::error::GltfError;
use super::material::GltfMaterial;
use crate::scene::metallic_roughness_texture::MetallicRoughnessTexture;
use crate::texture::TexelEncoding;

/// The metallic-roughness texture of primitive `prim` (mesh and primitive indices `at`) with
/// `material`, when the material has one (only [`GltfMaterial::metallic_roughness_texture`] of
/// a metallic-roughness kind is set). A primitive without the named `TEXCOORD_n` set gets a
/// warning and is shaded by the factors alone, as base-colour textures are.
pub(super) fn metallic_roughness_texture(
    sources: &TextureSources<'_>,
    cache: &mut TextureCache,
    scene_bytes: &mut u64,
    warnings: &mut Vec<String>,
    at: (usize, usize),
    prim: &json::mesh::Primitive,
    material: &GltfMaterial,
) -> Result<Option<MetallicRoughnessTexture>, GltfError> {
    let Some(reference) = material.metallic_roughness_texture else {
        return Ok(None);
    };
    let Some(uvs) = reference.read_uvs(sources.reader, prim)? else {
        warnings.push(format!(
            "mesh {} primitive {}: no TEXCOORD_{}, metallic-roughness texture ignored",
            at.0, at.1, reference.tex_coord
        ));
        return Ok(None);
    };
    let (texture, sampler) = cached_texture(
        sources,
        cache,
        reference.index,
        TexelEncoding::Linear,
        scene_bytes,
    )?;
    Ok(Some(MetallicRoughnessTexture {
        uvs,
        texture,
        sampler,
    }))
}
