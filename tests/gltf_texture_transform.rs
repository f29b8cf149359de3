//! `KHR_texture_transform` against its closed form: a unit floor quad whose texture
//! coordinates are its own (x, z), in set `TEXCOORD_1` (named only by the extension's
//! `texCoord` override), textured with a 4×4 PNG of 16 distinct colours through an offset,
//! rotation and scale. For every texel, points of the quad that the spec's matrix
//! `T · R · S` maps onto that texel's centre (inverted here in f64) must show its colour.

#[path = "support/gltf_writer.rs"]
mod gltf_writer;

use gltf_writer::{Quad, png_rgb, srgb_to_linear, temp_dir, write_quads_gltf};
use photon_maps::trace::glam::{DVec2, DVec3, Vec2, Vec3};
use photon_maps::trace::gltf::{GltfOptions, load_scene_with, read_content};
use photon_maps::trace::{Ray, RayKind};

const SIZE: u32 = 4;
const OFFSET: [f64; 2] = [0.25, -0.5];
const ROTATION: f64 = 0.7;
const SCALE: [f64; 2] = [2.0, 3.0];

/// Texel `(column, row)`'s sRGB code: every texel a different colour.
fn texel(i: u32, j: u32) -> [u8; 3] {
    [
        (40 + 60 * i) as u8,
        (30 + 70 * j) as u8,
        (200 - 45 * ((i + j) % 4)) as u8,
    ]
}

/// The extension's matrix applied to `uv`: `T · R · S` with `R · (x, y) = (cos x + sin y,
/// −sin x + cos y)`, the reading under which the specification's example (offset (0, 1),
/// rotation π/2, scale 0.5) selects the image's lower-left quadrant.
fn transform(uv: DVec2) -> DVec2 {
    let (s, c) = ROTATION.sin_cos();
    let scaled = uv * DVec2::from(SCALE);
    DVec2::new(c * scaled.x + s * scaled.y, -s * scaled.x + c * scaled.y) + DVec2::from(OFFSET)
}

/// The inverse of [`transform`].
fn inverse(t: DVec2) -> DVec2 {
    let (s, c) = ROTATION.sin_cos();
    let d = t - DVec2::from(OFFSET);
    // R⁻¹ = Rᵀ.
    DVec2::new(c * d.x - s * d.y, s * d.x + c * d.y) / DVec2::from(SCALE)
}

#[test]
fn transformed_coordinates_read_the_texel_the_closed_form_names() {
    let dir = temp_dir("texture-transform");
    let texels: Vec<[u8; 3]> = (0..SIZE * SIZE).map(|k| texel(k % SIZE, k / SIZE)).collect();
    std::fs::write(dir.join("atlas.png"), png_rgb(SIZE, SIZE, &texels)).unwrap();
    let corners = [
        Vec3::new(0.0, 0.0, 0.0),
        Vec3::new(0.0, 0.0, 1.0),
        Vec3::new(1.0, 0.0, 1.0),
        Vec3::new(1.0, 0.0, 0.0),
    ];
    let uvs = corners.map(|c| Vec2::new(c.x, c.z));
    // Lambertian (specular factor 0): the albedo is the texel itself.
    let material = format!(
        r#"{{"pbrMetallicRoughness":{{"metallicFactor":0,"baseColorTexture":{{"index":0,"texCoord":0,
            "extensions":{{"KHR_texture_transform":{{"offset":[{},{}],"rotation":{ROTATION},"scale":[{},{}],"texCoord":1}}}}}}}},
            "extensions":{{"KHR_materials_specular":{{"specularFactor":0}}}}}}"#,
        OFFSET[0], OFFSET[1], SCALE[0], SCALE[1]
    );
    let file = write_quads_gltf(&dir, &[Quad { corners, uvs }], &material, "atlas.png", &[], "");
    // The coordinates are set 1 only: set 0 would be read if the override were ignored.
    let json = std::fs::read_to_string(&file)
        .unwrap()
        .replace("\"TEXCOORD_0\"", "\"TEXCOORD_1\"");
    std::fs::write(&file, json).unwrap();
    let options = GltfOptions::default();
    let content = read_content(&file, &options).unwrap();
    assert!(content.warnings.is_empty(), "{:?}", content.warnings);
    let reference = content.meshes[0].material.base_color_texture.unwrap();
    assert_eq!(reference.tex_coord, 1);
    let scene = load_scene_with(&file, &options).unwrap();

    let mut checked = 0;
    for j in 0..SIZE {
        for i in 0..SIZE {
            let truth = texel(i, j).map(srgb_to_linear);
            // Every repeat of the texel's centre whose preimage lies well inside the quad.
            for a in -8..8 {
                for b in -8..8 {
                    let centre = DVec2::new(
                        (i as f64 + 0.5) / SIZE as f64 + a as f64,
                        (j as f64 + 0.5) / SIZE as f64 + b as f64,
                    );
                    let uv = inverse(centre);
                    assert!((transform(uv) - centre).length() < 1e-9);
                    if uv.min_element() < 0.02 || uv.max_element() > 0.98 {
                        continue;
                    }
                    let ray = Ray::new(Vec3::new(uv.x as f32, 1.0, uv.y as f32), Vec3::NEG_Y);
                    let hit = scene.intersect(&ray, f32::INFINITY, RayKind::Other).unwrap();
                    let albedo = scene.albedo_at(&hit).as_dvec3();
                    let expected = DVec3::from(truth);
                    assert!(
                        (albedo - expected).abs().max_element() < 2e-3,
                        "texel ({i}, {j}) at uv {uv}: albedo {albedo}, texel {expected}"
                    );
                    checked += 1;
                }
            }
        }
    }
    // The quad covers 2 × 3 = 6 texture areas: about 6 repeats of each of the 16 texels.
    println!("{checked} points checked against their texel");
    assert!(checked >= 60, "only {checked} points checked");
    std::fs::remove_dir_all(&dir).ok();
}
