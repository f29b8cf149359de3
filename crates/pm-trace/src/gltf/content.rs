//! A glTF file flattened into world space — triangles with materials, punctual lights and a
//! camera — independent of the scene type it is built into.

use std::path::Path;

use std::sync::Arc;

use glam::{Mat3, Vec2, Vec3};
use gltf::json;

use super::GltfOptions;
use super::accessor::AccessorReader;
use super::buffers::{Buffer, resolve_buffers};
use super::camera::{GltfCamera, place_camera};
use super::compact::{gather, keep_referenced};
use super::emissive::{TextureCache, TextureSources, cached_texture, emission_texture};
use super::error::GltfError;
use super::graph::{root_nodes, walk};
use super::light::{GltfLight, place_light};
use super::material::{GltfMaterial, map_material};
use super::primitive::{PrimitiveGeometry, read_primitive};
use super::source::{guard, parse, read_bounded};
use crate::emission::EmissionTexture;
use crate::texture::{Sampler, Texture};

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
    /// World-space vertex positions in metres.
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
}

/// A glTF file flattened into world space: what [`super::load_scene`] builds a scene from.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct GltfContent {
    /// Every triangle primitive reached from the scene, placed in the world.
    pub meshes: Vec<GltfMesh>,
    /// Every `KHR_lights_punctual` light reached from the scene.
    pub lights: Vec<GltfLight>,
    /// The first perspective camera reached from the scene, if any.
    pub camera: Option<GltfCamera>,
    /// Primitives skipped because they are points or lines.
    pub skipped_non_triangle: usize,
    /// Primitives skipped because they have no `POSITION` attribute.
    pub skipped_without_positions: usize,
    /// Things ignored that a user may want to know about (for example a texture that names
    /// a missing image but that no material uses).
    pub warnings: Vec<String>,
}

impl GltfContent {
    /// The bounds `(min, max)` of every vertex, `None` without geometry.
    pub fn bounds(&self) -> Option<(Vec3, Vec3)> {
        let mut points = self.meshes.iter().flat_map(|m| m.positions.iter().copied());
        let first = points.next()?;
        Some(points.fold((first, first), |(lo, hi), p| (lo.min(p), hi.max(p))))
    }

    /// Number of triangles over all meshes.
    pub fn triangle_count(&self) -> usize {
        self.meshes.iter().map(|m| m.triangles.len()).sum()
    }
}

/// Reads `path` (`.gltf` or `.glb`) into world-space content without building a scene.
/// Every call into the gltf crate runs behind a panic guard (see [`GltfError::Panic`]).
pub fn read_content(path: &Path, options: &GltfOptions) -> Result<GltfContent, GltfError> {
    let bytes = read_bounded(path, options.max_file_bytes)?;
    let (root, blob, warnings) = parse(path, &bytes)?;
    drop(bytes);
    let buffers = resolve_buffers(path, &root, blob, options.max_file_bytes)?;
    let mut content = guard(path, || flatten(path, &root, &buffers, options))?;
    content.warnings.splice(0..0, warnings);
    Ok(content)
}

/// Bytes held by the distinct buffers (entries sharing one file or chunk counted once).
fn buffers_held(buffers: &[Buffer]) -> u64 {
    let mut seen = std::collections::HashSet::new();
    buffers
        .iter()
        .filter(|b| seen.insert(b.identity()))
        .map(|b| b.held() as u64)
        .sum()
}

