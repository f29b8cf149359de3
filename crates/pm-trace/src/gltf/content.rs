//! A glTF file flattened into world space — triangles with materials, punctual lights and a
//! camera — independent of the scene type it is built into. Flattening takes two steps: the
//! walk decodes and places every primitive in f64 and grows the world bounds; then the origin
//! offset is chosen from those bounds ([`GltfContent::origin_offset`]) and every vertex,
//! camera and light is re-centred on it and rounded to f32.

use std::path::Path;

use std::collections::HashMap;

use glam::{DMat4, DVec3, Vec3};
use gltf::json;

use super::accessor::AccessorReader;
use super::buffers::{Buffer, resolve_buffers};
use super::camera::{GltfCamera, place_camera};
use super::decoded::{Decoded, LocalPrimitive, decode_primitive};
use super::emissive::{TextureCache, TextureSources};
use super::error::GltfError;
use super::graph::{PlacedNode, root_nodes, walk};
use super::light::{GltfLight, place_light};
use super::mesh::GltfMesh;
use super::node_transform::{NodeTransform, read_node_transforms};
use super::normal_transform::read_normal_transforms;
use super::options::GltfOptions;
use super::origin::WorldBounds;
use super::source::{guard, json_text, parse, read_bounded};
use gltf::json::extensions::texture::TextureTransform as JsonTransform;

/// A glTF file flattened into world space: what [`super::load_scene`] builds a scene from.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct GltfContent {
    /// Every triangle primitive reached from the scene, placed in the world (re-centred on
    /// [`Self::origin_offset`]).
    pub meshes: Vec<GltfMesh>,
    /// Every `KHR_lights_punctual` light reached from the scene.
    pub lights: Vec<GltfLight>,
    /// The first perspective camera reached from the scene, if any.
    pub camera: Option<GltfCamera>,
    /// The world point, in the file's metres and in f64, that the content's coordinates are
    /// relative to: a position `p` of a mesh, light or camera here is `origin_offset + p` in
    /// the file. The centre of the world bounds of every placed vertex when that centre lies
    /// farther from the file's origin than the bounds' largest side (a georeferenced model),
    /// else zero (nothing moved). The scene built from the content keeps it
    /// ([`Scene::origin_offset`](crate::Scene::origin_offset)).
    pub origin_offset: DVec3,
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
    // The gltf crate holds node transforms in f32; the walk composes them from the text.
    let transforms = read_node_transforms(path, json_text(&bytes), root.nodes.len())?;
    let normal_transforms = read_normal_transforms(path, json_text(&bytes), root.materials.len())?;
    drop(bytes);
    let buffers = resolve_buffers(path, &root, blob, options.max_file_bytes)?;
    let read_apart = (transforms.as_slice(), normal_transforms.as_slice());
    let mut content = guard(path, || flatten(path, &root, read_apart, &buffers, options))?;
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

/// Flattens the scene of `root` into world-space content: every node the scene reaches, in
/// walk order, placed by its `transforms` entry, adds its mesh's primitives, its camera (the
/// first one only) and its light.
fn flatten(
    file: &Path,
    root: &json::Root,
    (transforms, normal_transforms): (&[NodeTransform], &[Option<JsonTransform>]),
    buffers: &[Buffer],
    options: &GltfOptions,
) -> Result<GltfContent, GltfError> {
    let reader = AccessorReader::new(file, root, buffers);
    // The buffers are held while the scene is built from the content.
    let scene_bytes: u64 = buffers_held(buffers);
    let buffer_bytes: u64 = buffers.iter().map(|b| b.as_slice().len() as u64).sum();
    let roots = root_nodes(file, root)?;
    let placed = walk(file, root, transforms, &roots)?;
    let mut flattening = Flattening {
        sources: TextureSources {
            file,
            root,
            buffers,
            reader: &reader,
            options,
            normal_transforms,
        },
        buffer_bytes,
        scene_bytes,
        triangle_count: 0,
        textures: TextureCache::default(),
        decoded_cache: HashMap::new(),
        placements: Vec::new(),
        bounds: WorldBounds::default(),
        cameras: Vec::new(),
        lights: Vec::new(),
        content: GltfContent::default(),
    };
    for p in &placed {
        flattening.place_node(p)?;
    }
    flattening.finish()
}

/// A primitive placed by a node, kept until the origin offset is known.
struct Placement {
    node: usize,
    at: (usize, usize),
    world: DMat4,
    local: std::sync::Arc<LocalPrimitive>,
}

/// A node that holds a camera or a light (its index in the file's cameras or lights), kept
/// until the origin offset is known.
struct Placed {
    node: usize,
    index: usize,
    world: DMat4,
}

/// The content built so far from one file, with the budgets it has spent and the decodes and
/// textures later placements reuse.
struct Flattening<'a> {
    sources: TextureSources<'a>,
    /// Bytes of all the file's buffers: the most any accessor can claim.
    buffer_bytes: u64,
    /// Bytes the scene built from the content will take (checked against
    /// [`GltfOptions::max_scene_bytes`]).
    scene_bytes: u64,
    /// Triangles placed (checked against [`GltfOptions::max_triangles`]).
    triangle_count: u64,
    textures: TextureCache,
    /// Each primitive (mesh and primitive indices) decoded at its first placement.
    decoded_cache: HashMap<(usize, usize), Decoded>,
    /// Primitives placed, in walk order.
    placements: Vec<Placement>,
    /// Every placed vertex's world position, f64.
    bounds: WorldBounds,
    /// Nodes holding a camera, in walk order (the first perspective one is the camera).
    cameras: Vec<Placed>,
    /// Nodes holding a `KHR_lights_punctual` light, in walk order.
    lights: Vec<Placed>,
    content: GltfContent,
}

