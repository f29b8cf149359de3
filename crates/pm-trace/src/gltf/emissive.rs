//! glTF emissive textures: the material's `emissiveTexture` decoded through the shared
//! texture cache (one copy however many materials use it) and read at its `TEXCOORD_n`, with
//! `KHR_texture_transform` applied.

use std::collections::HashMap;
use std::path::Path;
use std::sync::Arc;

use gltf::json;

use super::GltfOptions;
use super::accessor::AccessorReader;
use super::buffers::Buffer;
use super::error::GltfError;
use super::image::load_texture;
use super::material::GltfMaterial;
use crate::emission::EmissionTexture;
use crate::texture::{Sampler, Texture};

/// Decoded textures by glTF texture index, shared by base-colour and emissive uses.
pub(super) type TextureCache = HashMap<usize, (Arc<Texture>, Sampler)>;

/// Where textures come from: the file, its JSON, its buffers and the loader's limits.
pub(super) struct TextureSources<'a> {
    pub(super) file: &'a Path,
    pub(super) root: &'a json::Root,
    pub(super) buffers: &'a [Buffer],
    pub(super) reader: &'a AccessorReader<'a>,
    pub(super) options: &'a GltfOptions,
}

/// Texture `texture` from the cache, else decoded (a broken or missing image is
/// [`GltfError::Image`]) and its bytes added to `scene_bytes`.
pub(super) fn cached_texture(
    sources: &TextureSources<'_>,
    cache: &mut TextureCache,
    texture: usize,
    scene_bytes: &mut u64,
) -> Result<(Arc<Texture>, Sampler), GltfError> {
    if let Some(t) = cache.get(&texture) {
        return Ok(t.clone());
    }
    let t = load_texture(
        sources.file,
        sources.root,
        sources.buffers,
        texture,
        sources.options,
    )?;
    *scene_bytes = scene_bytes.saturating_add(t.0.heap_bytes() as u64);
    cache.insert(texture, t.clone());
    Ok(t)
}

/// The emission texture of primitive `prim` (mesh and primitive indices `at`) with
/// `material`, read only when the material has an emissive texture *and* a non-zero
/// emission factor (glTF's `emissiveFactor` defaults to black, which no texture can
/// brighten: such a texture is not decoded, with a warning). A primitive without the named `TEXCOORD_n` set gets a warning and emits the
/// factor alone, as base-colour textures do.
pub(super) fn emission_texture(
    sources: &TextureSources<'_>,
    cache: &mut TextureCache,
    scene_bytes: &mut u64,
    warnings: &mut Vec<String>,
    at: (usize, usize),
    prim: &json::mesh::Primitive,
    material: &GltfMaterial,
) -> Result<Option<EmissionTexture>, GltfError> {
    let Some(reference) = material.emissive_texture else {
        return Ok(None);
    };
    let (texture, set) = (reference.index, reference.tex_coord);
    if material.emission.max_element() <= 0.0 {
        warnings.push(format!(
            "mesh {} primitive {}: emissive texture {texture} ignored under a black emission factor",
            at.0, at.1
        ));
        return Ok(None);
    }
    let Some(uvs) = reference.read_uvs(sources.reader, prim)? else {
        warnings.push(format!(
            "mesh {} primitive {}: no TEXCOORD_{set}, emissive texture ignored",
            at.0, at.1
        ));
        return Ok(None);
    };
    let (texture, sampler) = cached_texture(sources, cache, texture, scene_bytes)?;
    Ok(Some(EmissionTexture {
        uvs,
        texture,
        sampler,
    }))
}
