//! Hand-written hostile glTF files (tests/data/gltf/scenes) and a few generated ones: each is
//! refused with the right kind of error and none reads outside the scene's folder. The
//! sentinel `tests/data/gltf/sentinel.bin` beside that folder holds a valid triangle buffer,
//! so a loader that read it would *succeed*: the refusal kind proves it was not read.
//! (`known.gltf`, read against values worked out by hand, has its own test file.)

#[path = "support/scratch.rs"]
mod scratch;
use scratch::Scratch;

use std::path::{Path, PathBuf};

use glam::Vec3;
use pm_trace::gltf::{BufferError, GltfError, GltfOptions, MAX_DEPTH, read_content};

const SCENES: &str = concat!(env!("CARGO_MANIFEST_DIR"), "/tests/data/gltf/scenes");
const SENTINEL: &str = concat!(env!("CARGO_MANIFEST_DIR"), "/tests/data/gltf/sentinel.bin");

fn load(name: &str) -> Result<pm_trace::gltf::GltfContent, GltfError> {
    read_content(&Path::new(SCENES).join(name), &GltfOptions::default())
}

fn buffer_error(name: &str) -> BufferError {
    match load(name) {
        Err(GltfError::Buffer { reason, buffer, .. }) => {
            assert_eq!(buffer, 0);
            reason
        }
        other => panic!("{name}: expected a buffer error, got {other:?}"),
    }
}

fn triangle_gltf(uri: &str) -> String {
    format!(
        r#"{{"asset":{{"version":"2.0"}},"buffers":[{{"byteLength":36,"uri":{uri:?}}}],
        "bufferViews":[{{"buffer":0,"byteLength":36}}],
        "accessors":[{{"bufferView":0,"componentType":5126,"count":3,"type":"VEC3","min":[0,0,0],"max":[1,1,0]}}],
        "meshes":[{{"primitives":[{{"attributes":{{"POSITION":0}}}}]}}],
        "nodes":[{{"mesh":0}}],"scenes":[{{"nodes":[0]}}]}}"#
    )
}

#[test]
fn the_sentinel_is_a_loadable_buffer() {
    // Without this the refusals below would prove nothing: the sentinel, reached legally,
    // loads as a triangle.
    let scratch = Scratch::new("sentinel");
    std::fs::copy(SENTINEL, scratch.0.join("sentinel.bin")).unwrap();
    let file = scratch.0.join("ok.gltf");
    std::fs::write(&file, triangle_gltf("sentinel.bin")).unwrap();
    let content = read_content(&file, &GltfOptions::default()).unwrap();
    assert_eq!(content.triangle_count(), 1);
}

#[test]
fn parent_traversal_is_refused() {
    for name in [
        "traversal.gltf",
        "encoded_traversal.gltf",
        "encoded_dots_traversal.gltf",
        "dev_zero.gltf",
    ] {
        assert!(
            matches!(buffer_error(name), BufferError::EscapesFolder { .. }),
            "{name}"
        );
    }
}

#[test]
fn absolute_paths_are_refused() {
    for name in ["absolute.gltf", "encoded_absolute.gltf"] {
        assert!(
            matches!(buffer_error(name), BufferError::Absolute { .. }),
            "{name}"
        );
    }
    // The sentinel's real absolute path, which exists and would load.
    let scratch = Scratch::new("absolute");
    let file = scratch.0.join("abs.gltf");
    let sentinel = Path::new(SENTINEL).canonicalize().unwrap();
    std::fs::write(&file, triangle_gltf(sentinel.to_str().unwrap())).unwrap();
    let err = read_content(&file, &GltfOptions::default()).unwrap_err();
    assert!(
        matches!(
            &err,
            GltfError::Buffer {
                reason: BufferError::Absolute { .. },
                ..
            }
        ),
        "{err}"
    );
}

#[test]
fn schemes_are_refused() {
    for name in ["file_uri.gltf", "file_url_absolute.gltf", "http.gltf"] {
        assert!(matches!(buffer_error(name), BufferError::Scheme { .. }), "{name}");
    }
}

#[test]
fn invalid_percent_escape_is_an_error_not_a_panic() {
    assert!(matches!(
        buffer_error("bad_escape.gltf"),
        BufferError::BadEscape { .. }
    ));
}

#[test]
fn non_regular_and_missing_files_are_refused() {
    assert!(matches!(
        buffer_error("directory.gltf"),
        BufferError::NotRegularFile { .. }
    ));
    assert!(matches!(
        buffer_error("missing.gltf"),
        BufferError::Unreadable { .. }
    ));
}

#[test]
fn file_longer_than_its_byte_length_is_refused() {
    assert!(matches!(
        buffer_error("longer_than_declared.gltf"),
        BufferError::LongerThanDeclared { declared: 24 }
    ));
}

