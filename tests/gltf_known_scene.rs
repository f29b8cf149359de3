//! `tests/data/gltf/scenes/known.gltf` read against values worked out by hand: node
//! transforms (scale, rotation, a parent's translation), materials, the three kinds of light
//! and their scale, and the camera.

use std::path::Path;

use glam::Vec3;
use pm_trace::Material;
use pm_trace::bsdf::MetallicRoughness;
use pm_trace::gltf::{GltfCamera, GltfLight, GltfOptions, read_content};

const SCENES: &str = concat!(env!("CARGO_MANIFEST_DIR"), "/tests/data/gltf/scenes");

fn load(name: &str) -> pm_trace::gltf::GltfContent {
    read_content(&Path::new(SCENES).join(name), &GltfOptions::default()).unwrap()
}

fn close(a: Vec3, b: Vec3) -> bool {
    (a - b).abs().max_element() < 1e-5
}

#[test]
fn known_scene_maps_transforms_materials_lights_and_camera() {
    let c = load("known.gltf");
    let tris: Vec<Vec<Vec3>> = c.meshes.iter().map(|m| m.positions.clone()).collect();
    // Worked out by hand from the node transforms (parent translation (1, 2, 3)).
    let expected = [
        [
            Vec3::new(1., 2., 3.),
            Vec3::new(3., 2., 3.),
            Vec3::new(1., 4., 3.),
        ], // scale 2
        [
            Vec3::new(1., 2., 3.),
            Vec3::new(2., 2., 3.),
            Vec3::new(1., 2., 4.),
        ], // 90° about x
        [
            Vec3::new(11., 2., 3.),
            Vec3::new(12., 2., 3.),
            Vec3::new(11., 3., 3.),
        ], // matrix
        [
            Vec3::new(1., 2., 3.),
            Vec3::new(0., 2., 3.),
            Vec3::new(1., 3., 3.),
        ], // mirrored x
        [
            Vec3::new(1., 2., 2.),
            Vec3::new(2., 2., 2.),
            Vec3::new(1., 3., 2.),
        ], // z − 1
    ];
    assert_eq!(tris.len(), 5, "the default scene (1), not scene 0, is walked");
    for (got, want) in tris.iter().zip(&expected) {
        assert!(
            got.iter().zip(want).all(|(a, b)| close(*a, *b)),
            "{got:?} vs {want:?}"
        );
    }
    // The mirroring transform keeps the front face: winding is flipped back.
    assert_eq!(c.meshes[3].triangles, vec![[0, 2, 1]]);
    assert_eq!(c.meshes[0].triangles, vec![[0, 1, 2]]);

    let kinds: Vec<Material> = c.meshes.iter().map(|m| m.material.kind).collect();
    // glTF 2.0 Appendix B, factor for factor: "paint" (metallic 0, roughness 0.8) is a
    // dielectric, "chrome" (metallic 1, roughness 0.05) a smooth metal, "lamp" (no
    // pbrMetallicRoughness: the defaults) and mesh 4 (no material) rough white metals.
    let mr = |base: Vec3, metallic: f32, roughness: f32| {
        Material::MetallicRoughness(MetallicRoughness::new(base, metallic, roughness).unwrap())
    };
    assert_eq!(kinds[0], mr(Vec3::new(0.5, 0.25, 0.125), 0.0, 0.8));
    assert_eq!(kinds[1], mr(Vec3::new(0.9, 0.8, 0.7), 1.0, 0.05));
    assert_eq!(kinds[2], Material::Glass { ior: 1.33 });
    assert_eq!(kinds[3], mr(Vec3::ONE, 1.0, 1.0));
    assert_eq!(kinds[4], mr(Vec3::ONE, 1.0, 1.0));
    assert_eq!(c.meshes[3].material.emission, Vec3::new(8.0, 4.0, 2.0));
    assert_eq!(c.meshes[4].material_index, None);
    assert!(c.meshes.iter().take(3).all(|m| m.material.emission == Vec3::ZERO));

    // 683 cd of white-ish light is 1 W/sr per unit colour; 68.3 lux is 0.1 W/m².
    assert_eq!(c.lights.len(), 3);
    match c.lights[0] {
        GltfLight::Point { position, intensity } => {
            assert!(close(position, Vec3::new(0., 3., 0.)));
            assert!(close(intensity, Vec3::new(1., 0.5, 0.25)));
        }
        other => panic!("{other:?}"),
    }
    match c.lights[1] {
        GltfLight::Spot {
            direction,
            intensity,
            inner_cone_angle,
            outer_cone_angle,
            ..
        } => {
            assert!(
                close(direction, Vec3::Y),
                "−Z turned 90° about +x points up: {direction}"
            );
            assert!(close(intensity, Vec3::splat(2.0)));
            assert_eq!((inner_cone_angle, outer_cone_angle), (0.2, 0.4));
        }
        other => panic!("{other:?}"),
    }
    match c.lights[2] {
        GltfLight::Directional {
            direction,
            irradiance,
        } => {
            assert!(close(direction, Vec3::NEG_Y));
            assert!(close(irradiance, Vec3::splat(0.1)));
        }
        other => panic!("{other:?}"),
    }
    let scaled = read_content(
        &Path::new(SCENES).join("known.gltf"),
        &GltfOptions {
            light_scale: 683.0,
            ..GltfOptions::default()
        },
    )
    .unwrap();
    assert!(
        matches!(scaled.lights[2], GltfLight::Directional { irradiance, .. } if close(irradiance, Vec3::splat(68.3)))
    );

    let camera: GltfCamera = c.camera.unwrap();
    assert!(close(camera.position, Vec3::new(0., 1., 5.)));
    assert!(close(camera.look_at - camera.position, Vec3::NEG_Z));
    assert!(close(camera.up, Vec3::Y));
    assert_eq!(camera.vfov, 0.8);
}
