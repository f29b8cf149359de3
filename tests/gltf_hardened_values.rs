//! glTF values that gave wrong images rather than errors: vertex colours that are infinite,
//! huge or plain integers, emitters with infinite or negative emission, and emitters spanning
//! 10¹⁸ m (one alone that far out is re-centred). Each file is written here, one cube room with
//! a lamp, differing in one value.

#[path = "support/scratch.rs"]
mod scratch;
#[path = "support/unit_cube_room.rs"]
mod unit_cube_room;
use scratch::Scratch;

use pm_trace::glam::Vec3;
use pm_trace::gltf::{GltfError, GltfOptions, load_scene_with};

fn percent(bytes: &[u8]) -> String {
    bytes.iter().map(|b| format!("%{b:02X}")).collect()
}

/// One vertex colour attribute: component type, normalized flag, type and its bytes.
struct Colours {
    component: u32,
    normalized: bool,
    ty: &'static str,
    bytes: Vec<u8>,
}

/// A unit cube room (inward, 8 vertices) offset by `offset`, a point lamp inside it, and
/// `colours` as its `COLOR_0`, with `material` as its material (JSON).
fn room(offset: [f32; 3], colours: Option<&Colours>, material: &str) -> String {
    let positions: Vec<u8> = unit_cube_room::corners()
        .into_iter()
        .flat_map(|c| {
            c.into_iter()
                .zip(offset)
                .map(|(v, o)| v + o)
                .collect::<Vec<f32>>()
        })
        .flat_map(f32::to_le_bytes)
        .collect();
    let indices: Vec<u8> = unit_cube_room::triangle_indices()
        .into_iter()
        .flat_map(u32::to_le_bytes)
        .collect();
    let mut bin = positions.clone();
    bin.extend(&indices);
    let mut views = vec![
        format!(
            r#"{{"buffer":0,"byteOffset":0,"byteLength":{}}}"#,
            positions.len()
        ),
        format!(
            r#"{{"buffer":0,"byteOffset":{},"byteLength":{}}}"#,
            positions.len(),
            indices.len()
        ),
    ];
    let (lo, hi) = (offset, offset.map(|o| o + 1.0));
    let mut accessors = vec![
        format!(
            r#"{{"bufferView":0,"componentType":5126,"count":8,"type":"VEC3","min":{lo:?},"max":{hi:?}}}"#
        ),
        r#"{"bufferView":1,"componentType":5125,"count":36,"type":"SCALAR"}"#.to_owned(),
    ];
    let mut attributes = r#""POSITION":0"#.to_owned();
    if let Some(c) = colours {
        // Aligned to 4 bytes, as accessors need.
        while !bin.len().is_multiple_of(4) {
            bin.push(0);
        }
        views.push(format!(
            r#"{{"buffer":0,"byteOffset":{},"byteLength":{}}}"#,
            bin.len(),
            c.bytes.len()
        ));
        bin.extend(&c.bytes);
        accessors.push(format!(
            r#"{{"bufferView":2,"componentType":{},"normalized":{},"count":8,"type":"{}"}}"#,
            c.component, c.normalized, c.ty
        ));
        attributes += r#","COLOR_0":2"#;
    }
    let lamp = offset.map(|o| o + 0.5);
    format!(
        r#"{{"asset":{{"version":"2.0"}},
        "extensionsUsed":["KHR_lights_punctual","KHR_materials_emissive_strength"],
        "extensions":{{"KHR_lights_punctual":{{"lights":[{{"type":"point","intensity":100}}]}}}},
        "buffers":[{{"byteLength":{},"uri":"data:application/octet-stream,{}"}}],
        "bufferViews":[{}],"accessors":[{}],
        "meshes":[{{"primitives":[{{"attributes":{{{attributes}}},"indices":1,"material":0}}]}}],
        "materials":[{material}],
        "nodes":[{{"mesh":0}},{{"translation":{lamp:?},"extensions":{{"KHR_lights_punctual":{{"light":0}}}}}}],
        "scenes":[{{"nodes":[0,1]}}],"scene":0}}"#,
        bin.len(),
        percent(&bin),
        views.join(","),
        accessors.join(","),
    )
}

/// Grey Lambertian (`KHR_materials_specular`'s factor 0: no Fresnel layer, albedo = base).
const GREY: &str = r#"{"pbrMetallicRoughness":{"baseColorFactor":[0.5,0.5,0.5,1],"metallicFactor":0},"extensions":{"KHR_materials_specular":{"specularFactor":0}}}"#;

impl Scratch {
    fn load(&self, name: &str, json: &str) -> Result<pm_trace::Scene, GltfError> {
        let path = self.0.join(name);
        std::fs::write(&path, json).unwrap();
        load_scene_with(&path, &GltfOptions::default())
    }
}

fn float_colours(values: [f32; 3]) -> Colours {
    Colours {
        component: 5126,
        normalized: false,
        ty: "VEC3",
        bytes: (0..8).flat_map(|_| values).flat_map(f32::to_le_bytes).collect(),
    }
}

#[test]
fn non_finite_vertex_colours_are_refused_naming_the_accessor() {
    let scratch = Scratch::new("colours");
    assert!(
        scratch
            .load(
                "plain.gltf",
                &room([0.0; 3], Some(&float_colours([0.5; 3])), GREY)
            )
            .is_ok()
    );
    for bad in [f32::INFINITY, f32::NAN, f32::NEG_INFINITY] {
        let json = room([0.0; 3], Some(&float_colours([0.5, bad, 0.5])), GREY);
        match scratch.load("bad.gltf", &json) {
            Err(GltfError::Accessor {
                accessor: 2, reason, ..
            }) => {
                assert!(reason.contains("not finite"), "{reason}")
            }
            other => panic!("{bad}: {:?}", other.map(|_| ())),
        }
    }
}

