//! A seeded mutation test of the render example, run as a user runs it: valid glTF scenes
//! (external buffer, PNG or JPEG texture, `NORMAL`, `TEXCOORD_0`, `COLOR_0`) and valid
//! progressive shards are mutated (accessor types, counts and values, image sizes, bit
//! depths, colour types, truncation, a JPEG marked progressive, shard headers, pass ranges
//! and pixel values, random bytes) and each mutant is rendered or merged. Every run must end
//! within 20 s with status 0 or 1 and no panic; a successful run's EXR must hold only finite
//! pixels; and no file but the outputs named may change.
//!
//! CI runs a short run (`PM_MUTATION_CASES` unset: 24 glTF and 12 shard mutants); set
//! `PM_MUTATION_CASES=N` for N of each and `PM_MUTATION_SEED` for another seed. A failing
//! case prints its seed, index and mutations; its files are kept under the temp folder.

#[path = "support/example.rs"]
mod example;

use exr::meta::attribute::{AttributeValue, Text};
use exr::prelude::{Encoding, LayerAttributes, SpecificChannels, Vec2, WritableImage};
use std::collections::BTreeMap;
use std::path::{Path, PathBuf};
use std::process::{Command, Stdio};
use std::time::{Duration, Instant};

/// SplitMix64: small, seeded, the same sequence everywhere.
struct Rng(u64);

impl Rng {
    fn next(&mut self) -> u64 {
        self.0 = self.0.wrapping_add(0x9e37_79b9_7f4a_7c15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xbf58_476d_1ce4_e5b9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94d0_49bb_1331_11eb);
        z ^ (z >> 31)
    }
    fn below(&mut self, n: usize) -> usize {
        (self.next() % n as u64) as usize
    }
    fn pick<'a, T>(&mut self, items: &'a [T]) -> &'a T {
        &items[self.below(items.len())]
    }
}

fn cases() -> usize {
    std::env::var("PM_MUTATION_CASES")
        .ok()
        .and_then(|v| v.parse().ok())
        .unwrap_or(0)
}

fn seed() -> u64 {
    std::env::var("PM_MUTATION_SEED")
        .ok()
        .and_then(|v| v.parse().ok())
        .unwrap_or(21)
}

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
    let corners: Vec<[f32; 3]> = (0..8)
        .map(|i| [(i & 1) as f32, ((i >> 1) & 1) as f32, ((i >> 2) & 1) as f32])
        .collect();
    let normals: Vec<[f32; 3]> = corners.iter().map(|c| c.map(|v| 0.5 - v)).collect();
    let uvs: Vec<[f32; 2]> = corners.iter().map(|c| [c[0], c[2]]).collect();
    let colours: Vec<[f32; 4]> = corners.iter().map(|c| [c[0], 0.5, c[2], 1.0]).collect();
    let quads = [
        [0u32, 4, 5, 1],
        [2, 3, 7, 6],
        [0, 2, 6, 4],
        [1, 5, 7, 3],
        [4, 6, 7, 5],
        [0, 1, 3, 2],
    ];
    let indices: Vec<u32> = quads
        .iter()
        .flat_map(|q| [q[0], q[1], q[2], q[0], q[2], q[3]])
        .collect();
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

fn scene_json(b: &Buffers, accessors: &[Accessor], image_uri: &str, tex_coord: u32) -> String {
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
        "nodes":[{{"mesh":0}},{{"translation":[0.5,0.5,0.5],"extensions":{{"KHR_lights_punctual":{{"light":0}}}}}}],
        "cameras":[{{"type":"perspective","perspective":{{"yfov":1.2,"znear":0.01}}}}],
        "scenes":[{{"nodes":[0,1]}}],"scene":0}}"#,
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
struct Mutant {
    files: BTreeMap<&'static str, Vec<u8>>,
    done: Vec<String>,
}

