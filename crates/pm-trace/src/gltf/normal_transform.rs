//! `KHR_texture_transform` on each material's `normalTexture`, read from the JSON text: the
//! gltf crate types the extension on `textureInfo` only (its untyped extension maps come with a
//! feature that buffers every object while parsing, past the loader's memory budget), so only
//! these fields of each material are parsed here, every other field skipped.

use std::path::Path;

use gltf::json::extensions::texture::TextureTransform as JsonTransform;
use serde::Deserialize;

use super::error::GltfError;

/// The document with only its materials' normal-texture transforms.
#[derive(Deserialize)]
struct MaterialsText {
    #[serde(default)]
    materials: Vec<MaterialText>,
}

#[derive(Deserialize)]
struct MaterialText {
    #[serde(rename = "normalTexture")]
    normal_texture: Option<NormalText>,
}

#[derive(Deserialize)]
struct NormalText {
    extensions: Option<NormalExtensions>,
}

#[derive(Deserialize)]
struct NormalExtensions {
    #[serde(rename = "KHR_texture_transform")]
    transform: Option<JsonTransform>,
}

/// Each material's normal-texture `KHR_texture_transform` (`None` where it has none), read
/// from `json` (the `.gltf` file's text or a GLB's JSON chunk) after the gltf crate parsed it
/// into `parsed_materials` materials. A different count, or an extension that is not a
/// `KHR_texture_transform` object, is [`GltfError::Parse`].
pub(super) fn read_normal_transforms(
    file: &Path,
    json: &[u8],
    parsed_materials: usize,
) -> Result<Vec<Option<JsonTransform>>, GltfError> {
    let refuse = |message: String| GltfError::Parse {
        file: file.to_path_buf(),
        message,
    };
    let text: MaterialsText = serde_json::from_slice(json)
        .map_err(|e| refuse(format!("reading the normal textures' KHR_texture_transform: {e}")))?;
    if text.materials.len() != parsed_materials {
        return Err(refuse(format!(
            "{} materials read again for their normal textures, {parsed_materials} parsed",
            text.materials.len()
        )));
    }
    Ok(text
        .materials
        .into_iter()
        .map(|m| {
            m.normal_texture
                .and_then(|n| n.extensions)
                .and_then(|e| e.transform)
        })
        .collect())
}