/// The bytes one placement of primitive `prim` will take, from its accessors' declared counts
/// (nothing decoded yet): [`GltfOptions::BYTES_PER_VERTEX`] for every vertex decoded and
/// [`GltfOptions::BYTES_PER_TRIANGLE`] for every triangle it can make. Counts are capped by
/// what `buffer_bytes` can hold (12 bytes a position, 1 an index): an accessor that claims
/// more, or does not exist, fails with its own error when read.
fn placement_bytes(root: &json::Root, prim: &json::mesh::Primitive, buffer_bytes: u64) -> u64 {
    use json::mesh::{Mode, Semantic};
    use json::validation::Checked;
    let count = |a: usize| root.accessors.get(a).map_or(0, |a| a.count.0);
    let Some(position) = prim.attributes.get(&Checked::Valid(Semantic::Positions)) else {
        return 0;
    };
    let vertices = count(position.value()).min(buffer_bytes / 12);
    let indices = prim
        .indices
        .map_or(vertices, |i| count(i.value()).min(buffer_bytes));
    let triangles = match prim.mode {
        Checked::Valid(Mode::Triangles) => indices / 3,
        Checked::Valid(Mode::TriangleStrip | Mode::TriangleFan) => indices.saturating_sub(2),
        _ => 0,
    };
    // An emissive primitive is also an area light holding its triangles again.
    let emits = prim
        .material
        .and_then(|m| root.materials.get(m.value()))
        .is_some_and(|m| m.emissive_factor.0.iter().any(|&c| c > 0.0));
    let per_triangle = if emits {
        GltfOptions::BYTES_PER_TRIANGLE + GltfOptions::BYTES_PER_EMITTING_TRIANGLE
    } else {
        GltfOptions::BYTES_PER_TRIANGLE
    };
    vertices
        .saturating_mul(GltfOptions::BYTES_PER_VERTEX)
        .saturating_add(triangles.saturating_mul(per_triangle))
}

use json::accessor::Type;
use json::mesh::Semantic;
use json::validation::Checked;