fn gltf_mutant(rng: &mut Rng) -> Mutant {
    let mut b = room_buffers();
    let mut accessors = vec![
        Accessor {
            component: 5126,
            normalized: false,
            count: 8,
            ty: "VEC3",
            offset: 0,
        },
        Accessor {
            component: 5126,
            normalized: false,
            count: 8,
            ty: "VEC3",
            offset: 0,
        },
        Accessor {
            component: 5126,
            normalized: false,
            count: 8,
            ty: "VEC2",
            offset: 0,
        },
        Accessor {
            component: 5126,
            normalized: false,
            count: 8,
            ty: "VEC4",
            offset: 0,
        },
        Accessor {
            component: 5125,
            normalized: false,
            count: 36,
            ty: "SCALAR",
            offset: 0,
        },
    ];
    let mut image = png(4, 4, png::ColorType::Rgb, png::BitDepth::Eight);
    let mut image_name = "tex.png";
    let mut tex_coord = 0;
    let mut done = Vec::new();
    for _ in 0..1 + rng.below(3) {
        match rng.below(10) {
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
        scene_json(&b, &accessors, image_name, tex_coord).into_bytes(),
    );
    files.insert("scene.bin", b.bin);
    files.insert(image_name, image);
    files.insert("sentinel.txt", b"not to be touched".to_vec());
    Mutant { files, done }
}

/// Every file under `dir` with its bytes, outputs left out.
fn snapshot(dir: &Path, outputs: &[&str]) -> BTreeMap<PathBuf, Vec<u8>> {
    let mut out = BTreeMap::new();
    let mut stack = vec![dir.to_path_buf()];
    while let Some(d) = stack.pop() {
        for e in std::fs::read_dir(&d).unwrap() {
            let p = e.unwrap().path();
            if p.is_dir() {
                stack.push(p);
            } else if !outputs.iter().any(|o| p.ends_with(o)) {
                out.insert(p.clone(), std::fs::read(&p).unwrap());
            }
        }
    }
    out
}

/// Runs the example in `dir` with `args`; checks the run ended within 20 s with status 0
/// or 1 and no panic, that a success's EXR `out` has only finite pixels, and that nothing
/// but `outputs` changed. `label` names the case in failures. Returns whether it succeeded
/// (`None`: the example is not built).
fn check_run(dir: &Path, args: &[&str], out: &str, outputs: &[&str], label: &str) -> Option<bool> {
    let exe = example::example("render")?;
    let before = snapshot(dir, outputs);
    let mut child = Command::new(exe)
        .args(args)
        .current_dir(dir)
        .stdout(Stdio::null())
        .stderr(Stdio::piped())
        .spawn()
        .unwrap();
    let start = Instant::now();
    let status = loop {
        if let Some(status) = child.try_wait().unwrap() {
            break status;
        }
        if start.elapsed() > Duration::from_secs(20) {
            let _ = child.kill();
            let _ = child.wait();
            panic!("{label}: ran past 20 s (kept in {})", dir.display());
        }
        std::thread::sleep(Duration::from_millis(10));
    };
    let mut stderr = String::new();
    use std::io::Read as _;
    child.stderr.take().unwrap().read_to_string(&mut stderr).unwrap();
    assert!(
        !stderr.contains("panicked"),
        "{label}: panicked: {stderr} (kept in {})",
        dir.display()
    );
    assert!(
        matches!(status.code(), Some(0 | 1)),
        "{label}: status {status:?} (an abort or a signal): {stderr} (kept in {})",
        dir.display()
    );
    if status.success() {
        let image = photon_maps::render::Image::read_exr(dir.join(out)).unwrap();
        assert!(
            image.pixels().iter().all(|p| p.is_finite()),
            "{label}: non-finite pixels (kept in {})",
            dir.display()
        );
    }
    let after = snapshot(dir, outputs);
    assert!(
        before == after,
        "{label}: a file that is no output changed (kept in {})",
        dir.display()
    );
    Some(status.success())
}

/// Counts of rendered and refused mutants; both must occur, or the mutants test nothing.
#[derive(Default)]
struct Tally {
    rendered: usize,
    refused: usize,
}

impl Tally {
    fn add(&mut self, outcome: bool) {
        if outcome {
            self.rendered += 1;
        } else {
            self.refused += 1;
        }
    }

    fn check(&self, what: &str) {
        eprintln!("{what}: {} rendered, {} refused", self.rendered, self.refused);
        assert!(
            self.rendered > 0 && self.refused > 0,
            "{what}: the mutants are all alike"
        );
    }
}

const MODES: [&[&str]; 4] = [
    &["--mode", "photon-map", "--photons", "300"],
    &["--mode", "path-trace"],
    &["--mode", "sppm", "--photons", "300", "--passes", "1"],
    &["--mode", "progressive", "--photons", "300", "--passes", "1"],
];

#[test]
fn mutated_gltf_scenes_render_or_are_refused_cleanly() {
    let n = match cases() {
        0 => 24,
        n => n,
    };
    let seed = seed();
    let mut rng = Rng(seed);
    let mut tally = Tally::default();
    for case in 0..n {
        let mutant = gltf_mutant(&mut rng);
        let mode = *rng.pick(&MODES);
        let dir = std::env::temp_dir().join(format!("pm-mutation-gltf-{}-{case}", std::process::id()));
        let _ = std::fs::remove_dir_all(&dir);
        std::fs::create_dir_all(&dir).unwrap();
        for (name, bytes) in &mutant.files {
            std::fs::write(dir.join(name), bytes).unwrap();
        }
        let mut args = vec!["--scene", "scene.gltf", "--size", "8x6", "--out", "out/x.exr"];
        args.extend_from_slice(mode);
        let label = format!("seed {seed} glTF case {case} {mode:?}: {:?}", mutant.done);
        let Some(outcome) = check_run(&dir, &args, "out/x.exr", &["out/x.exr", "out/x.png"], &label) else {
            return;
        };
        tally.add(outcome);
        std::fs::remove_dir_all(&dir).ok();
    }
    tally.check("glTF mutants");
}

fn words(x: f64) -> (u32, u32) {
    ((x.to_bits() >> 32) as u32, x.to_bits() as u32)
}

/// A shard file written by hand (the format the library documents), every pixel's sums
/// `(hi, lo)`; the header's five lines as given.
fn write_shard(path: &Path, lines: &[String], hi: f64, lo: f64) {
    let (h, l) = (words(hi), words(lo));
    let mean = hi as f32;
    let channels = SpecificChannels::build()
        .with_channel::<f32>("R")
        .with_channel::<f32>("G")
        .with_channel::<f32>("B")
        .with_channel::<u32>("pmSumHi0R")
        .with_channel::<u32>("pmSumHi1R")
        .with_channel::<u32>("pmSumLo0R")
        .with_channel::<u32>("pmSumLo1R")
        .with_channel::<u32>("pmSumHi0G")
        .with_channel::<u32>("pmSumHi1G")
        .with_channel::<u32>("pmSumLo0G")
        .with_channel::<u32>("pmSumLo1G")
        .with_channel::<u32>("pmSumHi0B")
        .with_channel::<u32>("pmSumHi1B")
        .with_channel::<u32>("pmSumLo0B")
        .with_channel::<u32>("pmSumLo1B")
        .with_pixel_fn(|_: Vec2<usize>| {
            (
                mean, mean, mean, h.0, h.1, l.0, l.1, h.0, h.1, l.0, l.1, h.0, h.1, l.0, l.1,
            )
        });
    let mut attributes = LayerAttributes::default();
    let text = Text::new_or_none(lines.join("\n").as_str()).unwrap_or_default();
    attributes
        .other
        .insert(Text::from("photonMapsShard"), AttributeValue::Text(text));
    let layer = exr::prelude::Layer::new((8, 6), attributes, Encoding::SMALL_LOSSLESS, channels);
    exr::prelude::Image::from_layer(layer)
        .write()
        .to_file(path)
        .unwrap();
}

/// The header of a shard: its scene and settings lines read from a real one.
fn header_of(path: &Path) -> (String, String) {
    let meta = exr::meta::MetaData::read_from_file(path, false).unwrap();
    let h = &meta.headers[0];
    let text = h
        .own_attributes
        .other
        .get(&Text::from("photonMapsShard"))
        .or_else(|| h.shared_attributes.other.get(&Text::from("photonMapsShard")));
    let Some(AttributeValue::Text(t)) = text else {
        panic!("no shard header")
    };
    let t = t.to_string();
    let lines: Vec<&str> = t.split('\n').collect();
    (lines[3].to_owned(), lines[4].to_owned())
}

#[test]
fn mutated_shards_merge_or_are_refused_cleanly() {
    let n = match cases() {
        0 => 12,
        n => n / 2,
    };
    let seed = seed();
    let mut rng = Rng(seed ^ 0x5eed);
    let base = std::env::temp_dir().join(format!("pm-mutation-shards-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&base);
    std::fs::create_dir_all(&base).unwrap();
    let render = |name: &str, first: &str| {
        let args = [
            "--mode",
            "progressive",
            "--size",
            "8x6",
            "--photons",
            "300",
            "--passes",
            "1",
            "--first-pass",
            first,
            "--out",
            name,
        ];
        let exe = example::example("render")?;
        let status = Command::new(exe).args(args).current_dir(&base).output().unwrap();
        assert!(
            status.status.success(),
            "{}",
            String::from_utf8_lossy(&status.stderr)
        );
        Some(std::fs::read(base.join(name)).unwrap())
    };
    let Some(a) = render("a.exr", "0") else { return };
    let b = render("b.exr", "1").unwrap();
    let (scene, settings) = header_of(&base.join("a.exr"));
    let mut tally = Tally::default();
    let passes = [
        "0",
        "1",
        "2",
        "18446744073709551613",
        "18446744073709551614",
        "18446744073709551615",
    ];
    for case in 0..n {
        let dir = base.join(format!("case{case}"));
        std::fs::create_dir_all(&dir).unwrap();
        let (pa, pb) = (dir.join("a.exr"), dir.join("b.exr"));
        std::fs::write(&pa, &a).unwrap();
        std::fs::write(&pb, &b).unwrap();
        let target = if rng.below(2) == 0 { &pa } else { &pb };
        let done = match rng.below(4) {
            0 => {
                let mut bytes = std::fs::read(target).unwrap();
                let at = rng.below(bytes.len().min(600));
                bytes[at] ^= 1 << rng.below(8);
                std::fs::write(target, bytes).unwrap();
                format!("bit flip at {at}")
            }
            1 => {
                let mut bytes = std::fs::read(target).unwrap();
                let keep = rng.below(bytes.len());
                bytes.truncate(keep);
                std::fs::write(target, bytes).unwrap();
                format!("cut at {keep}")
            }
            2 => {
                let (first, count) = (*rng.pick(&passes), *rng.pick(&passes));
                let lines = [
                    "photon-maps shard v2".to_owned(),
                    first.into(),
                    count.into(),
                    scene.clone(),
                    settings.clone(),
                ];
                write_shard(target, &lines, 1.0, 0.0);
                format!("header passes {first} + {count}")
            }
            _ => {
                let values = [f64::NAN, f64::INFINITY, -1.0, 1e300, 1e-320, 0.0];
                let (hi, lo) = (*rng.pick(&values), *rng.pick(&values));
                let first = if target == &pa { "0" } else { "1" };
                let lines = [
                    "photon-maps shard v2".to_owned(),
                    first.into(),
                    "1".into(),
                    scene.clone(),
                    settings.clone(),
                ];
                write_shard(target, &lines, hi, lo);
                format!("pixel sums {hi} + {lo}")
            }
        };
        let args = ["--merge", "a.exr", "b.exr", "--out", "m.exr"];
        let label = format!("seed {seed} shard case {case} ({}): {done}", target.display());
        tally.add(check_run(&dir, &args, "m.exr", &["m.exr", "m.png"], &label).unwrap_or(false));
    }
    tally.check("shard mutants");
    std::fs::remove_dir_all(&base).ok();
}
