//! Base-colour textures against independent truth: the corpus's BoxTextured face against its
//! PNG decoded here with the png crate, a generated checkerboard of known mean albedo, and
//! hostile image references that must be typed errors.

use std::path::{Path, PathBuf};
use std::sync::Arc;

use photon_maps::trace::glam::{Vec2, Vec3};
use photon_maps::trace::gltf::{GltfOptions, load_scene, read_content};
use photon_maps::trace::{PointLight, RayKind, Sampler, Scene, Surface, Texture, VertexAttributes};

const CORPUS: &str = concat!(env!("CARGO_MANIFEST_DIR"), "/../shared/gltf-corpus");

fn corpus() -> Option<PathBuf> {
    let dir = std::env::var_os("PM_GLTF_CORPUS").map_or_else(|| PathBuf::from(CORPUS), PathBuf::from);
    if dir.is_dir() {
        Some(dir)
    } else {
        println!("notice: {} is absent; this test checks nothing", dir.display());
        None
    }
}

/// Mean linear colour of an 8-bit RGB(A) PNG, decoded here independently of the loader.
fn png_mean_linear(path: &Path) -> Vec3 {
    let mut decoder = png::Decoder::new(std::io::BufReader::new(std::fs::File::open(path).unwrap()));
    decoder.set_transformations(png::Transformations::EXPAND | png::Transformations::STRIP_16);
    let mut reader = decoder.read_info().unwrap();
    let mut buf = vec![0; reader.output_buffer_size().unwrap()];
    let frame = reader.next_frame(&mut buf).unwrap();
    let channels = frame.color_type.samples();
    let lin = |c: u8| {
        let c = c as f64 / 255.0;
        if c <= 0.04045 {
            c / 12.92
        } else {
            ((c + 0.055) / 1.055).powf(2.4)
        }
    };
    let mut sum = [0.0f64; 3];
    let mut n = 0.0;
    for px in buf[..frame.buffer_size()].chunks_exact(channels) {
        for (s, &c) in sum.iter_mut().zip(px.iter().take(3)) {
            *s += lin(c);
        }
        n += 1.0;
    }
    Vec3::new((sum[0] / n) as f32, (sum[1] / n) as f32, (sum[2] / n) as f32)
}

#[test]
fn box_textured_face_shows_the_logo_colours() {
    let Some(corpus) = corpus() else { return };
    let dir = corpus.join("assimp-glTF2/BoxTextured-glTF");
    let scene = load_scene(&dir.join("BoxTextured.gltf")).unwrap();
    let truth = png_mean_linear(&dir.join("CesiumLogoFlat.png"));
    // Camera rays over the image; keep hits on faces seen head-on (one whole face, the logo
    // mapped once over it), and compare the mean albedo with the PNG's mean colour.
    let centre = scene.camera().ray(0.5, 0.5, 1.0);
    let facing = scene
        .intersect(&centre, f32::INFINITY, RayKind::Camera)
        .unwrap()
        .normal;
    let (mut sum, mut n) = (Vec3::ZERO, 0.0f32);
    let (mut blue, mut green) = (0, 0);
    for y in 0..100 {
        for x in 0..100 {
            let ray = scene
                .camera()
                .ray((x as f32 + 0.5) / 100.0, (y as f32 + 0.5) / 100.0, 1.0);
            let Some(hit) = scene.intersect(&ray, f32::INFINITY, RayKind::Camera) else {
                continue;
            };
            if hit.normal.dot(facing) < 0.999 {
                continue;
            }
            let a = scene.albedo_at(&hit);
            sum += a;
            n += 1.0;
            blue += (a.z > 0.3 && a.z > 1.5 * a.x) as u32;
            green += (a.y > 1.5 * a.z && a.y > 1.5 * a.x) as u32;
        }
    }
    assert!(n > 1000.0, "the face covers only {n} samples");
    let mean = sum / n;
    println!("face mean albedo {mean}, texture mean {truth}, {blue} blue and {green} green samples");
    assert!((mean - truth).abs().max_element() < 0.05, "{mean} vs {truth}");
    assert!(blue > 100 && green > 100, "the logo's sky and hills are missing");
}

#[test]
fn nvpro_cornell_box_loads_with_a_warning_for_its_unused_broken_texture() {
    let Some(corpus) = corpus() else { return };
    let file = corpus.join("cornell/nvpro-vk_raytracing_tutorial_KHR/cornellBox.gltf");
    let content = read_content(&file, &GltfOptions::default()).unwrap();
    assert!(
        content.warnings.iter().any(|w| w.contains("texture 0")),
        "{:?}",
        content.warnings
    );
    load_scene(&file).unwrap();
}

/// A floor quad with a checkerboard of black and white texels, tiled by Repeat.
fn checkerboard_scene(tiles: f32) -> Scene {
    let texels = (0..64)
        .map(|i| {
            if (i % 8 + i / 8) % 2 == 0 {
                [255; 3]
            } else {
                [0; 3]
            }
        })
        .collect();
    let texture = Arc::new(Texture::from_srgb8(8, 8, texels).unwrap());
    let floor = [
        Vec3::new(-1.0, 0.0, -1.0),
        Vec3::new(-1.0, 0.0, 1.0),
        Vec3::new(1.0, 0.0, 1.0),
        Vec3::new(1.0, 0.0, -1.0),
    ];
    let uvs = vec![
        Vec2::ZERO,
        Vec2::new(0.0, tiles),
        Vec2::new(tiles, tiles),
        Vec2::new(tiles, 0.0),
    ];
    Scene::builder()
        .attributed_mesh(
            &floor,
            &[[0, 1, 2], [0, 2, 3]],
            Surface::diffuse(Vec3::splat(0.8)),
            VertexAttributes {
                uvs: Some(uvs),
                colors: None,
                normals: None,
                base_color_texture: Some((texture, Sampler::default())),
                ..VertexAttributes::default()
            },
        )
        .light(PointLight::new(Vec3::new(0.0, 2.0, 0.0), Vec3::splat(10.0)))
        .build()
        .unwrap()
}

