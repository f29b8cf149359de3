//! Scenes, lights, a watertight BVH, deterministic parallel photon tracing and the partition
//! of surfaces into photon maps.
//!
//! A [`Scene`] is built with [`Scene::builder`] from meshes (through
//! [`pm_geom::HalfEdgeMesh`]), analytic shapes (sphere, ring), [`Light`]s and a [`Camera`].
//! Every mesh face, sphere and ring side is a *part* ([`PartId`]); a [`Partitioner`]
//! ([`SingleMap`], [`CreaseAngle`], and [`Contact`], the one to use unless you reproduce the
//! report: crease-angle maps that never join across a line where faces pierce, stand on,
//! overlap or nearly touch each other) takes the scene and returns a [`Partitioned`]: the
//! scene (for [`Contact`], split where faces meet) with the photon map of each of its parts.
//! [`trace_photons`] shoots
//! photons from the lights and stores them per map; [`PhotonMaps::build`] turns them into
//! kd-trees plus each map's polygons for the geometry-based estimators (coplanar, edge-connected
//! faces merged into larger convex polygons, so a finely split wall costs one clip; merged the
//! first time the map is read, so that a render builds the polygons of the maps it sees). Ball & Stejko's
//! scenes, the same rooms built from solid boxes, and scale scenes for measuring how cost grows,
//! are in [`scenes`].
//!
//! Where the camera sees a small part of what the lights light, an [`EmissionGuide`] learnt
//! by [`EmissionGuide::learn`] from a pilot of photon paths (and a caller's test of what the
//! camera sees) drops most photons that would light nothing seen at their light, and raises
//! the power of those it keeps: [`trace_guided_photon_paths`] is unbiased (Hachisuka &
//! Jensen's photon-path visibility, applied at the light).
//!
//! How a surface scatters light is a [`Bsdf`] ([`bsdf`]): the built-in Lambertian, mirror
//! and glass of [`Material`] implement it, and a renderer author brings their own through
//! [`Material::Custom`] ([`Surface::with_bsdf`]); the photon tracer and the renderer's delta
//! chain and path tracer scatter through it. The module docs give its conventions (world
//! space, `eval` without the cosine, delta lobes) and an example implementation.
//!
//! A mesh may carry [`VertexAttributes`]: texture coordinates, colours and normals, a
//! base-colour and an emission texture, and [`MaterialTextures`]: textures that multiply a
//! [`bsdf::MetallicRoughness`]'s metalness, roughness, specular strength and specular colour
//! at each point (read into [`ShadingPoint::factors`](bsdf::ShadingPoint::factors)), and a
//! normal map ([`NormalTexture`], in glTF's tangent-space convention, with
//! [`mikktspace_tangents`] for meshes without tangents) that bends
//! [`Scene::shading_normal_at`], kept at least [`MIN_MAPPED_COSINE`] above the geometric
//! surface. The glTF loader (module `gltf`, feature `gltf`) fills them from a file's materials.
//!
//! # Conventions
//!
//! - Units: metres; light *power* is the total emitted flux in watts per RGB channel;
//!   radiance in W/(m²·sr), irradiance in W/m². Colours are linear RGB.
//! - Right-handed coordinates, +y up (as glTF); angles in radians; `f32` throughout the
//!   scene and the renderer. The glTF loader composes node transforms in f64 and re-centres a
//!   model placed far from its file's origin before rounding it to f32; the offset it removed
//!   is [`Scene::origin_offset`] (f64; zero for scenes built directly or left in place), and a
//!   scene point `p` is `origin_offset + p` in the file (the `gltf` module's *Placement*).
//! - Polygons are counter-clockwise seen from the side their normal points to.
//! - Emitters: an emitting surface of radiance `L` and area `A` emits `π L A` watts from its
//!   front, `2π L A` when its [`Surface::sides`] is [`Sides::Double`]; a point light of
//!   intensity `I` (W/sr) emits `4π I`. [`Sides::Single`] surfaces are culled for camera rays
//!   seen from the back; photon, shadow and path rays see both sides of every surface. An
//!   [`EmissionTexture`] multiplies a mesh's emission; its [`TexturedAreaLight`] takes power
//!   and light selection from each triangle's mean emission and reads the texture at each
//!   sampled point (so its estimates are unbiased). The glTF loader's
//!   `gltf::GltfOptions::light_units` says how a file's emissive strength (cd/m²), candela
//!   and lux become these watts, keeping emitters and lamps at their authored ratio or not.
//! - With `N` photons emitted, each starts with `Φ_total / N` on average (lights are chosen in
//!   proportion to their power).
//! - Tracing is deterministic: photon path `i` draws from its own stream `Rng::new(seed, i)`
//!   (the key hashed into both the PCG state and its increment, so neighbouring paths and
//!   seeds are independent), so results are bit-identical for any number of threads.
//! - Ray queries ([`Scene::intersect`], [`Scene::occluded`]) are watertight: no ray slips
//!   between triangles that share an edge. A ray leaving a surface point starts at
//!   [`Scene::spawn_ray`]'s offset origin and is searched with [`Scene::intersect_from`] (shadow
//!   rays: [`Scene::occluded_from`]), which skip the triangle it leaves: on a sliver, the
//!   triangle test's rounding would now and then find it again. Scenes of up to 64 triangles test every triangle
//!   (four at a time); larger ones go through an obvhs 8-wide BVH built by our own binned-SAH
//!   builder (O(n log n) on any input, a triangle fan included), which is tested to find
//!   exactly the same hits, also right next to the ray's origin and along the axes. Analytic
//!   shapes are searched apart from the triangles.
//! - Memory: a built scene holds 80–94 bytes per triangle ([`Scene::heap_bytes`]: the
//!   half-edge mesh, each triangle's corners, part and surface once, the BVH nodes); building it peaks
//!   near 400 bytes per triangle. Ray cost grows with the log of the triangle count plus
//!   cache misses: 24 → 240k triangles costs about 3× per path-traced sample (see
//!   `examples/scale.rs`).
//!
//! # Features
//!
//! - `gltf` (default): the `gltf` module loads `.gltf`/`.glb` scenes safely.
//!
//! # Limits
//!
//! [`SceneBuilder::build`] refuses invalid lights and cameras ([`SceneError::InvalidLight`],
//! [`SceneError::InvalidCamera`]); [`trace_photons`] traces at most [`MAX_PHOTON_PATHS`] paths
//! and stores at most [`MAX_STORED_PHOTONS`] photons ([`TraceError::TooManyPhotons`],
//! [`TraceError::TooManyPhotonsStored`]); the glTF loader's limits are on
//! `gltf::GltfOptions` (file and buffer bytes, triangles, a scene byte budget).
//!
//! # Example
//!
//! ```
//! use pm_trace::{CreaseAngle, Partitioner, PhotonMaps, PointLight, Scene, Surface, TraceOptions, trace_photons};
//! use pm_trace::glam::Vec3;
//!
//! // A 2 m floor under a 100 W white point light.
//! let floor = [Vec3::new(-1.0, 0.0, -1.0), Vec3::new(-1.0, 0.0, 1.0), Vec3::new(1.0, 0.0, 1.0), Vec3::new(1.0, 0.0, -1.0)];
//! let scene = Scene::builder()
//!     .mesh(&floor, &[[0u32, 1, 2, 3]], Surface::diffuse(Vec3::splat(0.5)))
//!     .light(PointLight::new(Vec3::new(0.0, 1.0, 0.0), Vec3::splat(100.0)))
//!     .build()?;
//! let partitioned = CreaseAngle::default().partition(scene)?;
//! let (scene, maps) = (partitioned.scene(), partitioned.assignment());
//! let traced = trace_photons(scene, maps, &TraceOptions { photons: 10_000, seed: 1, max_bounces: 8, ..TraceOptions::default() })?;
//! // Seen from the light, the floor covers 1/6 of all directions: about 1,667 photons land on it
//! // (bounced photons fly up and away).
//! let stored = traced.stats().total_stored();
//! assert!((1_550..1_790).contains(&stored), "{stored}");
//! let photon_maps = PhotonMaps::build(scene, maps, traced)?;
//! assert_eq!(photon_maps.len(), 1);
//! # Ok::<(), Box<dyn std::error::Error>>(())
//! ```
//!
//! # References
//!
//! - H. W. Jensen, *Global Illumination using Photon Maps*, Rendering Techniques '96
//!   (Eurographics Workshop on Rendering), 1996: photon maps and the disc estimate
//!   `E = Σ Φ / (π r²)` over the k nearest photons.
//! - R. D. Larsen and N. J. Christensen, *Optimizing Photon Mapping Using Multiple Photon Maps
//!   for Irradiance Estimates*, WSCG 2003: one photon map per group of faces joined across
//!   edges with a small crease angle, so that no estimate gathers through a wall.
//! - H. Hey and W. Purgathofer, *Advanced Radiance Estimation for Photon Map Global
//!   Illumination*, Computer Graphics Forum 21(3), 2002: gather in a cube and divide by the
//!   surface area actually inside it, so that edges are not darkened.
//! - Ball and Stejko's project report, which combines the three and whose scenes (the Cornell
//!   box, the lit and unlit rooms, the coloured rooms, the accordion), four variants (basic,
//!   multiple maps, geometry area, both) and timing table this workspace reproduces; "the
//!   report" in these docs is that report. The reproduction is in the repository's
//!   `docs/results.md`.

