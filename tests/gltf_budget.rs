//! The glTF loader within bounded memory, counted: a global allocator tracks the bytes live on
//! the heap while files built here are loaded. Instancing (one mesh placed by thousands of
//! nodes), many triangles, and many `buffers` entries naming one file must either load within
//! the byte budget (`GltfOptions::max_scene_bytes`, `max_file_bytes`) or stop with a typed
//! error naming it, never allocate past it.

#[path = "support/scratch.rs"]
mod scratch;
use scratch::{Scratch, glb};

use photon_maps::trace::gltf::{BufferError, GltfError, GltfOptions, load_scene_with};
use proptest::prelude::*;
use std::path::{Path, PathBuf};
use std::sync::Mutex;

#[path = "support/tracking_allocator.rs"]
mod tracking_allocator;

/// One measurement at a time: the tests of this file share the counters.
static MEASURE: Mutex<()> = Mutex::new(());

/// Runs `f` and returns its result with the peak heap growth above what was live before.
fn peak_growth<T>(f: impl FnOnce() -> T) -> (T, usize) {
    let base = tracking_allocator::reset_peak();
    let out = f();
    (out, tracking_allocator::peak().saturating_sub(base))
}

/// A GLB holding one mesh of `vertices` positions (at least 3 per triangle) and `triangles`
/// indexed triangles, placed by `placements` nodes (each moved along z), with an emissive
/// material so the scene has a light.
fn instanced_glb(vertices: usize, triangles: usize, placements: usize) -> Vec<u8> {
    let vertices = vertices.max(3 * triangles);
    let mut bin = Vec::with_capacity(vertices * 12 + triangles * 12);
    for j in 0..vertices {
        let (i, corner) = ((j / 3) as f32, j % 3);
        let p = [i, (corner == 1) as u8 as f32, (corner == 2) as u8 as f32];
        for c in p {
            bin.extend_from_slice(&c.to_le_bytes());
        }
    }
    for t in 0..triangles as u32 {
        for k in 0..3 {
            bin.extend_from_slice(&(3 * t + k).to_le_bytes());
        }
    }
    let positions_len = vertices * 12;
    let nodes: Vec<String> = (0..placements)
        .map(|k| format!(r#"{{"mesh":0,"translation":[0,0,{}]}}"#, 2 * k))
        .collect();
    let roots: Vec<String> = (0..placements).map(|k| k.to_string()).collect();
    let max_x = (vertices / 3).max(1) - 1;
    let json = format!(
        concat!(
            r#"{{"asset":{{"version":"2.0"}},"scene":0,"scenes":[{{"nodes":[{roots}]}}],"nodes":[{nodes}],"#,
            r#""materials":[{{"emissiveFactor":[1,1,1]}}],"#,
            r#""meshes":[{{"primitives":[{{"attributes":{{"POSITION":0}},"indices":1,"material":0}}]}}],"#,
            r#""buffers":[{{"byteLength":{total}}}],"#,
            r#""bufferViews":[{{"buffer":0,"byteLength":{positions_len}}},{{"buffer":0,"byteOffset":{positions_len},"byteLength":{indices_len}}}],"#,
            r#""accessors":[{{"bufferView":0,"componentType":5126,"count":{vertices},"type":"VEC3","min":[0,0,0],"max":[{max_x},1,1]}},"#,
            r#"{{"bufferView":1,"componentType":5125,"count":{index_count},"type":"SCALAR"}}]}}"#
        ),
        roots = roots.join(","),
        nodes = nodes.join(","),
        total = bin.len(),
        positions_len = positions_len,
        indices_len = triangles * 12,
        vertices = vertices,
        max_x = max_x,
        index_count = triangles * 3,
    );
    glb(&json, &bin)
}

fn write(dir: &Path, name: &str, bytes: &[u8]) -> PathBuf {
    let path = dir.join(name);
    std::fs::write(&path, bytes).unwrap();
    path
}

/// Slack over the budget for what is not counted: the parsed JSON document, the node walk, the
/// error's strings, the allocator's rounding.
const SLACK: usize = 4 << 20;

#[test]
fn instancing_a_mesh_of_many_vertices_decodes_it_once_within_the_budget() {
    let _lock = MEASURE.lock().unwrap_or_else(|p| p.into_inner());
    // 20,000 positions (240 KB) and one triangle, placed by 5,000 nodes: 100 million vertices
    // decoded (2.4 GB of positions) if each placement decoded them again. Decoded once, each
    // placement holds the triangle's three vertices.
    let scratch = Scratch::new("vertices");
    let file = write(&scratch.0, "placed.glb", &instanced_glb(20_000, 1, 5_000));
    let budget = 64u64 << 20;
    let options = GltfOptions {
        max_scene_bytes: budget,
        ..GltfOptions::default()
    };
    let (result, peak) = peak_growth(|| load_scene_with(&file, &options));
    let scene = result.unwrap();
    assert_eq!(scene.meshes().len(), 5_000);
    assert!(
        scene
            .meshes()
            .iter()
            .all(|m| m.half_edge_mesh().vertex_count() == 3)
    );
    println!("instanced vertices: loaded with a peak of {peak} bytes for a {budget}-byte budget");
    assert!(
        peak <= budget as usize + SLACK,
        "peak {peak} past the budget {budget}"
    );
    // A budget smaller than the one decode: refused before decoding, naming the budget.
    let small = 1u64 << 20;
    let options = GltfOptions {
        max_scene_bytes: small,
        ..GltfOptions::default()
    };
    let (result, peak) = peak_growth(|| load_scene_with(&file, &options));
    let err = result.unwrap_err();
    assert!(
        matches!(err, GltfError::SceneTooLarge { budget: b, .. } if b == small),
        "{err}"
    );
    assert!(err.to_string().contains("max_scene_bytes"), "{err}");
    assert_eq!(err.to_string().lines().count(), 1, "{err}");
    assert!(
        peak <= small as usize + SLACK,
        "peak {peak} past the budget {small}"
    );
}

#[test]
fn a_small_file_placing_millions_of_triangles_is_refused_before_the_scene_is_built() {
    let _lock = MEASURE.lock().unwrap_or_else(|p| p.into_inner());
    // 1,000 triangles placed 20,000 times: 20 million triangles (within max_triangles), about
    // 9 GB while building; the default 4 GiB budget refuses it, here a smaller one.
    let scratch = Scratch::new("triangles");
    let file = write(&scratch.0, "many.glb", &instanced_glb(3_000, 1_000, 20_000));
    let budget = 128u64 << 20;
    let options = GltfOptions {
        max_scene_bytes: budget,
        ..GltfOptions::default()
    };
    let (result, peak) = peak_growth(|| load_scene_with(&file, &options));
    let err = result.unwrap_err();
    assert_eq!(err.kind(), "scene-too-large", "{err}");
    println!("instanced triangles: refused with a peak of {peak} bytes for a {budget}-byte budget");
    assert!(
        peak <= budget as usize + SLACK,
        "peak {peak} past the budget {budget}"
    );
    // The default budget refuses it too (counted, nothing decoded past it).
    let default = GltfOptions::default();
    assert!(20_000_000 * GltfOptions::BYTES_PER_TRIANGLE > default.max_scene_bytes);
}

#[test]
fn the_documented_costs_bound_the_measured_peak_of_a_loaded_scene() {
    let _lock = MEASURE.lock().unwrap_or_else(|p| p.into_inner());
    // A scene that fits: its peak while loading and building must stay within what the budget
    // counts for it (so the documented per-vertex and per-triangle costs are true bounds). Its
    // material is emissive, so every triangle is an area light's too.
    let scratch = Scratch::new("fits");
    let (vertices, triangles, placements) = (6_000usize, 2_000usize, 20usize);
    let bytes = instanced_glb(vertices, triangles, placements);
    let file = write(&scratch.0, "fits.glb", &bytes);
    let (scene, peak) = peak_growth(|| load_scene_with(&file, &GltfOptions::default()));
    let scene = scene.unwrap();
    let counted = bytes.len() as u64
        + (placements * vertices) as u64 * GltfOptions::BYTES_PER_VERTEX
        + (placements * triangles) as u64
            * (GltfOptions::BYTES_PER_TRIANGLE + GltfOptions::BYTES_PER_EMITTING_TRIANGLE);
    println!(
        "{} triangles: peak {peak} bytes, counted {counted} ({:.0} bytes per triangle at the peak, the scene keeps {})",
        placements * triangles,
        peak as f64 / (placements * triangles) as f64,
        scene.heap_bytes()
    );
    assert!(
        peak as u64 <= counted + SLACK as u64,
        "peak {peak} > counted {counted}"
    );
}

#[test]
fn many_buffer_entries_naming_one_file_read_it_once() {
    let _lock = MEASURE.lock().unwrap_or_else(|p| p.into_inner());
    // 400 buffers naming one 256 KiB file: 100 MiB if each entry read the file again.
    let scratch = Scratch::new("buffers");
    let size = 256 << 10;
    let mut data = vec![0u8; size];
    for (i, c) in [0f32, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 1.0, 0.0].iter().enumerate() {
        data[4 * i..4 * i + 4].copy_from_slice(&c.to_le_bytes());
    }
    write(&scratch.0, "data.bin", &data);
    let buffers: Vec<String> = (0..400)
        .map(|_| format!(r#"{{"uri":"data.bin","byteLength":{size}}}"#))
        .collect();
    let json = format!(
        concat!(
            r#"{{"asset":{{"version":"2.0"}},"scenes":[{{"nodes":[0]}}],"nodes":[{{"mesh":0}}],"#,
            r#""meshes":[{{"primitives":[{{"attributes":{{"POSITION":0}}}}]}}],"#,
            r#""buffers":[{buffers}],"bufferViews":[{{"buffer":399,"byteLength":36}}],"#,
            r#""accessors":[{{"bufferView":0,"componentType":5126,"count":3,"type":"VEC3","min":[0,0,0],"max":[1,1,0]}}]}}"#
        ),
        buffers = buffers.join(",")
    );
    let file = write(&scratch.0, "shared.gltf", json.as_bytes());
    let (result, peak) = peak_growth(|| load_scene_with(&file, &GltfOptions::default()));
    result.unwrap();
    println!("400 entries of one {size}-byte file: peak {peak} bytes");
    assert!(
        peak < 4 * size + SLACK,
        "peak {peak}: the file was read more than once"
    );

    // Distinct files past the total limit: a typed error naming it.
    write(&scratch.0, "other.bin", &data);
    let two = json.replacen(r#""uri":"data.bin""#, r#""uri":"other.bin""#, 1);
    let file = write(&scratch.0, "two.gltf", two.as_bytes());
    let tight = GltfOptions {
        max_file_bytes: (size + size / 2) as u64,
        ..GltfOptions::default()
    };
    let err = load_scene_with(&file, &tight).unwrap_err();
    assert!(
        matches!(
            &err,
            GltfError::Buffer {
                reason: BufferError::TotalTooLarge { .. },
                ..
            }
        ),
        "{err}"
    );
}

#[test]
fn a_triangle_fan_of_60k_vertices_loads() {
    let _lock = MEASURE.lock().unwrap_or_else(|p| p.into_inner());
    // Degenerate for a BVH builder: every triangle shares vertex 0 (quadratic in obvhs's PLOC).
    let n = 60_000usize;
    let mut bin = Vec::with_capacity(n * 12);
    bin.extend_from_slice(&[0u8; 12]);
    for i in 1..n {
        let a = i as f32 / n as f32 * std::f32::consts::PI;
        for c in [a.cos(), a.sin(), 0.0] {
            bin.extend_from_slice(&c.to_le_bytes());
        }
    }
    let json = format!(
        concat!(
            r#"{{"asset":{{"version":"2.0"}},"scenes":[{{"nodes":[0]}}],"nodes":[{{"mesh":0}}],"#,
            r#""meshes":[{{"primitives":[{{"attributes":{{"POSITION":0}},"mode":6}}]}}],"#,
            r#""buffers":[{{"byteLength":{len}}}],"bufferViews":[{{"buffer":0,"byteLength":{len}}}],"#,
            r#""accessors":[{{"bufferView":0,"componentType":5126,"count":{n},"type":"VEC3","min":[-1,0,0],"max":[1,1,0]}}]}}"#
        ),
        len = bin.len(),
        n = n
    );
    let scratch = Scratch::new("fan");
    let file = write(&scratch.0, "fan.glb", &glb(&json, &bin));
    let scene = load_scene_with(&file, &GltfOptions::default()).unwrap();
    assert!(scene.heap_bytes() > 0);
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(24))]

    /// Whatever the instancing, vertex and triangle counts: a scene within the budget, or a
    /// typed error naming it, and never a peak past the budget.
    #[test]
    fn extreme_instancing_stays_within_the_budget(
        vertices in 3usize..30_000,
        triangles in 1usize..2_000,
        placements in 1usize..3_000,
        budget_mib in 8u64..64,
    ) {
        let _lock = MEASURE.lock().unwrap_or_else(|p| p.into_inner());
        let scratch = Scratch::new("prop");
        let file = write(&scratch.0, "p.glb", &instanced_glb(vertices, triangles, placements));
        let budget = budget_mib << 20;
        let options = GltfOptions { max_scene_bytes: budget, ..GltfOptions::default() };
        let (result, peak) = peak_growth(|| load_scene_with(&file, &options));
        match result {
            Ok(_) => {}
            Err(e) => prop_assert_eq!(e.kind(), "scene-too-large", "{}", e),
        }
        prop_assert!(peak <= budget as usize + SLACK, "peak {} past the budget {}", peak, budget);
    }
}
