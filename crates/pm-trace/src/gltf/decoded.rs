//! A mesh primitive decoded once, in its mesh's own space, and placed by every node that
//! names it: its accessors are read, its material mapped and its textures looked up at the
//! first placement; each placement only transforms the vertices its triangles use.

use std::path::Path;
use std::sync::Arc;

use glam::{Mat4, Vec2, Vec3};
use gltf::json;
use gltf::json::extensions::texture::TextureTransform as JsonTransform;
use json::accessor::Type;
use json::mesh::Semantic;
use json::validation::Checked;

use super::accessor::AccessorReader;
use super::compact::{gather, keep_referenced};
use super::emissive::{TextureCache, TextureSources, cached_texture, emission_texture};
use super::error::GltfError;
use super::image::ImageRead;
use super::material::{GltfMaterial, map_material};
use super::material_textures::{material_textures, with_tangents};
use super::options::GltfOptions;
use super::primitive::{PrimitiveGeometry, read_primitive};
use crate::emission::EmissionTexture;
use crate::sampler::Sampler;
use crate::scene::material_texture::MaterialTexture;
use crate::scene::material_textures::MaterialTextures;
use crate::scene::normal_texture::NormalTexture;
use crate::texture::Texture;

/// A triangle primitive in its mesh's space, only the vertices its triangles use.
#[derive(Debug)]
pub(super) struct LocalPrimitive {
    pub(super) material_index: Option<usize>,
    pub(super) positions: Vec<Vec3>,
    pub(super) triangles: Vec<[u32; 3]>,
    pub(super) material: GltfMaterial,
    pub(super) uvs: Option<Vec<Vec2>>,
    pub(super) colors: Option<Vec<Vec3>>,
    /// Normals as the file gives them (transformed per placement).
    pub(super) normals: Option<Vec<Vec3>>,
    pub(super) base_color_texture: Option<(Arc<Texture>, Sampler)>,
    pub(super) emission_texture: Option<EmissionTexture>,
    pub(super) material_textures: MaterialTextures,
}

/// A texture with the sampler that reads it.
type SampledTexture = (Arc<Texture>, Sampler);

/// What a primitive decodes to.
#[derive(Clone, Debug)]
pub(super) enum Decoded {
    /// Triangles, shared by every placement.
    Triangles(Arc<LocalPrimitive>),
    /// Points or lines: nothing to render.
    NotTriangles,
    /// No `POSITION` attribute.
    NoPositions,
}

