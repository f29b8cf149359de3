//! Node transforms keep the file's f64 digits (issue 33): sibling nodes a UTM northing out
//! (5,712,345 m, where f32's step is 0.5 m) land where the file's decimal text puts them, to
//! within the re-centred scene's own f32 precision, for `translation` and for `matrix`, in
//! `.gltf` and `.glb`. The truth is computed here in f64 from the text's numbers and the
//! accessor's f32 vertices. Hostile node fields are refused with a typed error, never a panic.

#[path = "support/scratch.rs"]
mod scratch;

use std::panic::{AssertUnwindSafe, catch_unwind};
use std::path::{Path, PathBuf};

use glam::{DMat4, DVec3, Vec3};
use pm_trace::gltf::{GltfContent, GltfOptions, read_content};
use scratch::{Scratch, glb};

/// The one triangle every node places, in the accessor's f32.
const TRIANGLE: [[f32; 3]; 3] = [[0.0, 0.0, 0.0], [0.1, 0.0, 0.0], [0.0, 0.1, 0.0]];

/// The triangle's buffer: three f32 positions.
fn triangle_bytes() -> Vec<u8> {
    TRIANGLE.iter().flatten().flat_map(|v| v.to_le_bytes()).collect()
}

/// A glTF document whose root nodes are `nodes` (JSON objects written out as given, each
/// placing mesh 0, the triangle); `uri` is the buffer's URI, `None` for a GLB's binary chunk.
fn document(nodes: &[String], uri: Option<&str>) -> String {
    let uri = uri.map_or(String::new(), |u| format!(r#","uri":"{u}""#));
    let roots: Vec<String> = (0..nodes.len()).map(|i| i.to_string()).collect();
    format!(
        r#"{{"asset":{{"version":"2.0"}},"buffers":[{{"byteLength":36{uri}}}],
        "bufferViews":[{{"buffer":0,"byteLength":36}}],
        "accessors":[{{"bufferView":0,"componentType":5126,"count":3,"type":"VEC3","min":[0,0,0],"max":[0.1,0.1,0]}}],
        "meshes":[{{"primitives":[{{"attributes":{{"POSITION":0}}}}]}}],
        "nodes":[{}],"scenes":[{{"nodes":[{}]}}],"scene":0}}"#,
        nodes.join(","),
        roots.join(",")
    )
}

/// Writes `nodes` as `name.gltf` (buffer as a data: URI) and as `name.glb`; returns both paths.
fn write_both(scratch: &Scratch, name: &str, nodes: &[String]) -> [PathBuf; 2] {
    let hex: String = triangle_bytes().iter().map(|b| format!("%{b:02X}")).collect();
    let uri = format!("data:application/octet-stream,{hex}");
    let gltf = scratch.0.join(format!("{name}.gltf"));
    std::fs::write(&gltf, document(nodes, Some(&uri))).unwrap();
    let binary = scratch.0.join(format!("{name}.glb"));
    std::fs::write(&binary, glb(&document(nodes, None), &triangle_bytes())).unwrap();
    [gltf, binary]
}

/// The world position (f64, the file's coordinates) of every vertex each node placed, from
/// the loaded content: `origin_offset + p`.
fn world_vertices(content: &GltfContent, node: usize) -> Vec<DVec3> {
    let mesh = content.meshes.iter().find(|m| m.node == node).unwrap();
    mesh.positions
        .iter()
        .map(|p| content.origin_offset + p.as_dvec3())
        .collect()
}

/// The tolerance for a loaded world position: f32 rounding at the re-centred scene's own
/// coordinates (a few steps at the largest one), plus f64's at the offset.
fn tolerance(content: &GltfContent) -> f64 {
    let largest = content
        .meshes
        .iter()
        .flat_map(|m| m.positions.iter())
        .fold(0.0f32, |a, p| a.max(p.abs().max_element()));
    4.0 * f64::from(f32::EPSILON) * f64::from(largest)
        + 8.0 * f64::EPSILON * content.origin_offset.abs().max_element()
}

