//! `KHR_materials_specular`'s textures reach the BSDF at each hit: one 2×1 RGBA PNG is both
//! the `specularTexture` (strength in its alpha channel, linear) and the `specularColorTexture`
//! (sRGB colour in its RGB channels) of a quad whose two halves read one texel each. At hits on
//! each half, the scene's material must equal `MetallicRoughness::with_specular` built here
//! from the texel's values times the factors, decoded independently of the loader. A second
//! file with specular factor 0 and the same textures stays Lambertian (factor × texel = 0).

#[path = "support/gltf_writer.rs"]
mod gltf_writer;

use gltf_writer::{Quad, png_rgba, srgb_to_linear, temp_dir, write_quads_gltf};
use photon_maps::trace::bsdf::{Bsdf, MetallicRoughness, ShadingPoint};
use photon_maps::trace::glam::{Vec2, Vec3};
use photon_maps::trace::gltf::{GltfOptions, load_scene_with, read_content};
use photon_maps::trace::{Material, Ray, RayKind};

/// The two texels: sRGB-coded specular colour and, in alpha, the specular strength.
const TEXELS: [[u8; 4]; 2] = [[255, 128, 64, 51], [10, 200, 90, 230]];
const SPECULAR_FACTOR: f32 = 0.8;
const SPECULAR_COLOR_FACTOR: [f32; 3] = [1.0, 0.9, 0.7];
const BASE: [f32; 3] = [0.5, 0.4, 0.3];
const ROUGHNESS: f32 = 0.4;

/// A 2 m × 1 m quad facing +z whose texture's u runs along x, written with `material`.
fn quad_file(name: &str, material: &str) -> std::path::PathBuf {
    let dir = temp_dir(name);
    std::fs::write(dir.join("specular.png"), png_rgba(2, 1, &TEXELS)).unwrap();
    let corners = [
        Vec3::new(0.0, 0.0, 0.0),
        Vec3::new(2.0, 0.0, 0.0),
        Vec3::new(2.0, 1.0, 0.0),
        Vec3::new(0.0, 1.0, 0.0),
    ];
    let uvs = [
        Vec2::new(0.0, 1.0),
        Vec2::new(1.0, 1.0),
        Vec2::new(1.0, 0.0),
        Vec2::new(0.0, 0.0),
    ];
    let file = write_quads_gltf(&dir, &[Quad { corners, uvs }], material, "specular.png", &[], "");
    // Nearest-texel lookup: every point of a half reads its texel alone.
    let json = std::fs::read_to_string(&file).unwrap();
    std::fs::write(
        &file,
        json.replace(r#""samplers":[{}]"#, r#""samplers":[{"magFilter":9728}]"#),
    )
    .unwrap();
    file
}

fn material_json(specular_factor: f32) -> String {
    let [br, bg, bb] = BASE;
    let [sr, sg, sb] = SPECULAR_COLOR_FACTOR;
    format!(
        r#"{{"pbrMetallicRoughness":{{"baseColorFactor":[{br},{bg},{bb},1],"metallicFactor":0,"roughnessFactor":{ROUGHNESS}}},
            "extensions":{{"KHR_materials_specular":{{"specularFactor":{specular_factor},"specularTexture":{{"index":0}},
            "specularColorFactor":[{sr},{sg},{sb}],"specularColorTexture":{{"index":0}}}}}}}}"#
    )
}

#[test]
fn specular_and_specular_colour_texels_reach_the_bsdf_at_each_half() {
    let file = quad_file("specular-textures", &material_json(SPECULAR_FACTOR));
    let options = GltfOptions::default();
    let content = read_content(&file, &options).unwrap();
    assert!(content.warnings.is_empty(), "{:?}", content.warnings);
    let textures = &content.meshes[0].material_textures;
    assert!(textures.specular.is_some() && textures.specular_color.is_some());
    let scene = load_scene_with(&file, &options).unwrap();

    let wo = Vec3::new(0.3, -0.2, 1.0).normalize();
    let directions = [
        Vec3::Z,
        Vec3::new(-0.3, 0.2, 1.0).normalize(),
        Vec3::new(0.5, 0.1, 0.6).normalize(),
        Vec3::new(-0.9, 0.0, 0.2).normalize(),
    ];
    let mut strengths = Vec::new();
    for (half, texel) in TEXELS.iter().enumerate() {
        for dx in [0.0f32, 0.3, -0.3] {
            let x = 0.5 + half as f32 + dx;
            let ray = Ray::new(Vec3::new(x, 0.5, 1.0), Vec3::NEG_Z);
            let hit = scene
                .intersect(&ray, 10.0, RayKind::Other)
                .expect("the quad is hit");
            let at = scene.shading_point(&hit);
            let colour = Vec3::new(
                srgb_to_linear(texel[0]) as f32,
                srgb_to_linear(texel[1]) as f32,
                srgb_to_linear(texel[2]) as f32,
            );
            let strength = SPECULAR_FACTOR * (texel[3] as f32 / 255.0);
            let truth = MetallicRoughness::new(Vec3::from(BASE), 0.0, ROUGHNESS)
                .unwrap()
                .with_specular(strength, Vec3::from(SPECULAR_COLOR_FACTOR) * colour)
                .unwrap();
            let material = scene.material(&hit);
            assert!(matches!(material, Material::MetallicRoughness(_)), "{material:?}");
            let plain = ShadingPoint::facing(Vec3::Z);
            for wi in directions {
                let got = material.eval(&at, wo, wi);
                let want = truth.eval(&plain, wo, wi);
                assert!(
                    (got - want).abs().max_element() <= 1e-4 * want.max_element().max(1e-3),
                    "half {half} x {x} wi {wi}: {got} against {want}"
                );
            }
            // The diffuse weight 1 − max F follows the textured specular layer too.
            let diffuse = material.diffuse_albedo(&at);
            let want = truth.diffuse_albedo(&plain);
            assert!(
                (diffuse - want).abs().max_element() < 1e-5,
                "{diffuse} against {want}"
            );
            strengths.push(strength);
        }
    }
    // The halves differ: a loader that read the RGB as strength, or ignored the texture,
    // fails above (texel 0's red is 255, its alpha 51).
    assert!(strengths[0] < 0.2 && strengths[3] > 0.7, "{strengths:?}");
    std::fs::remove_dir_all(file.parent().unwrap()).ok();
}

#[test]
fn a_zero_specular_factor_stays_lambertian_whatever_its_textures() {
    let file = quad_file("specular-zero", &material_json(0.0));
    let scene = load_scene_with(&file, &GltfOptions::default()).unwrap();
    let hit = scene
        .intersect(
            &Ray::new(Vec3::new(0.5, 0.5, 1.0), Vec3::NEG_Z),
            10.0,
            RayKind::Other,
        )
        .unwrap();
    assert_eq!(
        scene.material(&hit),
        &Material::Lambertian {
            albedo: Vec3::from(BASE)
        }
    );
    let content = read_content(&file, &GltfOptions::default()).unwrap();
    assert!(content.meshes[0].material_textures.is_empty());
    std::fs::remove_dir_all(file.parent().unwrap()).ok();
}
