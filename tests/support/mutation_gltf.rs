//! The glTF mutants of the mutation test: a textured unit-cube room (external buffer, PNG or
//! JPEG texture, `NORMAL`, `TEXCOORD_0`, `COLOR_0`) written byte by byte, and the mutations
//! made to it (accessor types, counts, offsets and values, image sizes, bit depths, colour
//! types, truncation, a JPEG marked progressive, bit flips).

use super::Rng;
use std::collections::BTreeMap;
use std::path::Path;

const SPECIAL: [f32; 9] = [
    f32::NAN,
    f32::INFINITY,
    f32::NEG_INFINITY,
    3e38,
    -3e38,
    -1.0,
    0.0,
    1e-40,
    1e18,
];

/// The scene's binary buffer: positions, normals, texture coordinates, colours, indices of a
/// unit cube room seen from inside, each at a recorded offset.
struct Buffers {
    bin: Vec<u8>,
    /// (name, byte offset, byte length) of each attribute block.
    blocks: Vec<(&'static str, usize, usize)>,
}

fn room_buffers() -> Buffers {
    let corners = super::unit_cube_room::corners();
    let normals: Vec<[f32; 3]> = corners.iter().map(|c| c.map(|v| 0.5 - v)).collect();
    let uvs: Vec<[f32; 2]> = corners.iter().map(|c| [c[0], c[2]]).collect();
    let colours: Vec<[f32; 4]> = corners.iter().map(|c| [c[0], 0.5, c[2], 1.0]).collect();
    let indices = super::unit_cube_room::triangle_indices();
    let mut bin = Vec::new();
    let mut blocks = Vec::new();
    let mut push = |name, bytes: Vec<u8>| {
        blocks.push((name, bin.len(), bytes.len()));
        bin.extend(bytes);
    };
    push(
        "POSITION",
        corners.iter().flatten().flat_map(|f| f.to_le_bytes()).collect(),
    );
    push(
        "NORMAL",
        normals.iter().flatten().flat_map(|f| f.to_le_bytes()).collect(),
    );
    push(
        "TEXCOORD_0",
        uvs.iter().flatten().flat_map(|f| f.to_le_bytes()).collect(),
    );
    push(
        "COLOR_0",
        colours.iter().flatten().flat_map(|f| f.to_le_bytes()).collect(),
    );
    push("indices", indices.iter().flat_map(|i| i.to_le_bytes()).collect());
    Buffers { bin, blocks }
}

/// The accessors' JSON fields that mutations change.
struct Accessor {
    component: u32,
    normalized: bool,
    count: i64,
    ty: &'static str,
    offset: i64,
}

impl Accessor {
    /// `count` unnormalized 32-bit floats of type `ty` from the start of their view.
    fn float(count: i64, ty: &'static str) -> Self {
        Accessor {
            component: 5126,
            normalized: false,
            count,
            ty,
            offset: 0,
        }
    }
}

fn scene_json(
    b: &Buffers,
    accessors: &[Accessor],
    image_uri: &str,
    tex_coord: u32,
    placement: &str,
) -> String {
    let views: Vec<String> = b
        .blocks
        .iter()
        .map(|(_, offset, len)| format!(r#"{{"buffer":0,"byteOffset":{offset},"byteLength":{len}}}"#))
        .collect();
    let accessor_json: Vec<String> = accessors
        .iter()
        .enumerate()
        .map(|(i, a)| {
            let bounds = if i == 0 { r#","min":[0,0,0],"max":[1,1,1]"# } else { "" };
            format!(
                r#"{{"bufferView":{i},"byteOffset":{},"componentType":{},"normalized":{},"count":{},"type":"{}"{bounds}}}"#,
                a.offset, a.component, a.normalized, a.count, a.ty
            )
        })
        .collect();
    format!(
        r#"{{"asset":{{"version":"2.0"}},"extensionsUsed":["KHR_lights_punctual"],
        "extensions":{{"KHR_lights_punctual":{{"lights":[{{"type":"point","intensity":30}}]}}}},
        "buffers":[{{"byteLength":{},"uri":"scene.bin"}}],
        "bufferViews":[{}],"accessors":[{}],
        "images":[{{"uri":"{image_uri}"}}],"textures":[{{"source":0}}],
        "materials":[{{"pbrMetallicRoughness":{{"baseColorTexture":{{"index":0,"texCoord":{tex_coord}}},"metallicFactor":0}}}}],
        "meshes":[{{"primitives":[{{"attributes":{{"POSITION":0,"NORMAL":1,"TEXCOORD_0":2,"COLOR_0":3}},"indices":4,"material":0}}]}}],
        "nodes":[{{"mesh":0}},{{"translation":[0.5,0.5,0.5],"extensions":{{"KHR_lights_punctual":{{"light":0}}}}}},
            {{"children":[0,1]{placement}}}],
        "cameras":[{{"type":"perspective","perspective":{{"yfov":1.2,"znear":0.01}}}}],
        "scenes":[{{"nodes":[2]}}],"scene":0}}"#,
        b.bin.len(),
        views.join(","),
        accessor_json.join(","),
    )
}

fn png(width: u32, height: u32, color: png::ColorType, depth: png::BitDepth) -> Vec<u8> {
    let mut out = Vec::new();
    let mut e = png::Encoder::new(&mut out, width, height);
    e.set_color(color);
    e.set_depth(depth);
    if color == png::ColorType::Indexed {
        e.set_palette(vec![0u8, 0, 0, 200, 100, 50]);
    }
    let samples = match color {
        png::ColorType::Grayscale | png::ColorType::Indexed => 1,
        png::ColorType::GrayscaleAlpha => 2,
        png::ColorType::Rgb => 3,
        png::ColorType::Rgba => 4,
    };
    let bits = samples * depth as usize;
    let row = (width as usize * bits).div_ceil(8);
    let data: Vec<u8> = (0..row * height as usize)
        .map(|i| (i * 37 % 251) as u8 & if color == png::ColorType::Indexed { 1 } else { 0xFF })
        .collect();
    let mut w = e.write_header().unwrap();
    w.write_image_data(&data).unwrap();
    w.finish().unwrap();
    out
}

fn crc32(bytes: &[u8]) -> u32 {
    let mut crc = !0u32;
    for &b in bytes {
        crc ^= b as u32;
        for _ in 0..8 {
            crc = if crc & 1 != 0 {
                (crc >> 1) ^ 0xEDB8_8320
            } else {
                crc >> 1
            };
        }
    }
    !crc
}

/// Rewrites IHDR bytes `at..at+value.len()` of a PNG and its CRC (nothing for an image cut
/// before the end of its IHDR, or a JPEG).
fn patch_ihdr(png: &mut [u8], at: usize, value: &[u8]) {
    if png.len() < 33 || !png.starts_with(b"\x89PNG") {
        return;
    }
    png[at..at + value.len()].copy_from_slice(value);
    let crc = crc32(&png[12..29]);
    png[29..33].copy_from_slice(&crc.to_be_bytes());
}

/// One glTF mutant: its files and what was done to it.
pub struct Mutant {
    pub files: BTreeMap<&'static str, Vec<u8>>,
    pub done: Vec<String>,
}

/// A fresh room with one to three random mutations.
pub fn gltf_mutant(rng: &mut Rng) -> Mutant {
    let mut b = room_buffers();
    let mut accessors = vec![
        Accessor::float(8, "VEC3"),
        Accessor::float(8, "VEC3"),
        Accessor::float(8, "VEC2"),
        Accessor::float(8, "VEC4"),
        Accessor {
            component: 5125,
            ..Accessor::float(36, "SCALAR")
        },
    ];
    let mut image = png(4, 4, png::ColorType::Rgb, png::BitDepth::Eight);
    let mut image_name = "tex.png";
    let mut tex_coord = 0;
    let mut placement = String::new();
    let mut done = Vec::new();
    for _ in 0..1 + rng.below(3) {
        match rng.below(11) {
            0 => {
                // An attribute's component type and normalized flag.
                let a = 1 + rng.below(3);
                accessors[a].component = *rng.pick(&[5120, 5121, 5122, 5123, 5125, 5126]);
                accessors[a].normalized = rng.below(2) == 0;
                done.push(format!(
                    "accessor {a} component {} normalized {}",
                    accessors[a].component, accessors[a].normalized
                ));
            }
            1 | 2 => {
                // A special value in NORMAL, TEXCOORD_0, COLOR_0 (or POSITION).
                let (name, offset, len) = *rng.pick(&b.blocks[..4]);
                let at = offset + 4 * rng.below(len / 4);
                let v = *rng.pick(&SPECIAL);
                b.bin[at..at + 4].copy_from_slice(&v.to_le_bytes());
                done.push(format!("{name} value {v} at byte {at}"));
            }
            3 => {
                let a = rng.below(5);
                accessors[a].count = *rng.pick(&[0, 1, 7, 9, 1 << 20, i64::from(u32::MAX)]);
                done.push(format!("accessor {a} count {}", accessors[a].count));
            }
            4 => {
                let a = rng.below(5);
                accessors[a].offset = *rng.pick(&[4, 7, 1 << 30]);
                done.push(format!("accessor {a} byteOffset {}", accessors[a].offset));
            }
            5 => {
                // Declared size.
                let (w, h) = *rng.pick(&[(0u32, 4u32), (65535, 65535), (1 << 31, 1), (4, 100_000), (3, 4)]);
                patch_ihdr(&mut image, 16, &w.to_be_bytes());
                patch_ihdr(&mut image, 20, &h.to_be_bytes());
                done.push(format!("PNG declares {w}x{h}"));
            }
            6 => {
                // Bit depth and colour type, consistent or not.
                let (color, depth) = *rng.pick(&[
                    (png::ColorType::Grayscale, png::BitDepth::One),
                    (png::ColorType::Grayscale, png::BitDepth::Sixteen),
                    (png::ColorType::Rgb, png::BitDepth::Sixteen),
                    (png::ColorType::Rgba, png::BitDepth::Eight),
                    (png::ColorType::GrayscaleAlpha, png::BitDepth::Eight),
                    (png::ColorType::Indexed, png::BitDepth::Two),
                ]);
                image = png(4, 4, color, depth);
                if rng.below(2) == 0 {
                    let (d, c) = (
                        *rng.pick(&[1u8, 2, 4, 8, 16, 3]),
                        *rng.pick(&[0u8, 2, 3, 4, 6, 7]),
                    );
                    patch_ihdr(&mut image, 24, &[d, c]);
                    done.push(format!(
                        "PNG {color:?} {depth:?} relabelled depth {d} colour type {c}"
                    ));
                } else {
                    done.push(format!("PNG {color:?} {depth:?}"));
                }
            }
            7 => {
                // JPEG: baseline, marked progressive, or cut.
                image =
                    std::fs::read(Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/data/mutation/cyan.jpg"))
                        .unwrap();
                image_name = "tex.jpg";
                match rng.below(3) {
                    0 => done.push("baseline JPEG".into()),
                    1 => {
                        if let Some(at) = image.windows(2).position(|w| w == [0xFF, 0xC0]) {
                            image[at + 1] = 0xC2;
                        }
                        done.push("JPEG marked progressive (SOF2)".into());
                    }
                    _ => {
                        let keep = rng.below(image.len());
                        image.truncate(keep);
                        done.push(format!("JPEG cut at {keep}"));
                    }
                }
            }
            8 => {
                let keep = rng.below(image.len());
                image.truncate(keep);
                done.push(format!("image cut at {keep}"));
            }
            9 => {
                // The root node's transform: zero, negative and non-uniform scales, huge
                // translations (a georeferenced model), degenerate matrices and rotations.
                placement = rng
                    .pick(&[
                        r#","scale":[1,1,0]"#,
                        r#","scale":[0,0,0]"#,
                        r#","scale":[-1,1,1]"#,
                        r#","scale":[1e-6,1,1e6]"#,
                        r#","scale":[1e-30,1e-30,1e-30]"#,
                        r#","scale":[1e30,1e30,1e30]"#,
                        r#","translation":[6400000,0,0]"#,
                        r#","translation":[1e7,-1e7,3e6],"scale":[1e-3,1e-3,1e-3]"#,
                        r#","translation":[1e30,0,0]"#,
                        r#","translation":[3e38,3e38,0]"#,
                        r#","rotation":[0,0,0,0]"#,
                        r#","rotation":[0,0,0,1e20]"#,
                        r#","matrix":[0,0,0,0,0,0,0,0,0,0,0,0,0,0,0,0]"#,
                        r#","matrix":[1,0,0,0,0,1,0,0,0,0,1,0,1e7,1e7,1e7,1]"#,
                        r#","matrix":[1,0,0,0,0,1,0,0,0,0,1,0,0,0,0,0]"#,
                    ])
                    .to_string();
                done.push(format!("root node{placement}"));
            }
            _ => {
                if rng.below(2) == 0 {
                    tex_coord = 1;
                    done.push("texCoord 1 (no TEXCOORD_1)".into());
                } else {
                    for _ in 0..4 {
                        let at = rng.below(b.bin.len());
                        b.bin[at] ^= 1 << rng.below(8);
                    }
                    done.push("four bit flips in the buffer".into());
                }
            }
        }
    }
    let mut files = BTreeMap::new();
    files.insert(
        "scene.gltf",
        scene_json(&b, &accessors, image_name, tex_coord, &placement).into_bytes(),
    );
    files.insert("scene.bin", b.bin);
    files.insert(image_name, image);
    files.insert("sentinel.txt", b"not to be touched".to_vec());
    Mutant { files, done }
}