#[cfg(unix)]
#[test]
fn symlink_out_of_the_folder_is_refused() {
    let scratch = Scratch::new("symlink");
    let inner = scratch.0.join("scene");
    std::fs::create_dir(&inner).unwrap();
    std::fs::copy(SENTINEL, scratch.0.join("outside.bin")).unwrap();
    std::os::unix::fs::symlink(scratch.0.join("outside.bin"), inner.join("link.bin")).unwrap();
    let file = inner.join("s.gltf");
    std::fs::write(&file, triangle_gltf("link.bin")).unwrap();
    let err = read_content(&file, &GltfOptions::default()).unwrap_err();
    assert!(
        matches!(
            &err,
            GltfError::Buffer {
                reason: BufferError::EscapesFolder { .. },
                ..
            }
        ),
        "{err}"
    );
}

#[test]
fn percent_encoded_name_inside_the_folder_loads() {
    let content = load("valid_percent_encoded.gltf").unwrap();
    assert_eq!(content.triangle_count(), 1);
}

#[test]
fn cyclic_node_graph_is_an_error() {
    let err = load("cycle.gltf").unwrap_err();
    assert!(matches!(err, GltfError::Node { node: 0, .. }), "{err}");
    assert!(err.to_string().contains("cycle"), "{err}");
}