fn flatten(
    file: &Path,
    root: &json::Root,
    buffers: &[Buffer],
    options: &GltfOptions,
) -> Result<GltfContent, GltfError> {
    let reader = AccessorReader::new(file, root, buffers);
    // The buffers are held while the scene is built from the content.
    let mut scene_bytes: u64 = buffers_held(buffers);
    let buffer_bytes: u64 = buffers.iter().map(|b| b.as_slice().len() as u64).sum();
    let roots = root_nodes(file, root)?;
    let placed = walk(file, root, &roots)?;
    let mut content = GltfContent::default();
    let mut triangle_count = 0u64;
    let mut textures = TextureCache::default();
    let sources = TextureSources {
        file,
        root,
        buffers,
        reader: &reader,
        options,
    };
    for p in &placed {
        let node = &root.nodes[p.index];
        let missing = |what: &str, index: usize, len: usize| GltfError::Node {
            file: file.to_path_buf(),
            node: p.index,
            reason: format!("{what} {index} does not exist (the file has {len})"),
        };
        if let Some(mesh_index) = node.mesh.map(|m| m.value()) {
            let mesh = root
                .meshes
                .get(mesh_index)
                .ok_or_else(|| missing("mesh", mesh_index, root.meshes.len()))?;
            for (primitive, prim) in mesh.primitives.iter().enumerate() {
                let material_index = prim.material.map(|m| m.value());
                let material = match material_index {
                    Some(i) => Some(root.materials.get(i).ok_or_else(|| GltfError::Primitive {
                        file: file.to_path_buf(),
                        mesh: mesh_index,
                        primitive,
                        reason: format!(
                            "material {i} does not exist (the file has {})",
                            root.materials.len()
                        ),
                    })?),
                    None => None,
                };
                // Every placement decodes its vertices again: count them, before decoding.
                scene_bytes = scene_bytes.saturating_add(placement_bytes(root, prim, buffer_bytes));
                if scene_bytes > options.max_scene_bytes {
                    return Err(GltfError::SceneTooLarge {
                        file: file.to_path_buf(),
                        node: p.index,
                        mesh: mesh_index,
                        budget: options.max_scene_bytes,
                        needed: scene_bytes,
                    });
                }
                match read_primitive(file, &reader, (mesh_index, primitive), prim, p.world)? {
                    PrimitiveGeometry::Triangles { positions, triangles } => {
                        // Each placement decodes its accessors again: count what instancing adds.
                        triangle_count += triangles.len() as u64;
                        if triangle_count > options.max_triangles {
                            return Err(GltfError::Node {
                                file: file.to_path_buf(),
                                node: p.index,
                                reason: format!(
                                    "the scene places more than {} triangles (GltfOptions::max_triangles)",
                                    options.max_triangles
                                ),
                            });
                        }
                        let material =
                            map_material(material, options).map_err(|reason| GltfError::Primitive {
                                file: file.to_path_buf(),
                                mesh: mesh_index,
                                primitive,
                                reason: match material_index {
                                    Some(i) => format!("material {i}: {reason}"),
                                    None => reason,
                                },
                            })?;
                        let attribute = |semantic: Semantic| {
                            prim.attributes.get(&Checked::Valid(semantic)).map(|a| a.value())
                        };
                        let n = positions.len();
                        let mut base_color_texture = None;
                        let mut uvs: Option<Vec<Vec2>> = None;
                        if let Some(reference) = material.base_color_texture {
                            let texture = reference.index;
                            let loaded = cached_texture(&sources, &mut textures, texture, &mut scene_bytes)?;
                            uvs = reference.read_uvs(&reader, prim)?;
                            if uvs.is_some() {
                                base_color_texture = Some(loaded);
                            } else {
                                content.warnings.push(format!(
                                    "mesh {mesh_index} primitive {primitive}: no TEXCOORD_{}, base-colour texture ignored",
                                    reference.tex_coord
                                ));
                            }
                        }
                        let emission_texture = emission_texture(
                            &sources,
                            &mut textures,
                            &mut scene_bytes,
                            &mut content.warnings,
                            (mesh_index, primitive),
                            prim,
                            &material,
                        )?;
                        let colors = match attribute(Semantic::Colors(0)) {
                            Some(a) => Some(reader.read_colors(a)?),
                            None => None,
                        };
                        let normals = match attribute(Semantic::Normals) {
                            Some(a) => {
                                let to_world = Mat3::from_mat4(p.world).inverse().transpose();
                                Some(
                                    reader
                                        .read_vec(a, &[Type::Vec3])?
                                        .iter()
                                        .map(|v| {
                                            (to_world * v.truncate()).try_normalize().unwrap_or(Vec3::ZERO)
                                        })
                                        .collect::<Vec<Vec3>>(),
                                )
                            }
                            None => None,
                        };
                        let wrong = |what: &str, len: usize| GltfError::Primitive {
                            file: file.to_path_buf(),
                            mesh: mesh_index,
                            primitive,
                            reason: format!("{len} {what} for {n} positions"),
                        };
                        if let Some(u) = &uvs
                            && u.len() != n
                        {
                            return Err(wrong("texture coordinates", u.len()));
                        }
                        if let Some(e) = &emission_texture
                            && e.uvs.len() != n
                        {
                            return Err(wrong("emissive texture coordinates", e.uvs.len()));
                        }
                        if let Some(c) = &colors
                            && c.len() != n
                        {
                            return Err(wrong("colours", c.len()));
                        }
                        if let Some(v) = &normals
                            && v.len() != n
                        {
                            return Err(wrong("normals", v.len()));
                        }
                        // Only the vertices the triangles use are kept (and later welded).
                        let mut triangles = triangles;
                        let kept = keep_referenced(&mut triangles, n);
                        let positions = gather(&positions, &kept);
                        let uvs = uvs.map(|u| gather(&u, &kept));
                        let colors = colors.map(|c| gather(&c, &kept));
                        let normals = normals.map(|v| gather(&v, &kept));
                        let emission_texture = emission_texture.map(|e| EmissionTexture {
                            uvs: gather(&e.uvs, &kept),
                            ..e
                        });
                        content.meshes.push(GltfMesh {
                            node: p.index,
                            mesh: mesh_index,
                            primitive,
                            material_index,
                            positions,
                            triangles,
                            material,
                            uvs,
                            colors,
                            normals,
                            base_color_texture,
                            emission_texture,
                        })
                    }
                    PrimitiveGeometry::NotTriangles => content.skipped_non_triangle += 1,
                    PrimitiveGeometry::NoPositions => content.skipped_without_positions += 1,
                }
            }
        }
        if let Some(camera) = node.camera.map(|c| c.value())
            && content.camera.is_none()
        {
            content.camera = place_camera(file, root, p.index, camera, p.world)?;
        }
        let light = node
            .extensions
            .as_ref()
            .and_then(|e| e.khr_lights_punctual.as_ref())
            .map(|l| l.light.value());
        if let Some(light) = light {
            content
                .lights
                .push(place_light(file, root, p.index, light, p.world, options)?);
        }
    }
    Ok(content)
}
