//! Work the glTF loader shares instead of repeating: an image named by many textures is
//! decoded once (and its decode is checked against the byte budget from its header, before
//! it starts), and a primitive keeps only the vertices its triangles use, however large the
//! accessor and however many nodes place it.

#[path = "support/scratch.rs"]
mod scratch;
use scratch::{Scratch, glb};

#[path = "support/tracking_allocator.rs"]
mod tracking_allocator;

use photon_maps::trace::gltf::{GltfError, GltfOptions, load_scene_with, read_content};
use std::path::Path;
use std::sync::{Arc, Mutex};
use std::time::{Duration, Instant};

/// One measurement at a time: the tests of this file share the allocator's counters.
static MEASURE: Mutex<()> = Mutex::new(());

/// A black `side × side` RGB PNG (compresses to a few kilobytes at any size).
fn black_png(side: u32) -> Vec<u8> {
    let mut out = Vec::new();
    let mut e = png::Encoder::new(&mut out, side, side);
    e.set_color(png::ColorType::Rgb);
    e.set_depth(png::BitDepth::Eight);
    let mut w = e.write_header().unwrap();
    w.write_image_data(&vec![0u8; (side * side * 3) as usize])
        .unwrap();
    w.finish().unwrap();
    out
}

/// `count` textured quads, each with its own material and texture, every texture naming
/// image 0, a `side²` PNG in the binary chunk; a point lamp above.
fn shared_image_glb(count: usize, side: u32) -> Vec<u8> {
    let positions: [[f32; 3]; 4] = [[0.0, 0.0, 0.0], [0.0, 0.0, 1.0], [1.0, 0.0, 1.0], [1.0, 0.0, 0.0]];
    let uvs: [[f32; 2]; 4] = [[0.0, 0.0], [0.0, 1.0], [1.0, 1.0], [1.0, 0.0]];
    let mut bin: Vec<u8> = positions.iter().flatten().flat_map(|f| f.to_le_bytes()).collect();
    bin.extend(uvs.iter().flatten().flat_map(|f| f.to_le_bytes()));
    bin.extend([0u32, 1, 2, 0, 2, 3].iter().flat_map(|i| i.to_le_bytes()));
    let png = black_png(side);
    let png_at = bin.len();
    bin.extend(&png);
    let list = |f: &dyn Fn(usize) -> String| (0..count).map(f).collect::<Vec<_>>().join(",");
    let meshes = list(&|i| {
        format!(
            r#"{{"primitives":[{{"attributes":{{"POSITION":0,"TEXCOORD_0":1}},"indices":2,"material":{i}}}]}}"#
        )
    });
    let materials = list(&|i| {
        format!(r#"{{"pbrMetallicRoughness":{{"baseColorTexture":{{"index":{i}}},"metallicFactor":0}}}}"#)
    });
    let textures = list(&|_| r#"{"source":0}"#.to_owned());
    let mut nodes: Vec<String> = (0..count).map(|i| format!(r#"{{"mesh":{i}}}"#)).collect();
    nodes.push(r#"{"translation":[0.5,1,0.5],"extensions":{"KHR_lights_punctual":{"light":0}}}"#.into());
    let all = (0..nodes.len())
        .map(|i| i.to_string())
        .collect::<Vec<_>>()
        .join(",");
    let json = format!(
        r#"{{"asset":{{"version":"2.0"}},"extensionsUsed":["KHR_lights_punctual"],
        "extensions":{{"KHR_lights_punctual":{{"lights":[{{"type":"point","intensity":10}}]}}}},
        "buffers":[{{"byteLength":{}}}],
        "bufferViews":[{{"buffer":0,"byteOffset":0,"byteLength":48}},{{"buffer":0,"byteOffset":48,"byteLength":32}},
            {{"buffer":0,"byteOffset":80,"byteLength":24}},{{"buffer":0,"byteOffset":{png_at},"byteLength":{}}}],
        "accessors":[{{"bufferView":0,"componentType":5126,"count":4,"type":"VEC3","min":[0,0,0],"max":[1,0,1]}},
            {{"bufferView":1,"componentType":5126,"count":4,"type":"VEC2"}},
            {{"bufferView":2,"componentType":5125,"count":6,"type":"SCALAR"}}],
        "images":[{{"bufferView":3,"mimeType":"image/png"}}],
        "textures":[{textures}],"materials":[{materials}],"meshes":[{meshes}],
        "nodes":[{}],"scenes":[{{"nodes":[{all}]}}],"scene":0}}"#,
        bin.len(),
        png.len(),
        nodes.join(","),
    );
    glb(&json, &bin)
}

#[test]
fn an_image_named_by_forty_textures_is_decoded_once() {
    let _one = MEASURE.lock().unwrap_or_else(|e| e.into_inner());
    let scratch = Scratch::new("forty");
    let path = scratch.0.join("forty.glb");
    let side = 512;
    std::fs::write(&path, shared_image_glb(40, side)).unwrap();
    let base = tracking_allocator::reset_peak();
    let content = read_content(&path, &GltfOptions::default()).unwrap();
    let peak = tracking_allocator::peak() - base;
    assert_eq!(content.meshes.len(), 40);
    let first = content.meshes[0].base_color_texture.as_ref().unwrap().0.clone();
    for mesh in &content.meshes {
        let (texture, _) = mesh.base_color_texture.as_ref().unwrap();
        assert!(
            Arc::ptr_eq(texture, &first),
            "mesh {} has its own decode",
            mesh.mesh
        );
    }
    // One decode holds at most 12 bytes a texel at its peak; forty would hold forty times
    // the texels.
    let one_decode = 12 * (side * side) as usize;
    assert!(
        peak < 2 * one_decode,
        "peak {peak} B against {one_decode} B for one decode"
    );
}

#[test]
fn an_image_past_the_byte_budget_is_refused_from_its_header_before_decoding() {
    let _one = MEASURE.lock().unwrap_or_else(|e| e.into_inner());
    let scratch = Scratch::new("budget");
    let path = scratch.0.join("big.glb");
    let side = 2048u32;
    std::fs::write(&path, shared_image_glb(2, side)).unwrap();
    let options = GltfOptions {
        max_scene_bytes: 8 << 20,
        ..GltfOptions::default()
    };
    let base = tracking_allocator::reset_peak();
    let err = read_content(&path, &options).map(|_| ()).unwrap_err();
    let peak = tracking_allocator::peak() - base;
    match &err {
        GltfError::Image { image: 0, reason, .. } => assert!(reason.contains("max_scene_bytes"), "{reason}"),
        other => panic!("{other}"),
    }
    // The decode would hold 48 MiB (its 4 Mi texels); nothing near that was allocated.
    assert!(peak < 8 << 20, "peak {peak} B before the refusal");
    assert!(read_content(&path, &GltfOptions::default()).is_ok());
}

/// One triangle of an accessor of `vertices` vertices, placed by `nodes` nodes (each moved
/// up by its index), and a lamp.
fn instanced_triangle_glb(vertices: usize, nodes: usize) -> Vec<u8> {
    let mut bin: Vec<u8> = (0..vertices)
        .flat_map(|i| [i as f32 * 1e-3, (i % 2) as f32, (i % 7) as f32])
        .flat_map(f32::to_le_bytes)
        .collect();
    let indices_at = bin.len();
    bin.extend([0u32, 1, 2].iter().flat_map(|i| i.to_le_bytes()));
    let mut node_list: Vec<String> = (0..nodes)
        .map(|i| format!(r#"{{"mesh":0,"translation":[0,{},0]}}"#, i as f32 * 0.01))
        .collect();
    node_list.push(r#"{"translation":[0,5,0],"extensions":{"KHR_lights_punctual":{"light":0}}}"#.into());
    let all = (0..node_list.len())
        .map(|i| i.to_string())
        .collect::<Vec<_>>()
        .join(",");
    let max_x = (vertices - 1) as f32 * 1e-3;
    let json = format!(
        r#"{{"asset":{{"version":"2.0"}},"extensionsUsed":["KHR_lights_punctual"],
        "extensions":{{"KHR_lights_punctual":{{"lights":[{{"type":"point","intensity":10}}]}}}},
        "buffers":[{{"byteLength":{}}}],
        "bufferViews":[{{"buffer":0,"byteOffset":0,"byteLength":{indices_at}}},{{"buffer":0,"byteOffset":{indices_at},"byteLength":12}}],
        "accessors":[{{"bufferView":0,"componentType":5126,"count":{vertices},"type":"VEC3","min":[0,0,0],"max":[{max_x},1,6]}},
            {{"bufferView":1,"componentType":5125,"count":3,"type":"SCALAR"}}],
        "meshes":[{{"primitives":[{{"attributes":{{"POSITION":0}},"indices":1}}]}}],
        "nodes":[{}],"scenes":[{{"nodes":[{all}]}}],"scene":0}}"#,
        bin.len(),
        node_list.join(","),
    );
    glb(&json, &bin)
}

#[test]
fn a_triangle_placed_a_hundred_times_keeps_three_vertices_per_placement() {
    // Its allocations would count in the other tests' peaks.
    let _one = MEASURE.lock().unwrap_or_else(|e| e.into_inner());
    let scratch = Scratch::new("instanced");
    let path = scratch.0.join("instanced.glb");
    // 100,000 vertices, one triangle, 100 nodes: the weld ran over all 100,000 at every
    // placement (35 s; 300 nodes, over a minute).
    std::fs::write(&path, instanced_triangle_glb(100_000, 100)).unwrap();
    let start = Instant::now();
    let scene = load_scene_with(&path, &GltfOptions::default()).unwrap();
    // A bound for a hang, not a timing claim: the load takes a fraction of a second.
    assert!(start.elapsed() < Duration::from_secs(20), "{:?}", start.elapsed());
    assert_eq!(scene.meshes().len(), 100);
    for mesh in scene.meshes() {
        assert_eq!(mesh.half_edge_mesh().vertex_count(), 3);
    }
    let content = read_content(Path::new(&path), &GltfOptions::default()).unwrap();
    assert!(
        content
            .meshes
            .iter()
            .all(|m| m.positions.len() == 3 && m.triangles == [[0, 1, 2]])
    );
}