pub mod bsdf;
mod bvh;
pub mod camera;
pub mod emission;
pub mod error;
pub mod light;
pub mod material;
pub mod part;
pub mod partition;
pub mod photons;
pub mod ray;
pub mod rng;
pub mod sampler;
pub mod sampling;
pub mod scene;
pub mod scenes;
pub mod shape;
pub mod sides;
pub mod texture;
pub mod texture_transform;

#[cfg(feature = "gltf")]
pub mod gltf;

pub use bsdf::{Bsdf, BsdfSample, Lobes, ShadingPoint, TextureFactors};
pub use camera::Camera;
pub use emission::EmissionTexture;
pub use error::{MapError, MaterialError, PhotonFault, SceneError, TraceError};
pub use glam;
pub use light::{
    AreaLight, DirectionalLight, EmittedRay, IncidentPdf, Light, LightClone, LightSample, PointLight,
    SpotLight, TexturedAreaLight,
};
pub use material::{Material, Surface};
pub use part::{PartId, PartSource, SourceFace};
pub use partition::{
    Contact, ContactRecord, ContactSeconds, CreaseAngle, MapAssignment, PartitionError, Partitioned,
    Partitioner, SingleMap,
};
pub use photons::{
    EmissionGuide, GuideOptions, MAX_PHOTON_PATHS, MAX_STORED_PHOTONS, MapGeometry, MapOccupancy,
    NEAR_LIGHT_DISTANCE, PhotonMap, PhotonMaps, TraceOptions, TraceStats, TracedPhotons,
    trace_guided_photon_paths, trace_photon_paths, trace_photons,
};
pub use pm_kdtree::{Photon, PhotonKind};
pub use ray::Ray;
pub use rng::Rng;
pub use sampler::{Sampler, Wrap};
pub use scene::{
    Hit, MAX_SCENE_TRIANGLES, MIN_MAPPED_COSINE, MaterialTexture, MaterialTextures, NormalTexture,
    PAIRED_RAYS_MIN_TRIANGLES, RayKind, Scene, SceneBuilder, SceneMesh, VertexAttributes,
    mikktspace_tangents,
};
pub use shape::{Ring, RingSide, Shape, Sphere};
pub use sides::Sides;
pub use texture::{TexelEncoding, Texture};
pub use texture_transform::TextureTransform;