impl Flattening<'_> {
    /// Takes in what placed node `p` holds: its mesh's primitives (decoded and placed, their
    /// world bounds grown), its camera and its `KHR_lights_punctual` light (placed by
    /// [`Self::finish`]).
    fn place_node(&mut self, p: &PlacedNode) -> Result<(), GltfError> {
        let (file, root) = (self.sources.file, self.sources.root);
        let node = &root.nodes[p.index];
        if let Some(mesh_index) = node.mesh.map(|m| m.value()) {
            let mesh = root.meshes.get(mesh_index).ok_or_else(|| GltfError::Node {
                file: file.to_path_buf(),
                node: p.index,
                reason: format!(
                    "mesh {mesh_index} does not exist (the file has {})",
                    root.meshes.len()
                ),
            })?;
            for (primitive, prim) in mesh.primitives.iter().enumerate() {
                self.place_primitive(p, (mesh_index, primitive), prim)?;
            }
        }
        if let Some(camera) = node.camera.map(|c| c.value()) {
            self.cameras.push(Placed {
                node: p.index,
                index: camera,
                world: p.world,
            });
        }
        let light = node
            .extensions
            .as_ref()
            .and_then(|e| e.khr_lights_punctual.as_ref())
            .map(|l| l.light.value());
        if let Some(light) = light {
            self.lights.push(Placed {
                node: p.index,
                index: light,
                world: p.world,
            });
        }
        Ok(())
    }

    /// The content: the origin offset chosen from the world bounds, then every placed
    /// primitive, the first perspective camera and every light re-centred on it in f64 and
    /// rounded to f32.
    fn finish(mut self) -> Result<GltfContent, GltfError> {
        let (file, root, options) = (self.sources.file, self.sources.root, self.sources.options);
        let origin = self.bounds.origin_offset();
        let mut content = std::mem::take(&mut self.content);
        content.origin_offset = origin;
        content.meshes.reserve_exact(self.placements.len());
        for p in self.placements.drain(..) {
            content
                .meshes
                .push(p.local.place(file, p.node, p.at, p.world, origin)?);
        }
        for c in &self.cameras {
            content.camera = place_camera(file, root, c.node, c.index, c.world, origin)?;
            if content.camera.is_some() {
                break;
            }
        }
        for l in &self.lights {
            let light = place_light(file, root, l.node, l.index, l.world, origin, options)?;
            content.lights.push(light);
        }
        Ok(content)
    }

    /// Places primitive `prim` (mesh and primitive indices `at`) with node `p`: its bytes
    /// charged to the budget, decoded once, its triangles counted against
    /// [`GltfOptions::max_triangles`] and placed in the world (or counted as skipped).
    fn place_primitive(
        &mut self,
        p: &PlacedNode,
        at: (usize, usize),
        prim: &json::mesh::Primitive,
    ) -> Result<(), GltfError> {
        let (file, options) = (self.sources.file, self.sources.options);
        self.charge_placement(p, at, prim)?;
        match self.decode_once(at, prim)? {
            Decoded::Triangles(local) => {
                self.triangle_count += local.triangle_count() as u64;
                if self.triangle_count > options.max_triangles {
                    return Err(GltfError::Node {
                        file: file.to_path_buf(),
                        node: p.index,
                        reason: format!(
                            "the scene places more than {} triangles (GltfOptions::max_triangles)",
                            options.max_triangles
                        ),
                    });
                }
                local.add_world_bounds(p.world, &mut self.bounds);
                self.placements.push(Placement {
                    node: p.index,
                    at,
                    world: p.world,
                    local,
                });
            }
            Decoded::NotTriangles => self.content.skipped_non_triangle += 1,
            Decoded::NoPositions => self.content.skipped_without_positions += 1,
        }
        Ok(())
    }

    /// Adds the bytes one more placement of primitive `prim` (indices `at`) by node `p` takes to
    /// the scene's bytes, and fails with [`GltfError::SceneTooLarge`] past the budget. The
    /// first placement is counted from the accessors' declared counts, before decoding; the
    /// others from the decode they reuse.
    fn charge_placement(
        &mut self,
        p: &PlacedNode,
        at: (usize, usize),
        prim: &json::mesh::Primitive,
    ) -> Result<(), GltfError> {
        let bytes = match self.decoded_cache.get(&at) {
            Some(Decoded::Triangles(local)) => local.placement_bytes(),
            Some(_) => 0,
            None => placement_bytes(self.sources.root, prim, self.buffer_bytes),
        };
        self.scene_bytes = self.scene_bytes.saturating_add(bytes);
        if self.scene_bytes > self.sources.options.max_scene_bytes {
            return Err(GltfError::SceneTooLarge {
                file: self.sources.file.to_path_buf(),
                node: p.index,
                mesh: at.0,
                budget: self.sources.options.max_scene_bytes,
                needed: self.scene_bytes,
            });
        }
        Ok(())
    }

    /// Primitive `prim` (indices `at`) decoded: from the cache, else decoded now (its warnings
    /// added to the content's, its textures' bytes to the scene's) and cached.
    fn decode_once(
        &mut self,
        at: (usize, usize),
        prim: &json::mesh::Primitive,
    ) -> Result<Decoded, GltfError> {
        if let Some(d) = self.decoded_cache.get(&at) {
            return Ok(d.clone());
        }
        let d = decode_primitive(
            &self.sources,
            &mut self.textures,
            &mut self.scene_bytes,
            &mut self.content.warnings,
            at,
            prim,
        )?;
        self.decoded_cache.insert(at, d.clone());
        Ok(d)
    }
}
