//! Safe glTF 2.0 loading (`.gltf`, `.glb`) into a [`Scene`]: [`load_scene`] or
//! [`load_scene_with`]; [`read_content`] gives the flattened file without building a scene.
//!
//! # What is read, and what is refused
//!
//! Only the scene file itself, and buffers given as relative paths that stay inside the
//! scene's folder after percent-decoding and canonicalisation (symbolic links included), each
//! a regular file no larger than its declared `byteLength` (at most `byteLength + 1` bytes are
//! ever read). Buffers may also be `data:` URIs or the GLB binary chunk. Absolute paths,
//! `file:` and every other scheme, escapes such as `..%2F`, invalid escapes such as `%FF`,
//! and devices such as `/dev/zero` are refused with a [`GltfError`] naming the file and the
//! buffer. A GLB container's length fields are checked against the file before parsing.
//! Images are read only for base-colour, metallic-roughness and emissive textures that a placed
//! mesh's material uses (an emissive one only under a non-zero `emissiveFactor`, a
//! metallic-roughness one only for a metallic-roughness material), through
//! the same resolver (buffer views, `data:` URIs, files in the folder), and decoded only as
//! PNG or JPEG (`zune-jpeg`), refused from the header when larger than
//! [`GltfOptions::max_texture_pixels`]; each is decoded once however many materials share
//! it (twice if one reads it as colour and another as data). Memory is bounded: no accessor may describe
//! more bytes than the file's buffers hold, each buffer file is read once and all buffers
//! together hold at most [`GltfOptions::max_file_bytes`], and the instanced scene may hold at
//! most [`GltfOptions::max_triangles`] triangles and take at most
//! [`GltfOptions::max_scene_bytes`] (counted before decoding; many nodes may place one mesh).
//! The scene file and every buffer file must be regular files, checked before they are
//! opened (a FIFO would block).
//!
//! The gltf crate panics on some malformed files; the loader checks what it can first (GLB
//! lengths, `POSITION` accessor indices, accessor and buffer-view bounds, vertex indices)
//! and runs every call into the crate behind [`std::panic::catch_unwind`], reporting
//! [`GltfError::Panic`]. No panic hook is installed, so the process's hook may still print.
//!
//! # Mapping
//!
//! - **Geometry**: the default scene (else scene 0, else every root node) is walked with an
//!   explicit stack; a node reached twice (a cycle) or deeper than [`MAX_DEPTH`] is an error.
//!   World transforms compose `matrix` (column-major) or translation × rotation × scale, in
//!   f64 (see *Placement* below).
//!   Triangle lists, strips and fans are read, each primitive becoming one scene mesh;
//!   points and lines are skipped and counted ([`GltfContent::skipped_non_triangle`]).
//!   Non-finite positions and out-of-range indices are errors.
//! - **Materials** ([`GltfMaterial`]), glTF 2.0's Appendix B factor for factor:
//!
//!   | the file says | the renderer's material |
//!   |---|---|
//!   | `(1 − metallicFactor) × KHR_materials_transmission ≥ 0.5` | [`Material::Glass`](crate::material::Material::Glass) with `KHR_materials_ior` (1.5 without it or below 1): smooth and colourless whatever its roughness, base colour and transmission below one — an approximation (no rough or partly transmitting dielectric yet) |
//!   | `metallicFactor` 0 and `KHR_materials_specular`'s `specularFactor` 0 | [`Material::Lambertian`](crate::material::Material::Lambertian) of the base colour (Appendix B is then exactly `baseColor/π`; renders bit-identically to a hand-made Lambertian) |
//!   | anything else, glTF's default material (white, metallic 1, roughness 1: a rough white metal) included | [`Material::MetallicRoughness`](crate::material::Material::MetallicRoughness): `baseColorFactor`, `metallicFactor`, `roughnessFactor`, `KHR_materials_ior` (0 allowed, as the extension says) and `KHR_materials_specular`'s `specularFactor` and `specularColorFactor` |
//!
//!   No threshold turns a metal into a mirror or a rough surface into Lambert. At roughness 0
//!   the material stays GGX at [`MIN_ALPHA`](crate::bsdf::MIN_ALPHA) (a 0.06° lobe, sampled):
//!   [`Material::Mirror`](crate::material::Material::Mirror)'s constant reflectance is not the
//!   limit of Appendix B (which keeps Schlick's Fresnel, brighter towards grazing), and a
//!   roughness texture may vary it per point; the render core decides how to follow very sharp
//!   lobes. Out-of-range factors are clamped as viewers do (colours and metallic, roughness,
//!   transmission and specular to `[0, 1]`, the specular colour to non-negative).
//!
//!   Textures (PNG or JPEG, at the material's `TEXCOORD_n`, with its sampler's wrap modes,
//!   bilinear, and `KHR_texture_transform`'s offset, rotation, scale and `texCoord` applied to
//!   the coordinates: [`TextureRef`]): the base-colour texture (sRGB decoded to linear) and
//!   `COLOR_0` multiply the base colour at each hit ([`Scene::albedo_at`], and
//!   [`ShadingPoint::tint`](crate::bsdf::ShadingPoint::tint) for every BSDF); the
//!   `metallicRoughnessTexture` (linear values: blue multiplies `metallicFactor`, green
//!   `roughnessFactor`) reaches [`MetallicRoughness`](crate::bsdf::MetallicRoughness) through
//!   [`ShadingPoint::factors`](crate::bsdf::ShadingPoint::factors) at each hit, as do
//!   `KHR_materials_specular`'s `specularTexture` (its alpha channel, linear, multiplies
//!   `specularFactor`; an image without alpha reads as 1) and `specularColorTexture` (sRGB,
//!   multiplies `specularColorFactor`); the emissive texture is read for emission (below).
//!   The `normalTexture` (linear, times its `scale` in x and y) bends the shading normal
//!   ([`NormalTexture`](crate::NormalTexture)) in the frame of the primitive's `TANGENT` where
//!   it has one and `NORMAL` too, else of MikkTSpace tangents made at load
//!   ([`mikktspace_tangents`](crate::mikktspace_tangents), with glTF's sign convention), for
//!   every material kind; a mapped normal is kept at least
//!   [`MIN_MAPPED_COSINE`](crate::MIN_MAPPED_COSINE) above the geometric surface, and no ray
//!   leaves below it (see [`Scene::shading_normal_at`](crate::Scene::shading_normal_at)). The map shapes whatever reads the
//!   shading normal: shadow rays, BSDF lobes, the path tracer, mirror and glass bounces and
//!   photons read through a glossy BSDF; a diffuse photon estimate reads the flux through the
//!   geometric surface and is not changed by it. **Not read**: the occlusion texture
//!   (ambient occlusion is what the renderer computes) and `KHR_materials_transmission`'s
//!   texture. Each texture keeps a
//!   box-filtered mip chain: the photon-map and shadow-ray modes average it over the camera
//!   pixel's footprint ([`Scene::albedo_over`]), so a texture seen from afar does not alias;
//!   photon tracing, the path tracer and the progressive modes look textures up at points
//!   (their many samples average them). `NORMAL` gives smooth shading normals
//!   ([`Scene::shading_normal_at`]), used for the cosine terms, the glossy lobes and mirror
//!   and glass bounces. A texture naming a missing image that no material uses is a warning in
//!   [`GltfContent::warnings`]; one that a material uses is [`GltfError::Image`].
//!
//! - **Emission**: `emissiveFactor × KHR_materials_emissive_strength ×`
//!   [`LightUnits::emission_factor`] `×` [`GltfOptions::emission_scale`] is the surface's
//!   radiance in W/(m²·sr), times the `emissiveTexture` (sRGB decoded to linear, at its own
//!   `TEXCOORD_n`, with its sampler) at each point. Every emissive primitive also becomes a
//!   light: an [`AreaLight`](crate::AreaLight) of constant radiance, or with a texture a
//!   [`TexturedAreaLight`](crate::TexturedAreaLight), whose power and triangle selection come
//!   from each triangle's mean emission (a fixed quadrature of the texture) while photons and
//!   shadow rays read the texture at the point they sample (unbiased; see that type).
//! - **Sides** ([`crate::Sides`]): `doubleSided: true` emitters emit from both sides (power
//!   `2πLA` for radiance `L` and area `A`, against `πLA` from the front alone) in photon
//!   emission, shadow rays and camera or path hits. `doubleSided: false` faces (the default
//!   material too) emit from the front (counter-clockwise) side only and are culled for camera
//!   rays seen from the back, as glTF viewers do; photons, shadow and path rays still meet
//!   both sides, so closed scenes stay closed and single-sided walls still cast shadows.
//! - **Punctual lights** (`KHR_lights_punctual`): point and spot intensities in candela
//!   become radiant intensities in W/sr, directional illuminance in lux becomes irradiance in
//!   W/m², multiplying by [`LightUnits::punctual_factor`] (by default 1 / [`LUMENS_PER_WATT`],
//!   683 lm/W, the efficacy of 555 nm light) and by [`GltfOptions::light_scale`] (files that
//!   store "watts-like" numbers want 683).
//! - **Units** ([`GltfOptions::light_units`]): the default [`LightUnits::Mixed`] reads
//!   emission 1:1 as radiance but divides lamps by 683, so a file authored in one system of
//!   units gets emitters 683 times too bright relative to its lamps;
//!   [`LightUnits::Photometric`] (all photometric, divided by 683: physical watts) and
//!   [`LightUnits::Viewer`] (all taken 1:1, as glTF viewers shade) keep the authored ratio:
//!   an emitter of luminance `L` and area `A` to a point light of intensity `I` is
//!   `π L A : 4π I` in power. A point light of intensity `I` has power `4π I`; a spot becomes a hard cone of the
//!   outer angle with power `2π (1 − cos θ_outer) I` (the spec's advice for single-angle
//!   engines). Lights and cameras point down their node's −Z axis; `range` is ignored.
//! - **Camera**: the first perspective camera met in the walk (orthographic ones are
//!   skipped); otherwise [`frame_bounds`] places one on the +z side looking along −z.
//! - **No light at all**: with [`GltfOptions::default_light`] (the default) a white point
//!   light at the camera gives 1 W/m² at the centre of the bounds; without it the file is an
//!   error ([`GltfError::Scene`]).
//!
//! # Placement: f64 transforms and re-centring
//!
//! Georeferenced models (architecture, city and terrain exports) keep small coordinates in
//! their accessors and put a large translation — kilometres, a UTM northing — in a root node;
//! composed and applied in f32, that translation leaves a few centimetres or metres of
//! precision and thin walls collapse. So node transforms are composed in f64, every vertex is
//! placed in f64 (`world · p`), and the world bounds of all placed vertices are taken in f64.
//! When their centre lies farther from the file's origin than the bounds' largest side, the
//! scene is re-centred: that centre is subtracted from every vertex, camera and punctual light
//! position (in f64) before they are rounded to f32 once; normals and directions are unchanged.
//! A model around its own origin is left exactly where the file puts it (moving it would gain
//! at most two bits of f32 precision and change images by rounding). The offset removed is
//! [`GltfContent::origin_offset`] and [`Scene::origin_offset`] (zero when nothing moved): a
//! point `p` of the scene is `origin_offset + p` in the file, so nothing a user measures in
//! the file's coordinates is lost; the render example reports it (`"origin_offset"` in
//! `--stats-json`).
//!
//! The gltf crate holds `translation`, `rotation`, `scale` and `matrix` in f32, which would
//! round an arbitrary northing by up to half a metre before it is composed (and shift two
//! sibling nodes carrying separate large translations apart by that much). So the loader reads
//! those four fields of every node again from the JSON text (the `.gltf` file, or a GLB's JSON
//! chunk), each number as the f64 nearest its decimal text; a value exactly representable in
//! f32 reads as the same f64 as before, bit for bit. A field that is not an array of its
//! length of numbers finite in f64 is [`GltfError::NodeTransform`], naming the node and the
//! field (the gltf crate refuses most such files first, as [`GltfError::Parse`]). What
//! remains is f64's own precision at the offset (a step of 1.9 nm at 10⁴ km).
//! Geometry is refused, with an error naming the primitive, only where a re-centred position
//! is not finite in f32, and by the scene builder past ±10¹⁸ m
//! ([`SceneError::GeometryOutOfRange`](crate::SceneError::GeometryOutOfRange)); that limit
//! applies to the re-centred scene, so it bounds a model's extent, not its distance.
//!
//! # Example
//!
//! ```
//! use pm_trace::gltf::{GltfOptions, read_content};
//! let path = concat!(env!("CARGO_MANIFEST_DIR"), "/../../tests/data/gltf/scenes/known.gltf");
//! let content = read_content(path.as_ref(), &GltfOptions::default())?;
//! assert_eq!((content.triangle_count(), content.lights.len()), (5, 3));
//!
//! let escape = concat!(env!("CARGO_MANIFEST_DIR"), "/../../tests/data/gltf/scenes/traversal.gltf");
//! let err = pm_trace::gltf::load_scene(escape.as_ref()).unwrap_err();
//! assert_eq!(err.kind(), "buffer/escapes-folder");
//! # Ok::<(), pm_trace::gltf::GltfError>(())
//! ```

