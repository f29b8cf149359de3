//! What a caller may set when loading a glTF file: units, scales, and the bounds on bytes,
//! triangles and texels that keep a hostile file from exhausting memory.

use super::units::LightUnits;

/// Knobs for loading a glTF file. `GltfOptions::default()` follows the glTF units.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct GltfOptions {
    /// How emissive strength and punctual intensities become watts ([`LightUnits::Mixed`] by
    /// default, as the loader always read them; [`LightUnits::Photometric`] or
    /// [`LightUnits::Viewer`] for files authored in one system of units, so that emitters
    /// and lamps keep their ratio).
    pub light_units: LightUnits,
    /// Multiplies every punctual light's power after the [`Self::light_units`] conversion (1
    /// by default; 683 for files whose intensities are really watts).
    pub light_scale: f32,
    /// Multiplies every emissive surface's radiance after the [`Self::light_units`]
    /// conversion (1 by default).
    pub emission_scale: f32,
    /// The largest scene file read, and the most bytes read for all buffers together (each
    /// distinct file read once however many `buffers` entries name it), in bytes (1 GiB by
    /// default).
    pub max_file_bytes: u64,
    /// When the file has neither punctual lights nor emissive surfaces, add a point light at
    /// the camera (a "headlight") so the scene still renders (on by default).
    pub default_light: bool,
    /// The most triangles the scene may hold after instancing (20 million by default). A built
    /// scene holds 80–94 bytes per triangle (mesh, triangles, BVH; see `Scene::heap_bytes`),
    /// about 1.9 GB at this limit, and building it peaks near 400 bytes per triangle (the
    /// binary BVH and its 8-wide conversion), about 8 GB; photon maps come on top. Many nodes
    /// may place the same mesh, so a small file can describe a huge scene; past this limit
    /// loading stops with an error instead of exhausting memory.
    pub max_triangles: u64,
    /// The most bytes loading may take (4 GiB by default): the buffers held, plus
    /// [`Self::BYTES_PER_VERTEX`] for every vertex decoded and [`Self::BYTES_PER_TRIANGLE`] for
    /// every triangle, and the decoded images (each checked from its header before it is
    /// decoded). A primitive is decoded once, at its first placement, counted from its
    /// accessors' declared counts *before* decoding; it keeps only the vertices its triangles
    /// use, and every further placement counts those and its triangles. Past the budget
    /// loading stops with [`GltfError::SceneTooLarge`](super::GltfError::SceneTooLarge) (an image, [`GltfError::Image`](super::GltfError::Image)).
    pub max_scene_bytes: u64,
    /// The most texels one image may have (2²⁶ = 8192 × 8192 by default, 3 bytes a texel
    /// once decoded). Checked from the image's header before its pixels are allocated.
    pub max_texture_pixels: u64,
}

impl GltfOptions {
    /// The glTF units as written, a 1 GiB file limit, 20 million triangles, a 4 GiB scene
    /// budget, a headlight for unlit files.
    pub const DEFAULT: Self = Self {
        light_units: LightUnits::Mixed,
        light_scale: 1.0,
        emission_scale: 1.0,
        max_file_bytes: 1 << 30,
        default_light: true,
        max_triangles: 20_000_000,
        max_scene_bytes: 4 << 30,
        max_texture_pixels: 1 << 26,
    };

    /// Bytes counted per decoded vertex against [`Self::max_scene_bytes`]: its world position
    /// in the loaded content (12), the copy the scene builder takes (12), and the half-edge
    /// mesh's vertex and welding tables, rounded up (measured in `tests/gltf_budget.rs`).
    pub const BYTES_PER_VERTEX: u64 = 64;

    /// Bytes counted per triangle against [`Self::max_scene_bytes`]: the peak while the scene
    /// is built (about 370–400 bytes a triangle: half-edges, the BVH builder's work arrays and
    /// the compressed BVH, measured in `tests/scene_memory.rs`), plus the content's index
    /// triple (12), rounded up. The built scene keeps about 80–90 bytes a triangle.
    pub const BYTES_PER_TRIANGLE: u64 = 450;

    /// Bytes counted, on top of [`Self::BYTES_PER_TRIANGLE`], per triangle of an emissive
    /// primitive, which is also an area light: its corners (36), a frame (36) and a cumulative
    /// area (4), and with an emissive texture its corners' texture coordinates (24) and mean
    /// emission (4), rounded up.
    pub const BYTES_PER_EMITTING_TRIANGLE: u64 = 112;
}

impl Default for GltfOptions {
    fn default() -> Self {
        Self::DEFAULT
    }
}