/// Decodes primitive `prim` (mesh and primitive indices `at`) in its mesh's space: positions
/// and triangles, the material, the base-colour and emissive textures (through `textures`,
/// their bytes added to `scene_bytes`), texture coordinates, colours and normals; then keeps
/// only the vertices the triangles use.
pub(super) fn decode_primitive(
    sources: &TextureSources<'_>,
    textures: &mut TextureCache,
    scene_bytes: &mut u64,
    warnings: &mut Vec<String>,
    at: (usize, usize),
    prim: &json::mesh::Primitive,
) -> Result<Decoded, GltfError> {
    let (file, root, reader, options) = (sources.file, sources.root, sources.reader, sources.options);
    let material_index = prim.material.map(|m| m.value());
    let json_material = json_material(file, root, at, material_index)?;
    let (positions, triangles) = match read_primitive(file, reader, at, prim, Mat4::IDENTITY)? {
        PrimitiveGeometry::Triangles { positions, triangles } => (positions, triangles),
        PrimitiveGeometry::NotTriangles => return Ok(Decoded::NotTriangles),
        PrimitiveGeometry::NoPositions => return Ok(Decoded::NoPositions),
    };
    let material = primitive_material(
        file,
        at,
        json_material,
        material_index,
        sources.normal_transforms,
        options,
    )?;
    let (base_color_texture, uvs) =
        base_color_texture(sources, textures, scene_bytes, warnings, at, prim, &material)?;
    let emission = emission_texture(sources, textures, scene_bytes, warnings, at, prim, &material)?;
    let material_textures = material_textures(sources, textures, scene_bytes, warnings, at, prim, &material)?;
    let colors = vertex_colors(reader, prim)?;
    let normals = vertex_normals(reader, prim)?;
    let n = positions.len();
    let mut lengths = vec![
        ("texture coordinates".to_string(), uvs.as_ref().map(Vec::len)),
        (
            "emissive texture coordinates".to_string(),
            emission.as_ref().map(|e| e.uvs.len()),
        ),
        ("colours".to_string(), colors.as_ref().map(Vec::len)),
        ("normals".to_string(), normals.as_ref().map(Vec::len)),
    ];
    for (name, texture) in material_textures.named() {
        lengths.push((
            format!("{name} texture coordinates"),
            texture.map(|t| t.uvs.len()),
        ));
    }
    check_attribute_lengths(file, at, n, &lengths)?;
    let material_textures = with_tangents(
        material_textures,
        (file, at),
        reader,
        prim,
        (&positions, &triangles),
        normals.as_deref(),
    )?;
    // Only the vertices the triangles use are kept (and later welded).
    let mut triangles = triangles;
    let kept = keep_referenced(&mut triangles, n);
    Ok(Decoded::Triangles(Arc::new(LocalPrimitive {
        material_index,
        positions: gather(&positions, &kept),
        triangles,
        material,
        uvs: uvs.map(|u| gather(&u, &kept)),
        colors: colors.map(|c| gather(&c, &kept)),
        normals: normals.map(|v| gather(&v, &kept)),
        base_color_texture,
        emission_texture: emission.map(|e| EmissionTexture {
            uvs: gather(&e.uvs, &kept),
            ..e
        }),
        material_textures: gather_textures(material_textures, &kept),
    })))
}

/// `textures` with every texture's coordinates and the normal map's tangents kept for the
/// vertices `kept` only.
fn gather_textures(textures: MaterialTextures, kept: &[u32]) -> MaterialTextures {
    let keep = |t: Option<MaterialTexture>| {
        t.map(|t| MaterialTexture {
            uvs: gather(&t.uvs, kept),
            ..t
        })
    };
    MaterialTextures {
        metallic_roughness: keep(textures.metallic_roughness),
        specular: keep(textures.specular),
        specular_color: keep(textures.specular_color),
        normal: textures.normal.map(|n| NormalTexture {
            map: keep(Some(n.map)).expect("a texture stays a texture"),
            tangents: gather(&n.tangents, kept),
            ..n
        }),
    }
}

/// [`GltfError::Primitive`] for primitive `at` (mesh and primitive indices) of `file`.
fn primitive_error(file: &Path, at: (usize, usize), reason: String) -> GltfError {
    GltfError::Primitive {
        file: file.to_path_buf(),
        mesh: at.0,
        primitive: at.1,
        reason,
    }
}

/// The material `material_index` of primitive `at` (mesh and primitive indices) names, if
/// any; a missing one fails.
fn json_material<'r>(
    file: &Path,
    root: &'r json::Root,
    at: (usize, usize),
    material_index: Option<usize>,
) -> Result<Option<&'r json::Material>, GltfError> {
    match material_index {
        Some(i) => Ok(Some(root.materials.get(i).ok_or_else(|| {
            primitive_error(
                file,
                at,
                format!(
                    "material {i} does not exist (the file has {})",
                    root.materials.len()
                ),
            )
        })?)),
        None => Ok(None),
    }
}

/// The library's material for `json_material` (material `material_index` of primitive `at`,
/// or glTF's default without one); an unsupported one fails naming the material.
fn primitive_material(
    file: &Path,
    at: (usize, usize),
    json_material: Option<&json::Material>,
    material_index: Option<usize>,
    normal_transforms: &[Option<JsonTransform>],
    options: &GltfOptions,
) -> Result<GltfMaterial, GltfError> {
    let normal_transform = material_index
        .and_then(|i| normal_transforms.get(i))
        .and_then(Option::as_ref);
    map_material(json_material, normal_transform, options).map_err(|reason| {
        primitive_error(
            file,
            at,
            match material_index {
                Some(i) => format!("material {i}: {reason}"),
                None => reason,
            },
        )
    })
}