/// Checks every node's vertices against `truth(node, local vertex)`, and each pair of nodes'
/// separation against the truth's (after printing both largest errors, metres).
fn check_against_truth(path: &Path, nodes: usize, truth: impl Fn(usize, DVec3) -> DVec3) {
    let content = read_content(path, &GltfOptions::default()).unwrap();
    let tolerance = tolerance(&content);
    // Re-centred: the scene's coordinates are the model's size, not the northing's.
    assert!(tolerance < 1e-6, "{}: tolerance {tolerance}", path.display());
    let local: Vec<DVec3> = TRIANGLE.iter().map(|v| Vec3::from(*v).as_dvec3()).collect();
    let mut placed = Vec::new();
    for node in 0..nodes {
        for (got, v) in world_vertices(&content, node).iter().zip(&local) {
            placed.push((node, *v, *got, truth(node, *v)));
        }
    }
    let mut apart = Vec::new();
    for a in 0..nodes {
        for b in a + 1..nodes {
            let got = world_vertices(&content, a)[0] - world_vertices(&content, b)[0];
            apart.push((a, b, got, truth(a, local[0]) - truth(b, local[0])));
        }
    }
    let error = |got: DVec3, want: DVec3| (got - want).abs().max_element();
    let worst = |errors: &mut dyn Iterator<Item = f64>| errors.fold(0.0, f64::max);
    eprintln!(
        "{}: largest position error {:e} m, largest separation error {:e} m (tolerance {tolerance:e})",
        path.display(),
        worst(&mut placed.iter().map(|&(_, _, got, want)| error(got, want))),
        worst(&mut apart.iter().map(|&(_, _, got, want)| error(got, want))),
    );
    for (node, v, got, want) in placed {
        assert!(
            error(got, want) <= tolerance,
            "{}: node {node} vertex {v} at {got}, the file says {want}",
            path.display()
        );
    }
    for (a, b, got, want) in apart {
        assert!(
            error(got, want) <= tolerance,
            "{}: nodes {a} and {b} {got} apart, the file says {want}",
            path.display()
        );
    }
}

/// Easting, height and (negated) northing of the two siblings: 0.3 m apart along x and z,
/// neither representable in f32 (f32 rounds both northings to 5,712,345.5, one on top of the
/// other, and the eastings 0.3125 m apart).
const SIBLINGS: [[f64; 3]; 2] = [
    [412_345.678, 87.125, -5_712_345.678],
    [412_345.378, 87.125, -5_712_345.378],
];

#[test]
fn sibling_translations_a_northing_out_keep_their_decimal_places() {
    let scratch = Scratch::new("siblings");
    let nodes: Vec<String> = SIBLINGS
        .iter()
        .map(|t| format!(r#"{{"mesh":0,"translation":[{},{},{}]}}"#, t[0], t[1], t[2]))
        .collect();
    for path in write_both(&scratch, "siblings", &nodes) {
        check_against_truth(&path, 2, |node, v| DVec3::from(SIBLINGS[node]) + v);
    }
}

#[test]
fn sibling_matrices_a_northing_out_keep_their_decimal_places() {
    let scratch = Scratch::new("matrices");
    // Node 0: a quarter turn about +y; node 1: a uniform scale of 2.5. Column-major, the
    // translation in the last column.
    let linear: [[f64; 9]; 2] = [
        [0.0, 0.0, -1.0, 0.0, 1.0, 0.0, 1.0, 0.0, 0.0],
        [2.5, 0.0, 0.0, 0.0, 2.5, 0.0, 0.0, 0.0, 2.5],
    ];
    let matrices: Vec<[f64; 16]> = (0..2)
        .map(|n| {
            let (l, t) = (linear[n], SIBLINGS[n]);
            [
                l[0], l[1], l[2], 0.0, l[3], l[4], l[5], 0.0, l[6], l[7], l[8], 0.0, t[0], t[1], t[2], 1.0,
            ]
        })
        .collect();
    let nodes: Vec<String> = matrices
        .iter()
        .map(|m| {
            let values: Vec<String> = m.iter().map(f64::to_string).collect();
            format!(r#"{{"mesh":0,"matrix":[{}]}}"#, values.join(","))
        })
        .collect();
    for path in write_both(&scratch, "matrices", &nodes) {
        check_against_truth(&path, 2, |node, v| {
            DMat4::from_cols_array(&matrices[node]).transform_point3(v)
        });
    }
}

#[test]
fn hostile_node_fields_are_typed_errors_not_panics() {
    let scratch = Scratch::new("hostile");
    let cases = [
        r#""translation":[1,2]"#,
        r#""translation":[1,2,3,4]"#,
        r#""translation":["a",0,0]"#,
        r#""translation":[1e400,0,0]"#,
        r#""translation":[-1e400,0,0]"#,
        r#""translation":{"x":1}"#,
        r#""scale":[1,true,1]"#,
        r#""scale":[1,null,1]"#,
        r#""rotation":[0,0,0]"#,
        r#""rotation":[0,0,0,[1]]"#,
        r#""matrix":[1,0,0,0,0,1,0,0,0,0,1,0,0,0,0]"#,
        r#""matrix":[1,0,0,0,0,1,0,0,0,0,1,0,0,0,0,1e999]"#,
    ];
    for (i, case) in cases.iter().enumerate() {
        let nodes = [format!(r#"{{"mesh":0,{case}}}"#)];
        for path in write_both(&scratch, &format!("case{i}"), &nodes) {
            let result = catch_unwind(AssertUnwindSafe(|| read_content(&path, &GltfOptions::default())));
            let err = match result {
                Ok(Err(err)) => err,
                Ok(Ok(_)) => panic!("{case}: loaded"),
                Err(_) => panic!("{case}: panicked"),
            };
            // The gltf crate reads the nodes first and refuses these with its own message;
            // the f64 reader's own refusals (naming node and field) are tested beside it.
            assert!(
                ["parse", "node-transform"].contains(&err.kind()),
                "{case}: {} {err}",
                err.kind()
            );
        }
    }
}
