//! World-space glTF content to a [`Scene`]: one scene mesh per primitive, an area light per
//! emissive primitive (textured when its emission is), the punctual lights converted to the
//! library's lights, the camera, and a headlight for files without any light.

use std::f32::consts::PI;
use std::path::Path;

use glam::{Vec2, Vec3};

use super::camera::frame_bounds;
use super::content::GltfContent;
use super::error::GltfError;
use super::light::GltfLight;
use super::mesh::GltfMesh;
use super::options::GltfOptions;
use crate::camera::Camera;
use crate::light::Light;
use crate::light::area::AreaLight;
use crate::light::directional::DirectionalLight;
use crate::light::point::PointLight;
use crate::light::spot::SpotLight;
use crate::light::textured_area::TexturedAreaLight;
use crate::material::Surface;
use crate::scene::Scene;
use crate::scene::builder::SceneBuilder;
use crate::scene::shading::VertexAttributes;
use crate::sides::Sides;

/// Builds a scene from content read by [`read_content`](super::read_content). `file` only
/// names the source in errors.
pub fn build_scene(file: &Path, content: &GltfContent, options: &GltfOptions) -> Result<Scene, GltfError> {
    let scene_error = |reason: String| GltfError::Scene {
        file: file.to_path_buf(),
        reason,
    };
    let (min, max) = content
        .bounds()
        .ok_or_else(|| scene_error("the scene holds no triangles".into()))?;
    let mut builder = Scene::builder().origin_offset(content.origin_offset);
    let mut has_light = false;
    for mesh in content.meshes.iter().filter(|m| !m.triangles.is_empty()) {
        let surface = surface_of(mesh);
        builder = add_mesh(builder, mesh, surface);
        if mesh.material.emission.max_element() > 0.0
            && let Some(light) = emitter(mesh, surface.sides)
        {
            builder = builder.boxed_light(light);
            has_light = true;
        }
    }
    for light in &content.lights {
        builder = add_punctual_light(builder, light);
        has_light = true;
    }
    let camera = content.camera.unwrap_or_else(|| frame_bounds(min, max));
    if !has_light {
        if !options.default_light {
            return Err(scene_error(
                "the file has no punctual lights and no emissive surfaces".into(),
            ));
        }
        builder = builder.light(headlight(camera.position, (min + max) * 0.5));
    }
    builder
        .camera(Camera::new(
            camera.position,
            camera.look_at,
            camera.up,
            camera.vfov,
        ))
        .build()
        .map_err(|source| GltfError::Build {
            file: file.to_path_buf(),
            source,
        })
}

/// The surface of `mesh`: its material's scattering and emission, seen by the camera, from
/// both sides when the material is double-sided.
fn surface_of(mesh: &GltfMesh) -> Surface {
    let material = mesh.material;
    let sides = if material.double_sided {
        Sides::Double
    } else {
        Sides::Single
    };
    Surface {
        material: material.kind,
        emission: material.emission,
        camera_visible: true,
        sides,
    }
}

/// Adds `mesh` to `builder` with `surface`, with its vertex attributes (texture coordinates,
/// colours, normals, textures) when it has any.
fn add_mesh(builder: SceneBuilder, mesh: &GltfMesh, surface: Surface) -> SceneBuilder {
    let attributed = mesh.uvs.is_some()
        || mesh.colors.is_some()
        || mesh.normals.is_some()
        || mesh.emission_texture.is_some()
        || !mesh.material_textures.is_empty();
    if attributed {
        let attributes = VertexAttributes {
            uvs: mesh.uvs.clone(),
            colors: mesh.colors.clone(),
            normals: mesh.normals.clone(),
            base_color_texture: mesh.base_color_texture.clone(),
            emission_texture: mesh.emission_texture.clone(),
            material_textures: mesh.material_textures.clone(),
        };
        builder.attributed_mesh(&mesh.positions, &mesh.triangles, surface, attributes)
    } else {
        builder.mesh(&mesh.positions, &mesh.triangles, surface)
    }
}

/// Adds glTF punctual `light` to `builder` as the library's light: a point light of power
/// 4π × intensity, a spot of the power of its outer cone ([`spot_power`]), a directional light.
fn add_punctual_light(builder: SceneBuilder, light: &GltfLight) -> SceneBuilder {
    match *light {
        GltfLight::Point { position, intensity } => {
            builder.light(PointLight::new(position, 4.0 * PI * intensity))
        }
        GltfLight::Spot {
            position,
            direction,
            intensity,
            outer_cone_angle,
            ..
        } => builder.light(SpotLight::new(
            position,
            direction,
            outer_cone_angle,
            spot_power(intensity, outer_cone_angle),
        )),
        GltfLight::Directional {
            direction,
            irradiance,
        } => builder.light(DirectionalLight::new(direction, irradiance)),
    }
}

/// The area light of an emissive mesh: textured when its emission is (power and selection
/// per triangle from the texture's mean over it), else of constant radiance; emitting from
/// both sides for [`Sides::Double`]. `None` when nothing emits (no area, or a black texture).
fn emitter(mesh: &GltfMesh, sides: Sides) -> Option<Box<dyn Light>> {
    let emission = mesh.material.emission;
    let triangles: Vec<[Vec3; 3]> = mesh
        .triangles
        .iter()
        .map(|t| t.map(|i| mesh.positions[i as usize]))
        .collect();
    match &mesh.emission_texture {
        Some(texture) => {
            let uvs: Vec<[Vec2; 3]> = mesh
                .triangles
                .iter()
                .map(|t| t.map(|i| texture.uvs[i as usize]))
                .collect();
            let light = TexturedAreaLight::new(
                &triangles,
                &uvs,
                emission,
                texture.texture.clone(),
                texture.sampler,
                sides,
            );
            (light.triangle_count() > 0).then(|| Box::new(light) as Box<dyn Light>)
        }
        None => {
            let light = AreaLight::from_triangles(&triangles, emission).with_sides(sides);
            (light.area() > 0.0).then(|| Box::new(light) as Box<dyn Light>)
        }
    }
}

/// Total power of a uniform cone of half-angle `outer` with radiant intensity `intensity`:
/// `I · 2π (1 − cos θ)`. The renderer's spot has one hard edge; glTF's smooth falloff between
/// the inner and outer angles is replaced by full intensity out to the outer angle, as the
/// `KHR_lights_punctual` spec advises for engines with a single cone angle.
pub(super) fn spot_power(intensity: Vec3, outer: f32) -> Vec3 {
    intensity * (2.0 * PI * (1.0 - outer.cos()))
}

/// The default light of a file without lights: a white point light at the camera whose
/// irradiance at the centre of the scene's bounds, facing it, is 1 W/m².
fn headlight(eye: Vec3, center: Vec3) -> PointLight {
    let d2 = eye.distance_squared(center).max(1e-6);
    PointLight::new(eye, Vec3::splat(4.0 * PI * d2))
}
