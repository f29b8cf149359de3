//! glTF's `normalTexture` bends the shading normal as the specification's convention says: a
//! unit quad facing +z whose texture's u runs along +x and v *down* the image (so the image's
//! up is +y), with a one-texel normal map. Without `TANGENT` the loader makes MikkTSpace
//! tangents; the expected normal here is written from the convention alone (tangent along
//! increasing u, bitangent up the image, `n = normalize(T·x·s + B·y·s + N·z)` with
//! `(x, y, z) = 2·code/255 − 1`), independently of the loader. Also: the map's `scale`, the
//! back of a double-sided quad, a mirroring node, and a map leaning past the horizon (kept
//! `MIN_MAPPED_COSINE` above the geometric surface).

#[path = "support/gltf_writer.rs"]
mod gltf_writer;

use gltf_writer::{Quad, png_rgb, temp_dir, write_quads_gltf};
use photon_maps::trace::glam::{Vec2, Vec3};
use photon_maps::trace::gltf::{GltfOptions, load_scene_with, read_content};
use photon_maps::trace::{MIN_MAPPED_COSINE, Ray, RayKind, Scene};

/// A scene of one unit quad (x, y in `[0, 1]`, z = 0, front +z) with a one-texel normal map of
/// `texel`, `normal` the material's `normalTexture` JSON, the node's JSON `node`.
fn quad_scene(name: &str, texel: [u8; 3], normal: &str, node: &str) -> Scene {
    quad_scene_edited(name, texel, normal, &|json| {
        json.replacen(r#"{"mesh":0}"#, node, 1)
    })
}

/// [`quad_scene`] with the file's JSON passed through `edit`.
fn quad_scene_edited(name: &str, texel: [u8; 3], normal: &str, edit: &dyn Fn(&str) -> String) -> Scene {
    let dir = temp_dir(name);
    std::fs::write(dir.join("normal.png"), png_rgb(1, 1, &[texel])).unwrap();
    let corners = [Vec3::ZERO, Vec3::X, Vec3::new(1.0, 1.0, 0.0), Vec3::Y];
    let uvs = [
        Vec2::new(0.0, 1.0),
        Vec2::new(1.0, 1.0),
        Vec2::new(1.0, 0.0),
        Vec2::new(0.0, 0.0),
    ];
    let material = format!(
        r#"{{"pbrMetallicRoughness":{{"metallicFactor":0}},"doubleSided":true,"normalTexture":{normal}}}"#
    );
    let file = write_quads_gltf(&dir, &[Quad { corners, uvs }], &material, "normal.png", &[], "");
    let json = std::fs::read_to_string(&file).unwrap();
    std::fs::write(&file, edit(&json)).unwrap();
    let content = read_content(&file, &GltfOptions::default()).unwrap();
    assert!(content.warnings.is_empty(), "{:?}", content.warnings);
    let normal_map = content.meshes[0]
        .material_textures
        .normal
        .as_ref()
        .expect("a normal map");
    assert_eq!(normal_map.tangents.len(), 4);
    let scene = load_scene_with(&file, &GltfOptions::default()).unwrap();
    std::fs::remove_dir_all(&dir).ok();
    scene
}

/// [`quad_scene`]'s file with vertex normals +z and the vertex tangents `tangent` (one for all
/// four corners) added as `NORMAL` and `TANGENT` accessors in a second buffer.
fn with_tangents(json: &str, tangent: [f32; 4]) -> String {
    let mut root: serde_json::Value = serde_json::from_str(json).unwrap();
    let mut bytes = Vec::new();
    for _ in 0..4 {
        bytes.extend([0.0f32, 0.0, 1.0].iter().flat_map(|f| f.to_le_bytes()));
    }
    for _ in 0..4 {
        bytes.extend(tangent.iter().flat_map(|f| f.to_le_bytes()));
    }
    let hex: String = bytes.iter().map(|b| format!("%{b:02X}")).collect();
    let push = |root: &mut serde_json::Value, key: &str, value: serde_json::Value| {
        let list = root[key].as_array_mut().unwrap();
        list.push(value);
        list.len() - 1
    };
    let buffer = push(
        &mut root,
        "buffers",
        serde_json::json!({"byteLength": bytes.len(), "uri": format!("data:application/octet-stream,{hex}")}),
    );
    let normals = push(
        &mut root,
        "bufferViews",
        serde_json::json!({"buffer": buffer, "byteLength": 48}),
    );
    let tangents = push(
        &mut root,
        "bufferViews",
        serde_json::json!({"buffer": buffer, "byteOffset": 48, "byteLength": 64}),
    );
    let normal = push(
        &mut root,
        "accessors",
        serde_json::json!({"bufferView": normals, "componentType": 5126, "count": 4, "type": "VEC3"}),
    );
    let tangent = push(
        &mut root,
        "accessors",
        serde_json::json!({"bufferView": tangents, "componentType": 5126, "count": 4, "type": "VEC4"}),
    );
    let attributes = &mut root["meshes"][0]["primitives"][0]["attributes"];
    attributes["NORMAL"] = normal.into();
    attributes["TANGENT"] = tangent.into();
    root.to_string()
}

/// The tangent-space normal a texel codes, `2·code/255 − 1` per channel.
fn decoded(texel: [u8; 3]) -> Vec3 {
    Vec3::from(texel.map(|c| c as f32 / 255.0 * 2.0 - 1.0))
}

/// The shading normal where a ray from `origin` along `direction` meets the quad.
fn shading_normal(scene: &Scene, origin: Vec3, direction: Vec3) -> Vec3 {
    let hit = scene
        .intersect(&Ray::new(origin, direction), 10.0, RayKind::Other)
        .expect("the quad is hit");
    scene.shading_normal_at(&hit)
}

fn assert_near(got: Vec3, want: Vec3, what: &str) {
    assert!(
        (got - want).abs().max_element() < 2e-4,
        "{what}: {got} against {want}"
    );
}

const TILTED: [u8; 3] = [179, 153, 228];

#[test]
fn a_normal_map_tilts_along_u_and_up_the_image() {
    let t = decoded(TILTED);
    let want = Vec3::new(t.x, t.y, t.z).normalize();
    let scene = quad_scene("normal-map", TILTED, r#"{"index":0}"#, r#"{"mesh":0}"#);
    for (x, y) in [(0.3, 0.3), (0.7, 0.6), (0.5, 0.9)] {
        let n = shading_normal(&scene, Vec3::new(x, y, 1.0), Vec3::NEG_Z);
        assert_near(n, want, "front");
    }
    // Seen from behind (double-sided), the whole frame turns over: the normal is negated.
    let n = shading_normal(&scene, Vec3::new(0.4, 0.4, -1.0), Vec3::Z);
    assert_near(n, -want, "back");
    // The texel leans +x and +y: a loader that took the bitangent down the image (v's way)
    // or the tangent along v would give another normal.
    assert!(want.x > 0.3 && want.y > 0.15);
}

#[test]
fn the_scale_multiplies_x_and_y() {
    let t = decoded(TILTED);
    let want = Vec3::new(0.5 * t.x, 0.5 * t.y, t.z).normalize();
    let scene = quad_scene(
        "normal-map-scale",
        TILTED,
        r#"{"index":0,"scale":0.5}"#,
        r#"{"mesh":0}"#,
    );
    assert_near(
        shading_normal(&scene, Vec3::new(0.5, 0.5, 1.0), Vec3::NEG_Z),
        want,
        "scale",
    );
}

#[test]
fn a_mirroring_node_keeps_the_bitangent_up_the_image() {
    // Mirrored in x: the quad spans x in [−1, 0], u now runs along −x, the image's up is
    // still +y, and the front still faces +z (the loader flips the winding back).
    let t = decoded(TILTED);
    let want = Vec3::new(-t.x, t.y, t.z).normalize();
    let scene = quad_scene(
        "normal-map-mirror",
        TILTED,
        r#"{"index":0}"#,
        r#"{"mesh":0,"scale":[-1,1,1]}"#,
    );
    assert_near(
        shading_normal(&scene, Vec3::new(-0.5, 0.5, 1.0), Vec3::NEG_Z),
        want,
        "mirrored",
    );
}

#[test]
fn a_map_leaning_past_the_horizon_is_kept_above_the_surface() {
    // (1, 0.004, −0.92): below the quad. The normal is turned back towards +z, within the
    // plane of +z and the mapped normal, to the least cosine.
    let texel = [255, 128, 10];
    let scene = quad_scene("normal-map-steep", texel, r#"{"index":0}"#, r#"{"mesh":0}"#);
    let n = shading_normal(&scene, Vec3::new(0.5, 0.5, 1.0), Vec3::NEG_Z);
    assert!((n.length() - 1.0).abs() < 1e-5, "{n}");
    assert!((n.z - MIN_MAPPED_COSINE).abs() < 1e-5, "{n}");
    let t = decoded(texel);
    let along = Vec3::new(t.x, t.y, 0.0).normalize();
    let sin = (1.0 - MIN_MAPPED_COSINE * MIN_MAPPED_COSINE).sqrt();
    assert_near(
        n,
        Vec3::new(along.x * sin, along.y * sin, MIN_MAPPED_COSINE),
        "kept",
    );
}

#[test]
fn a_files_own_tangents_are_used_where_it_has_normals() {
    // TANGENT along +y with sign +1: T = +y and B = N × T = −x, a frame MikkTSpace would not
    // make here (its T is +x).
    let t = decoded(TILTED);
    let want = Vec3::new(-t.y, t.x, t.z).normalize();
    let scene = quad_scene_edited("normal-map-tangent", TILTED, r#"{"index":0}"#, &|json| {
        with_tangents(json, [0.0, 1.0, 0.0, 1.0])
    });
    assert_near(
        shading_normal(&scene, Vec3::new(0.5, 0.5, 1.0), Vec3::NEG_Z),
        want,
        "given",
    );
}

#[test]
fn the_normal_textures_texture_transform_turns_its_frame() {
    // KHR_texture_transform on the normalTexture (which the gltf crate does not type there)
    // rotating the texture coordinates a quarter turn: MikkTSpace's tangent follows the
    // turned u, so the mapped normal's tilt turns a quarter turn about +z.
    let plain = quad_scene("normal-map-plain", TILTED, r#"{"index":0}"#, r#"{"mesh":0}"#);
    let turned = quad_scene(
        "normal-map-turned",
        TILTED,
        r#"{"index":0,"extensions":{"KHR_texture_transform":{"rotation":1.5707964}}}"#,
        r#"{"mesh":0}"#,
    );
    let at = (Vec3::new(0.5, 0.5, 1.0), Vec3::NEG_Z);
    let (a, b) = (
        shading_normal(&plain, at.0, at.1),
        shading_normal(&turned, at.0, at.1),
    );
    assert!((a.z - b.z).abs() < 1e-4, "{a} {b}");
    let (ta, tb) = (a.truncate(), b.truncate());
    assert!((ta.length() - tb.length()).abs() < 1e-4, "{a} {b}");
    assert!(ta.dot(tb).abs() < 1e-3, "not turned a quarter: {a} {b}");
}
