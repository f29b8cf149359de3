//! Safe glTF 2.0 loading (`.gltf`, `.glb`) into a [`crate`] scene.
//!
//! Only the loader reads files, and only these: the scene file itself, and buffers given as
//! relative paths that stay inside the scene's folder after percent-decoding and
//! canonicalisation, each a regular file no larger than its declared `byteLength`. Buffers
//! may also be `data:` URIs or the GLB binary chunk. Absolute paths, `file:` and every other
//! scheme, escapes such as `..%2F`, invalid escapes such as `%FF`, and devices such as
//! `/dev/zero` are refused with a [`GltfError`] naming the file and the buffer. Images are
//! never read (textures are not used).
//!
//! The gltf crate panics on some malformed files; the loader checks what it can first (GLB
//! lengths, accessor and buffer-view bounds, indices) and runs every call into the crate
//! behind [`std::panic::catch_unwind`], reporting [`GltfError::Panic`]. No panic hook is
//! installed, so the process's hook may still print a message.
//!
//! # Mapping
//!
//! - **Geometry**: the default scene (else scene 0, else every root node) is walked with an
//!   explicit stack; a node reached twice (a cycle) or deeper than [`MAX_DEPTH`] is an
//!   error. Triangle lists, strips and fans are read; points and lines are skipped and
//!   counted ([`GltfContent::skipped_non_triangle`]).
//! - **Materials** ([`GltfMaterial`]): transmission ≥ 0.5 → glass (`KHR_materials_ior`,
//!   default 1.5); metallic ≥ 0.9 and roughness ≤ 0.1 → mirror with the base colour as
//!   reflectance; otherwise Lambertian with the base colour factor as albedo.
//! - **Emission**: `emissiveFactor × KHR_materials_emissive_strength ×`
//!   [`GltfOptions::emission_scale`] is the surface's radiance in W/(m²·sr) (glTF's
//!   nit-like units taken 1:1), and every emissive triangle becomes an area light.
//! - **Punctual lights** (`KHR_lights_punctual`): point and spot intensities in candela
//!   become radiant intensities in W/sr, directional illuminance in lux becomes irradiance in
//!   W/m², dividing by [`LUMENS_PER_WATT`] (683 lm/W, the efficacy of 555 nm light) and
//!   multiplying by [`GltfOptions::light_scale`] (files that store "watts-like" numbers want
//!   a scale of 683). Lights and cameras point down their node's −Z axis; `range` is ignored.
//! - **Camera**: the first perspective camera met in the walk; otherwise
//!   [`frame_bounds`] places one on the +z side looking along −z.
//!
//! # Example
//!
//! ```no_run
//! use pm_trace::gltf::{GltfOptions, read_content};
//! let content = read_content("scene.gltf".as_ref(), &GltfOptions::default())?;
//! println!("{} triangles, {} lights", content.triangle_count(), content.lights.len());
//! # Ok::<(), pm_trace::gltf::GltfError>(())
//! ```

mod accessor;
mod buffers;
mod camera;
mod content;
mod error;
mod graph;
mod light;
mod material;
mod primitive;
mod source;

pub use camera::{DEFAULT_VFOV, GltfCamera, frame_bounds};
pub use content::{GltfContent, GltfMesh, read_content};
pub use error::{BufferError, GltfError};
pub use graph::MAX_DEPTH;
pub use light::{GltfLight, LUMENS_PER_WATT};
pub use material::{GltfMaterial, SurfaceKind};

/// Knobs for loading a glTF file. `GltfOptions::default()` follows the glTF units.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct GltfOptions {
    /// Multiplies every punctual light's power after the photometric conversion (1 by
    /// default; 683 for files whose intensities are really watts).
    pub light_scale: f32,
    /// Multiplies every emissive surface's radiance (1 by default).
    pub emission_scale: f32,
    /// The largest scene file or buffer read, in bytes (1 GiB by default).
    pub max_file_bytes: u64,
    /// When the file has neither punctual lights nor emissive surfaces, add a point light at
    /// the camera (a "headlight") so the scene still renders (on by default).
    pub default_light: bool,
}

impl GltfOptions {
    /// The glTF units as written, a 1 GiB limit, a headlight for unlit files.
    pub const DEFAULT: Self = Self {
        light_scale: 1.0,
        emission_scale: 1.0,
        max_file_bytes: 1 << 30,
        default_light: true,
    };
}

impl Default for GltfOptions {
    fn default() -> Self {
        Self::DEFAULT
    }
}
