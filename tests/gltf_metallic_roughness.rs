//! glTF's metallic-roughness material reaches the BSDF at each hit: a 2×1 PNG used as both the
//! base-colour texture (sRGB colour) and the `metallicRoughnessTexture` (linear data: blue =
//! metallic, green = roughness) of one quad, whose two halves read one texel each. At hits on
//! each half, the scene's material evaluated at the hit's shading point must equal
//! `MetallicRoughness::new` built here from the texel's values times the factors, decoded
//! independently of the loader (sRGB by IEC 61966-2-1, data as `code / 255`).

#[path = "support/gltf_writer.rs"]
mod gltf_writer;

use gltf_writer::{Quad, png_rgb, srgb_to_linear, temp_dir, write_quads_gltf};
use photon_maps::trace::bsdf::{Bsdf, MetallicRoughness, ShadingPoint};
use photon_maps::trace::glam::{Vec2, Vec3};
use photon_maps::trace::gltf::{GltfOptions, load_scene_with, read_content};
use photon_maps::trace::{Material, Ray, RayKind};

/// The two texels: `[r, g, b]` sRGB-coded colour, and (g, b) as roughness and metalness.
const TEXELS: [[u8; 3]; 2] = [[200, 51, 255], [90, 204, 0]];
const BASE_FACTOR: [f32; 3] = [0.9, 0.8, 0.5];
const METALLIC_FACTOR: f32 = 0.8;
const ROUGHNESS_FACTOR: f32 = 0.5;

#[test]
fn metallic_roughness_texels_reach_the_bsdf_at_each_half() {
    let dir = temp_dir("metallic-roughness-texture");
    std::fs::write(dir.join("mr.png"), png_rgb(2, 1, &TEXELS)).unwrap();
    // A 2 m × 1 m quad facing +z; u runs along x, so x < 1 reads texel 0 and x > 1 texel 1.
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
    let [br, bg, bb] = BASE_FACTOR;
    let material = format!(
        r#"{{"pbrMetallicRoughness":{{"baseColorFactor":[{br},{bg},{bb},1],"metallicFactor":{METALLIC_FACTOR},
            "roughnessFactor":{ROUGHNESS_FACTOR},"baseColorTexture":{{"index":0}},
            "metallicRoughnessTexture":{{"index":0}}}},
            "extensions":{{"KHR_materials_ior":{{"ior":1.7}}}}}}"#
    );
    let file = write_quads_gltf(&dir, &[Quad { corners, uvs }], &material, "mr.png", &[], "");
    // Nearest-texel lookup: every point of a half reads its texel alone.
    let json = std::fs::read_to_string(&file).unwrap();
    std::fs::write(
        &file,
        json.replace(r#""samplers":[{}]"#, r#""samplers":[{"magFilter":9728}]"#),
    )
    .unwrap();
    let options = GltfOptions::default();
    let content = read_content(&file, &options).unwrap();
    assert!(content.warnings.is_empty(), "{:?}", content.warnings);
    assert!(content.meshes[0].material_textures.metallic_roughness.is_some());
    let scene = load_scene_with(&file, &options).unwrap();

    let wo = Vec3::new(0.3, -0.2, 1.0).normalize();
    let directions = [
        Vec3::Z,
        Vec3::new(-0.3, 0.2, 1.0).normalize(),
        Vec3::new(0.5, 0.1, 0.6).normalize(),
        Vec3::new(-0.9, 0.0, 0.2).normalize(),
    ];
    let mut checked = 0;
    for (half, texel) in TEXELS.iter().enumerate() {
        // Texel centres (u = 0.25, 0.75) and points around them on the same half.
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
            let truth = MetallicRoughness::new(
                Vec3::from(BASE_FACTOR) * colour,
                METALLIC_FACTOR * (texel[2] as f32 / 255.0),
                ROUGHNESS_FACTOR * (texel[1] as f32 / 255.0),
            )
            .unwrap()
            .with_ior(1.7)
            .unwrap();
            let material = scene.material(&hit);
            assert!(matches!(material, Material::MetallicRoughness(_)), "{material:?}");
            let plain = ShadingPoint::facing(Vec3::Z);
            for wi in directions {
                let got = material.eval(&at, wo, wi);
                let want = truth.eval(&plain, wo, wi);
                let tolerance = 1e-4 * want.max_element().max(1e-3);
                assert!(
                    (got - want).abs().max_element() <= tolerance,
                    "half {half} x {x} wi {wi}: {got} against {want}"
                );
                let (pdf, want_pdf) = (material.pdf(&at, wo, wi), truth.pdf(&plain, wo, wi));
                assert!(
                    (pdf - want_pdf).abs() <= 1e-4 * want_pdf.max(1e-3),
                    "{pdf} against {want_pdf}"
                );
            }
            // The photon-map estimators' diffuse reflectance follows the texels too.
            let diffuse = scene.albedo_at(&hit);
            let want = truth.diffuse_albedo(&plain);
            assert!(
                (diffuse - want).abs().max_element() < 1e-5,
                "{diffuse} against {want}"
            );
            checked += 1;
        }
    }
    assert_eq!(checked, 6);
    std::fs::remove_dir_all(&dir).ok();
}

#[test]
fn a_missing_texcoord_set_leaves_the_factors_with_a_warning() {
    let dir = temp_dir("metallic-roughness-no-texcoord");
    std::fs::write(dir.join("mr.png"), png_rgb(2, 1, &TEXELS)).unwrap();
    let corners = [Vec3::ZERO, Vec3::X, Vec3::new(1.0, 1.0, 0.0), Vec3::Y];
    let material = r#"{"pbrMetallicRoughness":{"metallicFactor":0.5,"roughnessFactor":0.5,
        "metallicRoughnessTexture":{"index":0,"texCoord":3}}}"#;
    let file = write_quads_gltf(
        &dir,
        &[Quad {
            corners,
            uvs: [Vec2::ZERO; 4],
        }],
        material,
        "mr.png",
        &[],
        "",
    );
    let content = read_content(&file, &GltfOptions::default()).unwrap();
    assert!(content.meshes[0].material_textures.metallic_roughness.is_none());
    assert!(
        content
            .warnings
            .iter()
            .any(|w| w.contains("TEXCOORD_3") && w.contains("metallic-roughness")),
        "{:?}",
        content.warnings
    );
    std::fs::remove_dir_all(&dir).ok();
}
