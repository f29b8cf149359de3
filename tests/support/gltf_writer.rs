//! Writes small glTF files for tests: textured quads in one data-URI buffer, a PNG beside
//! them, and whatever lights, cameras and extensions the test names as raw JSON.

#![allow(dead_code)]

use std::path::{Path, PathBuf};

use photon_maps::trace::glam::{Vec2, Vec3};

/// One quad: corners counter-clockwise seen from its front, and their texture coordinates.
pub struct Quad {
    pub corners: [Vec3; 4],
    pub uvs: [Vec2; 4],
}

/// An 8-bit RGB PNG of `width × height` texels (row-major, top row first).
pub fn png_rgb(width: u32, height: u32, texels: &[[u8; 3]]) -> Vec<u8> {
    assert_eq!(texels.len(), (width * height) as usize);
    let mut out = Vec::new();
    let mut e = png::Encoder::new(&mut out, width, height);
    e.set_color(png::ColorType::Rgb);
    e.set_depth(png::BitDepth::Eight);
    let mut w = e.write_header().unwrap();
    w.write_image_data(texels.as_flattened()).unwrap();
    w.finish().unwrap();
    out
}

/// An 8-bit RGBA PNG of `width × height` texels (row-major, top row first).
pub fn png_rgba(width: u32, height: u32, texels: &[[u8; 4]]) -> Vec<u8> {
    assert_eq!(texels.len(), (width * height) as usize);
    let mut out = Vec::new();
    let mut e = png::Encoder::new(&mut out, width, height);
    e.set_color(png::ColorType::Rgba);
    e.set_depth(png::BitDepth::Eight);
    let mut w = e.write_header().unwrap();
    w.write_image_data(texels.as_flattened()).unwrap();
    w.finish().unwrap();
    out
}

/// The sRGB decoding of IEC 61966-2-1, written here independently of the loader.
pub fn srgb_to_linear(code: u8) -> f64 {
    let c = code as f64 / 255.0;
    if c <= 0.04045 {
        c / 12.92
    } else {
        ((c + 0.055) / 1.055).powf(2.4)
    }
}

/// A fresh, empty folder under the system's temporary folder.
pub fn temp_dir(name: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("pm-{name}-{}", std::process::id()));
    std::fs::remove_dir_all(&dir).ok();
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

/// Writes `dir/scene.gltf`: the quads as one mesh (one primitive, material 0, POSITION and
/// TEXCOORD_0), placed by node 0; `material` is material 0's JSON (its base-colour texture,
/// if any, is texture 0 = image `image_uri`); `extra_nodes` are more node objects (lights,
/// cameras), each placed at the scene's root; `lights` is the `KHR_lights_punctual` light
/// array (empty for none).
pub fn write_quads_gltf(
    dir: &Path,
    quads: &[Quad],
    material: &str,
    image_uri: &str,
    extra_nodes: &[String],
    lights: &str,
) -> PathBuf {
    let n = quads.len();
    let mut bytes: Vec<u8> = Vec::new();
    for q in quads {
        for c in q.corners {
            bytes.extend(c.to_array().iter().flat_map(|f| f.to_le_bytes()));
        }
    }
    let uv_offset = bytes.len();
    for q in quads {
        for t in q.uvs {
            bytes.extend(t.to_array().iter().flat_map(|f| f.to_le_bytes()));
        }
    }
    let index_offset = bytes.len();
    for i in 0..n as u32 {
        for k in [0, 1, 2, 0, 2, 3] {
            bytes.extend((4 * i + k).to_le_bytes());
        }
    }
    let (lo, hi) = quads
        .iter()
        .flat_map(|q| q.corners)
        .fold((Vec3::INFINITY, Vec3::NEG_INFINITY), |(lo, hi), p| {
            (lo.min(p), hi.max(p))
        });
    let hex: String = bytes.iter().map(|b| format!("%{b:02X}")).collect();
    let mut nodes = vec![r#"{"mesh":0}"#.to_string()];
    nodes.extend(extra_nodes.iter().cloned());
    let roots: Vec<String> = (0..nodes.len()).map(|i| i.to_string()).collect();
    let extensions = if lights.is_empty() {
        String::new()
    } else {
        format!(
            r#","extensionsUsed":["KHR_lights_punctual"],"extensions":{{"KHR_lights_punctual":{{"lights":{lights}}}}}"#
        )
    };
    let json = format!(
        r#"{{"asset":{{"version":"2.0"}}{extensions},
        "buffers":[{{"byteLength":{len},"uri":"data:application/octet-stream,{hex}"}}],
        "bufferViews":[{{"buffer":0,"byteLength":{uv_offset}}},
                       {{"buffer":0,"byteOffset":{uv_offset},"byteLength":{uv_len}}},
                       {{"buffer":0,"byteOffset":{index_offset},"byteLength":{index_len}}}],
        "accessors":[{{"bufferView":0,"componentType":5126,"count":{vertices},"type":"VEC3",
                       "min":[{lx},{ly},{lz}],"max":[{hx},{hy},{hz}]}},
                     {{"bufferView":1,"componentType":5126,"count":{vertices},"type":"VEC2"}},
                     {{"bufferView":2,"componentType":5125,"count":{indices},"type":"SCALAR"}}],
        "images":[{{"uri":"{image_uri}"}}],
        "samplers":[{{}}],
        "textures":[{{"source":0,"sampler":0}}],
        "materials":[{material}],
        "meshes":[{{"primitives":[{{"attributes":{{"POSITION":0,"TEXCOORD_0":1}},"indices":2,"material":0}}]}}],
        "nodes":[{nodes}],"scenes":[{{"nodes":[{roots}]}}],"scene":0}}"#,
        len = bytes.len(),
        uv_len = index_offset - uv_offset,
        index_len = bytes.len() - index_offset,
        vertices = 4 * n,
        indices = 6 * n,
        lx = lo.x,
        ly = lo.y,
        lz = lo.z,
        hx = hi.x,
        hy = hi.y,
        hz = hi.z,
        nodes = nodes.join(","),
        roots = roots.join(","),
    );
    let path = dir.join("scene.gltf");
    std::fs::write(&path, json).unwrap();
    path
}