#[test]
fn node_chain_deeper_than_the_limit_is_an_error() {
    let scratch = Scratch::new("deep");
    let depth = MAX_DEPTH + 10;
    let nodes: Vec<String> = (0..depth)
        .map(|i| {
            if i + 1 < depth {
                format!(r#"{{"children":[{}]}}"#, i + 1)
            } else {
                r#"{"mesh":0}"#.to_owned()
            }
        })
        .collect();
    let json = triangle_gltf(
        "data:application/octet-stream;base64,AAAAAAAAAAAAAAAAAACAPwAAAAAAAAAAAAAAAAAAgD8AAAAA",
    )
    .replace(
        r#""nodes":[{"mesh":0}]"#,
        &format!(r#""nodes":[{}]"#, nodes.join(",")),
    );
    let file = scratch.0.join("deep.gltf");
    std::fs::write(&file, json).unwrap();
    let err = read_content(&file, &GltfOptions::default()).unwrap_err();
    assert!(
        matches!(&err, GltfError::Node { node, .. } if *node == MAX_DEPTH),
        "{err}"
    );
}

#[test]
fn accessor_count_beyond_its_buffer_is_an_error() {
    let err = load("huge_count.gltf").unwrap_err();
    assert!(matches!(err, GltfError::Accessor { accessor: 0, .. }), "{err}");
}

#[test]
fn index_out_of_range_names_mesh_primitive_and_index() {
    let err = load("index_out_of_range.gltf").unwrap_err();
    assert!(
        matches!(
            err,
            GltfError::Primitive {
                mesh: 0,
                primitive: 0,
                ..
            }
        ),
        "{err}"
    );
    assert!(
        err.to_string()
            .ends_with("mesh 0 primitive 0: index 255 out of range for 3 vertices"),
        "{err}"
    );
    assert!(err.to_string().contains("index_out_of_range.gltf"), "{err}");
}

#[test]
fn non_finite_position_is_an_error() {
    let err = load("non_finite_position.gltf").unwrap_err();
    assert!(matches!(err, GltfError::Primitive { .. }), "{err}");
    assert!(err.to_string().contains("position 1 is not finite"), "{err}");
}

fn glb(json: &str, bin: &[u8]) -> Vec<u8> {
    let mut json = json.as_bytes().to_vec();
    while !json.len().is_multiple_of(4) {
        json.push(b' ');
    }
    let total = 12 + 8 + json.len() + 8 + bin.len();
    let mut out = Vec::new();
    out.extend_from_slice(b"glTF");
    out.extend_from_slice(&2u32.to_le_bytes());
    out.extend_from_slice(&(total as u32).to_le_bytes());
    out.extend_from_slice(&(json.len() as u32).to_le_bytes());
    out.extend_from_slice(b"JSON");
    out.extend_from_slice(&json);
    out.extend_from_slice(&(bin.len() as u32).to_le_bytes());
    out.extend_from_slice(b"BIN\0");
    out.extend_from_slice(bin);
    out
}

#[test]
fn glb_with_bin_chunk_loads_and_lying_lengths_are_refused() {
    let scratch = Scratch::new("glb");
    let json = triangle_gltf("x").replace(r#","uri":"x""#, "");
    let bin = std::fs::read(SENTINEL).unwrap();
    let good = glb(&json, &bin);
    let file = scratch.0.join("good.glb");
    std::fs::write(&file, &good).unwrap();
    let content = read_content(&file, &GltfOptions::default()).unwrap();
    assert_eq!(content.meshes[0].positions[1], Vec3::X);

    // Header length larger than the file, then a BIN chunk length past the end.
    let mut lying = good.clone();
    lying[8..12].copy_from_slice(&u32::MAX.to_le_bytes());
    let mut chunk = good.clone();
    let bin_header = good.len() - bin.len() - 8;
    chunk[bin_header..bin_header + 4].copy_from_slice(&1000u32.to_le_bytes());
    for (name, bytes) in [
        ("lying.glb", lying),
        ("chunk.glb", chunk),
        ("cut.glb", good[..30].to_vec()),
    ] {
        let file = scratch.0.join(name);
        std::fs::write(&file, bytes).unwrap();
        let err = read_content(&file, &GltfOptions::default()).unwrap_err();
        assert!(matches!(err, GltfError::Glb { .. }), "{name}: {err}");
    }
}

fn sparse_gltf(sparse_index: u8) -> (Scratch, PathBuf) {
    let scratch = Scratch::new(&format!("sparse{sparse_index}"));
    let mut bin = std::fs::read(SENTINEL).unwrap(); // (0,0,0), (1,0,0), (0,1,0)
    bin.extend_from_slice(&[sparse_index, 0, 0, 0]);
    for c in [5.0f32, 6.0, 7.0] {
        bin.extend_from_slice(&c.to_le_bytes());
    }
    std::fs::write(scratch.0.join("s.bin"), &bin).unwrap();
    let json = r#"{"asset":{"version":"2.0"},"buffers":[{"byteLength":52,"uri":"s.bin"}],
        "bufferViews":[{"buffer":0,"byteLength":36},{"buffer":0,"byteOffset":36,"byteLength":1},
                       {"buffer":0,"byteOffset":40,"byteLength":12}],
        "accessors":[{"bufferView":0,"componentType":5126,"count":3,"type":"VEC3","min":[0,0,0],"max":[5,6,7],
          "sparse":{"count":1,"indices":{"bufferView":1,"componentType":5121},"values":{"bufferView":2}}}],
        "meshes":[{"primitives":[{"attributes":{"POSITION":0}}]}],
        "nodes":[{"mesh":0}],"scenes":[{"nodes":[0]}]}"#;
    let file = scratch.0.join("s.gltf");
    std::fs::write(&file, json).unwrap();
    (scratch, file)
}

#[test]
fn sparse_accessor_replaces_the_listed_element() {
    let (_scratch, file) = sparse_gltf(1);
    let content = read_content(&file, &GltfOptions::default()).unwrap();
    assert_eq!(
        content.meshes[0].positions,
        vec![Vec3::ZERO, Vec3::new(5.0, 6.0, 7.0), Vec3::Y]
    );
    let (_scratch, file) = sparse_gltf(3);
    let err = read_content(&file, &GltfOptions::default()).unwrap_err();
    assert!(
        err.to_string()
            .contains("sparse index 3 out of range for 3 elements"),
        "{err}"
    );
}

#[test]
fn instancing_past_the_triangle_budget_is_an_error_not_an_allocation() {
    // A few kilobytes of JSON: one triangle placed by 2,000 nodes. With a budget below that the
    // load stops with an error; with room to spare every placement is there.
    let scratch = Scratch::new("instancing");
    std::fs::copy(Path::new(SCENES).join("tri.bin"), scratch.0.join("tri.bin")).unwrap();
    let nodes: Vec<String> = (0..2000).map(|_| r#"{"mesh":0}"#.to_string()).collect();
    let roots: Vec<String> = (0..2000).map(|i| i.to_string()).collect();
    let text = triangle_gltf("tri.bin").replace(
        r#""nodes":[{"mesh":0}],"scenes":[{"nodes":[0]}]"#,
        &format!(
            r#""nodes":[{}],"scenes":[{{"nodes":[{}]}}]"#,
            nodes.join(","),
            roots.join(",")
        ),
    );
    let path = scratch.0.join("instanced.gltf");
    std::fs::write(&path, text).unwrap();
    let tight = GltfOptions {
        max_triangles: 1999,
        ..GltfOptions::default()
    };
    match read_content(&path, &tight) {
        Err(GltfError::Node { reason, .. }) => assert!(reason.contains("max_triangles"), "{reason}"),
        other => panic!("expected the triangle budget to stop the load, got {other:?}"),
    }
    let roomy = GltfOptions {
        max_triangles: 2000,
        ..GltfOptions::default()
    };
    let content = read_content(&path, &roomy).unwrap();
    assert_eq!(
        content.meshes.iter().map(|m| m.triangles.len()).sum::<usize>(),
        2000
    );
}
