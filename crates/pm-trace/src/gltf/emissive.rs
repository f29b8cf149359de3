//! glTF emissive textures: the material's `emissiveTexture` decoded through the shared
//! texture cache (one copy however many materials use it) and read at its `TEXCOORD_n`, with
//! `KHR_texture_transform` applied.

use std::collections::HashMap;
use std::path::Path;
use std::sync::Arc;

use gltf::json;

use super::accessor::AccessorReader;
use super::buffers::Buffer;
use super::error::GltfError;
use super::image::{ImageRead, load_image, texture_source};
use super::material::GltfMaterial;
use super::options::GltfOptions;
use crate::emission::EmissionTexture;
use crate::sampler::Sampler;
use crate::texture::{TexelEncoding, Texture};

/// Decoded images by glTF image index and how they are read (each decoded once however many
/// textures name it, and once more only if one material reads it as colour and another as
/// data, or its alpha) and the textures made of them, by texture index and read.
#[derive(Default)]
pub(super) struct TextureCache {
    images: HashMap<(usize, ImageRead), Arc<Texture>>,
    textures: HashMap<(usize, ImageRead), (Arc<Texture>, Sampler)>,
}

/// Where textures come from: the file, its JSON, its buffers and the loader's limits.
pub(super) struct TextureSources<'a> {
    pub(super) file: &'a Path,
    pub(super) root: &'a json::Root,
    pub(super) buffers: &'a [Buffer],
    pub(super) reader: &'a AccessorReader<'a>,
    pub(super) options: &'a GltfOptions,
    /// Each material's normal-texture `KHR_texture_transform`, read apart from the JSON text.
    pub(super) normal_transforms: &'a [Option<json::extensions::texture::TextureTransform>],
}

/// Texture `texture` read as `read` says (channels; sRGB for colour, linear for data) from the cache,
/// else its image from the image cache, else decoded (a broken, missing or too large image is
/// [`GltfError::Image`]; the decode is checked against what `scene_bytes` leaves of
/// [`GltfOptions::max_scene_bytes`] from the image's header before it starts) and its bytes
/// added to `scene_bytes`.
pub(super) fn cached_texture(
    sources: &TextureSources<'_>,
    cache: &mut TextureCache,
    texture: usize,
    read: ImageRead,
    scene_bytes: &mut u64,
) -> Result<(Arc<Texture>, Sampler), GltfError> {
    if let Some(t) = cache.textures.get(&(texture, read)) {
        return Ok(t.clone());
    }
    let (image, sampler) = texture_source(sources.file, sources.root, texture)?;
    let decoded = match cache.images.get(&(image, read)) {
        Some(decoded) => decoded.clone(),
        None => {
            let budget = sources.options.max_scene_bytes.saturating_sub(*scene_bytes);
            let srgb = load_image(
                sources.file,
                sources.root,
                sources.buffers,
                (image, read.channels),
                sources.options,
                budget,
            )?;
            let decoded = Arc::new(match read.encoding {
                TexelEncoding::Srgb => srgb,
                TexelEncoding::Linear => srgb.with_encoding(TexelEncoding::Linear),
            });
            *scene_bytes = scene_bytes.saturating_add(decoded.heap_bytes() as u64);
            cache.images.insert((image, read), decoded.clone());
            decoded
        }
    };
    cache.textures.insert((texture, read), (decoded.clone(), sampler));
    Ok((decoded, sampler))
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
    let (texture, sampler) = cached_texture(sources, cache, texture, ImageRead::COLOUR, scene_bytes)?;
    Ok(Some(EmissionTexture {
        uvs,
        texture,
        sampler,
    }))
}