/// Fails when an attribute of primitive `at` (named, with its length if present) does not
/// have one entry for each of its `n` positions.
fn check_attribute_lengths(
    file: &Path,
    at: (usize, usize),
    n: usize,
    lengths: &[(String, Option<usize>)],
) -> Result<(), GltfError> {
    for (what, len) in lengths {
        if let Some(len) = len.filter(|&len| len != n) {
            return Err(primitive_error(
                file,
                at,
                format!("{len} {what} for {n} positions"),
            ));
        }
    }
    Ok(())
}

/// The base-colour texture of `material` on primitive `prim` (indices `at`), loaded through
/// `textures` (its bytes added to `scene_bytes`), with the texture coordinates it reads. Without
/// those coordinates the texture is dropped, with a warning.
fn base_color_texture(
    sources: &TextureSources<'_>,
    textures: &mut TextureCache,
    scene_bytes: &mut u64,
    warnings: &mut Vec<String>,
    at: (usize, usize),
    prim: &json::mesh::Primitive,
    material: &GltfMaterial,
) -> Result<(Option<SampledTexture>, Option<Vec<Vec2>>), GltfError> {
    let Some(reference) = material.base_color_texture else {
        return Ok((None, None));
    };
    let loaded = cached_texture(sources, textures, reference.index, ImageRead::COLOUR, scene_bytes)?;
    let uvs = reference.read_uvs(sources.reader, prim)?;
    if uvs.is_some() {
        return Ok((Some(loaded), uvs));
    }
    let (mesh_index, primitive) = at;
    warnings.push(format!(
        "mesh {mesh_index} primitive {primitive}: no TEXCOORD_{}, base-colour texture ignored",
        reference.tex_coord
    ));
    Ok((None, uvs))
}

/// The accessor of attribute `semantic` of primitive `prim`, if it has one.
fn attribute(prim: &json::mesh::Primitive, semantic: Semantic) -> Option<usize> {
    prim.attributes.get(&Checked::Valid(semantic)).map(|a| a.value())
}

/// The vertex colours (`COLOR_0`) of primitive `prim`, if it has them.
fn vertex_colors(
    reader: &AccessorReader<'_>,
    prim: &json::mesh::Primitive,
) -> Result<Option<Vec<Vec3>>, GltfError> {
    match attribute(prim, Semantic::Colors(0)) {
        Some(a) => Ok(Some(reader.read_colors(a)?)),
        None => Ok(None),
    }
}

/// The vertex normals (`NORMAL`) of primitive `prim` as the file gives them, if it has them.
fn vertex_normals(
    reader: &AccessorReader<'_>,
    prim: &json::mesh::Primitive,
) -> Result<Option<Vec<Vec3>>, GltfError> {
    match attribute(prim, Semantic::Normals) {
        Some(a) => Ok(Some(
            reader
                .read_vec(a, &[Type::Vec3])?
                .iter()
                .map(|v| v.truncate())
                .collect::<Vec<Vec3>>(),
        )),
        None => Ok(None),
    }
}

impl LocalPrimitive {
    /// Triangles of one placement.
    pub(super) fn triangle_count(&self) -> usize {
        self.triangles.len()
    }

    /// The bytes one more placement takes: [`GltfOptions::BYTES_PER_VERTEX`] for each vertex
    /// kept and [`GltfOptions::BYTES_PER_TRIANGLE`] (and, for an emitter, its area light's
    /// share) for each triangle.
    pub(super) fn placement_bytes(&self) -> u64 {
        let per_triangle = if self.material.emission.max_element() > 0.0 {
            GltfOptions::BYTES_PER_TRIANGLE + GltfOptions::BYTES_PER_EMITTING_TRIANGLE
        } else {
            GltfOptions::BYTES_PER_TRIANGLE
        };
        (self.positions.len() as u64)
            .saturating_mul(GltfOptions::BYTES_PER_VERTEX)
            .saturating_add((self.triangles.len() as u64).saturating_mul(per_triangle))
    }
}