#[test]
fn checkerboard_mean_albedo_is_factor_times_half() {
    // Bilinear filtering of a periodic checkerboard keeps its mean, 0.5 in linear units.
    let scene = checkerboard_scene(3.0);
    let (mut sum, mut n) = (0.0f64, 0.0f64);
    for i in 0..200 {
        for j in 0..200 {
            let origin = Vec3::new(
                -1.0 + (i as f32 + 0.5) / 100.0,
                1.0,
                -1.0 + (j as f32 + 0.5) / 100.0,
            );
            let ray = photon_maps::trace::Ray {
                origin,
                direction: Vec3::NEG_Y,
            };
            let hit = scene.intersect(&ray, f32::INFINITY, RayKind::Other).unwrap();
            let a = scene.albedo_at(&hit);
            assert!(a.x == a.y && a.y == a.z && (0.0..=0.8).contains(&a.x));
            sum += a.x as f64;
            n += 1.0;
        }
    }
    let mean = sum / n;
    assert!(
        (mean - 0.4).abs() < 0.01,
        "mean albedo {mean}, expected 0.8 × 0.5"
    );
}

/// A one-triangle glTF whose material's base-colour texture is image `image_json`.
fn write_textured_gltf(dir: &Path, image_json: &str) -> PathBuf {
    // 3 positions then 3 texture coordinates, little-endian f32.
    let floats: [f32; 15] = [
        0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 1.0,
    ];
    let bytes: Vec<u8> = floats.iter().flat_map(|f| f.to_le_bytes()).collect();
    let hex: String = bytes.iter().map(|b| format!("%{b:02X}")).collect();
    let json = format!(
        r#"{{"asset":{{"version":"2.0"}},
        "buffers":[{{"byteLength":60,"uri":"data:application/octet-stream,{hex}"}}],
        "bufferViews":[{{"buffer":0,"byteLength":36}},{{"buffer":0,"byteOffset":36,"byteLength":24}}],
        "accessors":[{{"bufferView":0,"componentType":5126,"count":3,"type":"VEC3","min":[0,0,0],"max":[1,1,0]}},
                     {{"bufferView":1,"componentType":5126,"count":3,"type":"VEC2"}}],
        "images":[{image_json}],
        "textures":[{{"source":0}}],
        "materials":[{{"pbrMetallicRoughness":{{"baseColorTexture":{{"index":0}}}}}}],
        "meshes":[{{"primitives":[{{"attributes":{{"POSITION":0,"TEXCOORD_0":1}},"material":0}}]}}],
        "nodes":[{{"mesh":0}}],"scenes":[{{"nodes":[0]}}]}}"#
    );
    let path = dir.join("scene.gltf");
    std::fs::write(&path, json).unwrap();
    path
}

fn png_bytes(width: u32, height: u32) -> Vec<u8> {
    let mut out = Vec::new();
    let mut e = png::Encoder::new(&mut out, width, height);
    e.set_color(png::ColorType::Rgb);
    e.set_depth(png::BitDepth::Eight);
    let mut w = e.write_header().unwrap();
    w.write_image_data(&vec![200; (width * height * 3) as usize])
        .unwrap();
    w.finish().unwrap();
    out
}

#[test]
fn hostile_images_are_typed_errors() {
    let root = std::env::temp_dir().join(format!("pm-gltf-textures-{}", std::process::id()));
    let dir = root.join("scene");
    std::fs::create_dir_all(&dir).unwrap();
    std::fs::write(root.join("outside.png"), png_bytes(2, 2)).unwrap();
    std::fs::write(dir.join("ok.png"), png_bytes(2, 2)).unwrap();
    let whole = png_bytes(16, 16);
    std::fs::write(dir.join("truncated.png"), &whole[..whole.len() / 2]).unwrap();
    std::fs::write(dir.join("fake.jpg"), [0xFF, 0xD8, 0xFF, 0xE0, 0, 0x10]).unwrap();
    let mut huge = png_bytes(1, 1);
    huge[16..24].copy_from_slice(&[0, 0, 0xFF, 0xFF, 0, 0, 0xFF, 0xFF]);
    std::fs::write(dir.join("huge.png"), huge).unwrap();

    let ok = write_textured_gltf(&dir, r#"{"uri":"ok.png"}"#);
    load_scene(&ok).expect("a well-formed texture loads");
    for image in [
        r#"{"uri":"../outside.png"}"#,
        r#"{"uri":"truncated.png"}"#,
        r#"{"uri":"fake.jpg"}"#,
        r#"{"uri":"huge.png"}"#,
        r#"{"uri":"missing.png"}"#,
        r#"{"uri":"data:image/png;base64,iVBORw0KGgo="}"#,
    ] {
        let file = write_textured_gltf(&dir, image);
        let err = load_scene(&file).expect_err(image);
        assert_eq!(err.kind(), "image", "{image}: {err}");
    }
    std::fs::remove_dir_all(&root).ok();
}
