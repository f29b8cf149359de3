//! glTF material textures besides base colour and emission: the `metallicRoughnessTexture`
//! and `KHR_materials_specular`'s `specularTexture` (its alpha) and `specularColorTexture`,
//! and the `normalTexture` with its tangents (`TANGENT`, else MikkTSpace), each decoded through
//! the shared texture cache and read at its own `TEXCOORD_n`, with `KHR_texture_transform`.

use std::path::Path;

use glam::Vec3;
use gltf::json;
use json::accessor::Type;
use json::mesh::Semantic;
use json::validation::Checked;

use super::accessor::AccessorReader;
use super::emissive::{TextureCache, TextureSources, cached_texture};
use super::error::GltfError;
use super::image::ImageRead;
use super::material::GltfMaterial;
use super::texture_ref::TextureRef;
use crate::scene::material_texture::MaterialTexture;
use crate::scene::material_textures::MaterialTextures;
use crate::scene::normal_texture::{NormalTexture, mikktspace_tangents};

/// The material textures of primitive `prim` (mesh and primitive indices `at`) with
/// `material` (only those [`GltfMaterial`] keeps). A texture whose `TEXCOORD_n` set the
/// primitive lacks gets a warning and is left out, as base-colour textures are. The normal
/// map's tangents are left empty: [`with_tangents`] fills them once the attributes' lengths
/// are checked.
pub(super) fn material_textures(
    sources: &TextureSources<'_>,
    cache: &mut TextureCache,
    scene_bytes: &mut u64,
    warnings: &mut Vec<String>,
    at: (usize, usize),
    prim: &json::mesh::Primitive,
    material: &GltfMaterial,
) -> Result<MaterialTextures, GltfError> {
    let mut load = |reference: Option<TextureRef>, read: ImageRead, name: &str| {
        let Some(reference) = reference else {
            return Ok(None);
        };
        let Some(uvs) = reference.read_uvs(sources.reader, prim)? else {
            warnings.push(format!(
                "mesh {} primitive {}: no TEXCOORD_{}, {name} texture ignored",
                at.0, at.1, reference.tex_coord
            ));
            return Ok(None);
        };
        let (texture, sampler) = cached_texture(sources, cache, reference.index, read, scene_bytes)?;
        Ok::<_, GltfError>(Some(MaterialTexture {
            uvs,
            texture,
            sampler,
        }))
    };
    let metallic_roughness = load(
        material.metallic_roughness_texture,
        ImageRead::DATA,
        "metallic-roughness",
    )?;
    let specular = load(material.specular_texture, ImageRead::ALPHA_DATA, "specular")?;
    let specular_color = load(
        material.specular_color_texture,
        ImageRead::COLOUR,
        "specular colour",
    )?;
    let normal = match material.normal_texture {
        Some((reference, scale)) => {
            load(Some(reference), ImageRead::DATA, "normal")?.map(|map| NormalTexture {
                map,
                scale: if scale.is_finite() { scale } else { 1.0 },
                tangents: Vec::new(),
            })
        }
        None => None,
    };
    Ok(MaterialTextures {
        metallic_roughness,
        specular,
        specular_color,
        normal,
    })
}

/// `textures` with the normal map's tangents: the primitive's `TANGENT` where it has one and
/// `normals` too (glTF ignores tangents without normals), else MikkTSpace's over `positions`,
/// `triangles`, `normals` (flat without) and the map's texture coordinates. Every attribute
/// must already be checked to have one entry per position; `TANGENT` is checked here (a
/// mismatch is [`GltfError::Primitive`] for primitive `at` of `file`).
pub(super) fn with_tangents(
    mut textures: MaterialTextures,
    (file, at): (&Path, (usize, usize)),
    reader: &AccessorReader<'_>,
    prim: &json::mesh::Primitive,
    (positions, triangles): (&[Vec3], &[[u32; 3]]),
    normals: Option<&[Vec3]>,
) -> Result<MaterialTextures, GltfError> {
    let Some(normal) = &mut textures.normal else {
        return Ok(textures);
    };
    let given = match (normals, prim.attributes.get(&Checked::Valid(Semantic::Tangents))) {
        (Some(_), Some(accessor)) => Some(reader.read_vec(accessor.value(), &[Type::Vec4])?),
        _ => None,
    };
    normal.tangents = match given {
        Some(tangents) if tangents.len() != positions.len() => {
            return Err(GltfError::Primitive {
                file: file.to_path_buf(),
                mesh: at.0,
                primitive: at.1,
                reason: format!("{} tangents for {} positions", tangents.len(), positions.len()),
            });
        }
        Some(tangents) => tangents,
        None => mikktspace_tangents(positions, triangles, normals, &normal.map.uvs),
    };
    Ok(textures)
}