/// The albedo the scene gives at the centre of the room's floor, seen from above.
fn floor_albedo(scene: &pm_trace::Scene) -> Vec3 {
    let ray = pm_trace::Ray {
        origin: Vec3::new(0.5, 0.5, 0.5),
        direction: Vec3::NEG_Y,
    };
    let hit = scene
        .intersect(&ray, f32::INFINITY, pm_trace::RayKind::Other)
        .expect("the floor");
    scene.albedo_at(&hit)
}

#[test]
fn vertex_colours_multiply_within_zero_to_one() {
    let scratch = Scratch::new("clamped");
    // 3e38 used to give infinite SPPM pixels and path-traced means of 1e38.
    let huge = scratch
        .load(
            "huge.gltf",
            &room([0.0; 3], Some(&float_colours([3e38, 0.25, -1.0])), GREY),
        )
        .unwrap();
    assert_eq!(floor_albedo(&huge), Vec3::new(0.5, 0.125, 0.0));
    // Normalized unsigned bytes read as code / 255.
    let bytes = Colours {
        component: 5121,
        normalized: true,
        ty: "VEC4",
        bytes: (0..8).flat_map(|_| [255u8, 51, 0, 255]).collect(),
    };
    let scene = scratch
        .load("bytes.gltf", &room([0.0; 3], Some(&bytes), GREY))
        .unwrap();
    let albedo = floor_albedo(&scene);
    assert!(
        (albedo - Vec3::new(0.5, 0.1, 0.0)).abs().max_element() < 1e-6,
        "{albedo}"
    );
}

#[test]
fn integer_colours_not_marked_normalized_are_refused() {
    let scratch = Scratch::new("integers");
    // A plain UNSIGNED_BYTE colour of 252 rendered 504 times too bright (252 × the albedo
    // where 252/255 was meant).
    for (component, bytes) in [
        (
            5121u32,
            (0..8).flat_map(|_| [252u8, 252, 252, 255]).collect::<Vec<u8>>(),
        ),
        (
            5123,
            (0..8)
                .flat_map(|_| [1000u16, 1000, 1000, 1000])
                .flat_map(u16::to_le_bytes)
                .collect(),
        ),
    ] {
        let colours = Colours {
            component,
            normalized: false,
            ty: "VEC4",
            bytes,
        };
        match scratch.load("int.gltf", &room([0.0; 3], Some(&colours), GREY)) {
            Err(GltfError::Accessor {
                accessor: 2, reason, ..
            }) => {
                assert!(reason.contains("normalized"), "{reason}")
            }
            other => panic!("{component}: {:?}", other.map(|_| ())),
        }
    }
}

#[test]
fn emitters_with_infinite_or_negative_emission_are_refused_naming_the_material() {
    let scratch = Scratch::new("emitters");
    let strength = |s: &str| {
        format!(
            r#"{{"emissiveFactor":[1,1,1],"extensions":{{"KHR_materials_emissive_strength":{{"emissiveStrength":{s}}}}}}}"#
        )
    };
    for (material, needle) in [
        (strength("1e39"), "strength"),
        (strength("-3"), "strength"),
        (r#"{"emissiveFactor":[1e39,1,1]}"#.to_owned(), "factor"),
    ] {
        match scratch.load("emitter.gltf", &room([0.0; 3], None, &material)) {
            Err(GltfError::Primitive { reason, .. }) => {
                assert!(
                    reason.contains("material 0") && reason.contains(needle),
                    "{reason}"
                )
            }
            other => panic!("{material}: {:?}", other.map(|_| ())),
        }
    }
    assert!(
        scratch
            .load("ok.gltf", &room([0.0; 3], None, &strength("40")))
            .is_ok()
    );
}

#[test]
fn an_emitter_far_out_is_re_centred_and_one_spanning_past_the_limit_is_refused() {
    let scratch = Scratch::new("far");
    let emitter = r#"{"emissiveFactor":[1,1,1]}"#;
    for x in [1e18f32, -1e18] {
        // Alone, the room is moved to the origin (f32 had already flattened it to a square
        // in the file's accessors); the offset removed is kept.
        let scene = scratch
            .load("far.gltf", &room([x, 0.0, 0.0], None, emitter))
            .unwrap();
        assert_eq!(scene.origin_offset().x, f64::from(x));
        assert!(scene.bounds().max.abs().max_element() <= 1.0);
        // A second placement of it moved back to the origin: the scene now spans 10¹⁸ m,
        // which photons cannot be stored across.
        let spanning = room([x, 0.0, 0.0], None, emitter)
            .replace(
                r#""nodes":[{"mesh":0},"#,
                &format!(
                    r#""nodes":[{{"mesh":0}},{{"mesh":0,"translation":[{},0,0]}},"#,
                    -x
                ),
            )
            .replace(r#""nodes":[0,1]"#, r#""nodes":[0,1,2]"#);
        let err = scratch.load("far.gltf", &spanning).map(|_| ()).unwrap_err();
        assert!(err.to_string().contains("1e18"), "{x}: {err}");
    }
    assert!(
        scratch
            .load("near.gltf", &room([1e3, 0.0, 0.0], None, emitter))
            .is_ok()
    );
}