mod accessor;
mod buffers;
mod build;
mod camera;
mod compact;
mod content;
mod decoded;
mod emissive;
mod error;
mod external;
mod graph;
mod image;
mod light;
mod material;
mod material_textures;
mod mesh;
mod node_transform;
mod normal_transform;
mod options;
mod origin;
mod place;
mod primitive;
mod scattering;
mod source;
mod texture_ref;
mod units;

pub use build::build_scene;
pub use camera::{DEFAULT_VFOV, GltfCamera, frame_bounds};
pub use content::{GltfContent, read_content};
pub use error::{BufferError, GltfError};
pub use external::external_files;
pub use graph::MAX_DEPTH;
pub use light::GltfLight;
pub use material::GltfMaterial;
pub use mesh::GltfMesh;
pub use options::GltfOptions;
pub use texture_ref::TextureRef;
pub use units::{LUMENS_PER_WATT, LightUnits};

use std::path::Path;

use crate::scene::Scene;

/// Loads a `.gltf` or `.glb` file into a [`Scene`] with [`GltfOptions::default`].
///
/// ```
/// let path = concat!(env!("CARGO_MANIFEST_DIR"), "/../../tests/data/gltf/scenes/known.gltf");
/// let scene = pm_trace::gltf::load_scene(path.as_ref())?;
/// // Five triangles, three punctual lights and one emissive triangle (an area light).
/// assert_eq!(scene.lights().len(), 4);
/// # Ok::<(), pm_trace::gltf::GltfError>(())
/// ```
pub fn load_scene(path: &Path) -> Result<Scene, GltfError> {
    load_scene_with(path, &GltfOptions::default())
}

/// Loads a `.gltf` or `.glb` file into a [`Scene`]: [`read_content`] then [`build_scene`].
pub fn load_scene_with(path: &Path, options: &GltfOptions) -> Result<Scene, GltfError> {
    let content = read_content(path, options)?;
    build_scene(path, &content, options)
}
