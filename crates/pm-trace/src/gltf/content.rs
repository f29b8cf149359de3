//! A glTF file flattened into world space — triangles with materials, punctual lights and a
//! camera — independent of the scene type it is built into.

use std::path::Path;

use std::collections::HashMap;

use glam::Vec3;
use gltf::json;

use super::accessor::AccessorReader;
use super::buffers::{Buffer, resolve_buffers};
use super::camera::{GltfCamera, place_camera};
use super::decoded::{Decoded, decode_primitive};
use super::emissive::{TextureCache, TextureSources};
use super::error::GltfError;
use super::graph::{root_nodes, walk};
use super::light::{GltfLight, place_light};
use super::mesh::GltfMesh;
use super::options::GltfOptions;
use super::source::{guard, parse, read_bounded};

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
    let mut decoded_cache: HashMap<(usize, usize), Decoded> = HashMap::new();
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
                let at = (mesh_index, primitive);
                // The first placement decodes the accessors (counted from their declared
                // counts, before decoding); the others reuse the decode and count what they add.
                let bytes = match decoded_cache.get(&at) {
                    Some(Decoded::Triangles(local)) => local.placement_bytes(),
                    Some(_) => 0,
                    None => placement_bytes(root, prim, buffer_bytes),
                };
                scene_bytes = scene_bytes.saturating_add(bytes);
                if scene_bytes > options.max_scene_bytes {
                    return Err(GltfError::SceneTooLarge {
                        file: file.to_path_buf(),
                        node: p.index,
                        mesh: mesh_index,
                        budget: options.max_scene_bytes,
                        needed: scene_bytes,
                    });
                }
                let decoded = match decoded_cache.get(&at) {
                    Some(d) => d.clone(),
                    None => {
                        let d = decode_primitive(
                            &sources,
                            &mut textures,
                            &mut scene_bytes,
                            &mut content.warnings,
                            at,
                            prim,
                        )?;
                        decoded_cache.insert(at, d.clone());
                        d
                    }
                };
                match decoded {
                    Decoded::Triangles(local) => {
                        triangle_count += local.triangle_count() as u64;
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
                        content.meshes.push(local.place(file, p.index, at, p.world)?);
                    }
                    Decoded::NotTriangles => content.skipped_non_triangle += 1,
                    Decoded::NoPositions => content.skipped_without_positions += 1,
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
