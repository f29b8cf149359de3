//! glTF files built into scenes: the corpus Cornell box (an emissive area light, a default
//! camera looking into the open box) and the hand-written `known.gltf` (light powers from the
//! photometric conversion, worked out by hand), plus the headlight for unlit files.

use std::f32::consts::PI;
use std::path::{Path, PathBuf};

use glam::Vec3;
use pm_trace::gltf::{GltfError, GltfOptions, load_scene, load_scene_with};
use pm_trace::{Ray, RayKind};

const CORPUS: &str = concat!(env!("CARGO_MANIFEST_DIR"), "/../shared/gltf-corpus");
const SCENES: &str = concat!(env!("CARGO_MANIFEST_DIR"), "/tests/data/gltf/scenes");

fn corpus_file(relative: &str) -> Option<PathBuf> {
    let corpus = std::env::var_os("PM_GLTF_CORPUS").map_or_else(|| PathBuf::from(CORPUS), PathBuf::from);
    let file = corpus.join(relative);
    if file.is_file() {
        Some(file)
    } else {
        println!("notice: {} is absent; nothing checked", file.display());
        None
    }
}

fn close(a: Vec3, b: Vec3, tol: f32) -> bool {
    (a - b).abs().max_element() <= tol * b.abs().max_element().max(1.0)
}

#[test]
fn corpus_cornell_box_has_an_emissive_area_light_and_a_camera_looking_in() {
    let Some(file) = corpus_file("cornell/007Renderer/cornell_box.gltf") else {
        return;
    };
    let scene = load_scene(&file).unwrap();
    // The file's light: emissiveFactor (1, 0.70588, 0.23529) × emissiveStrength 17 on a
    // 0.47 m × 0.38 m quad (its accessor's min/max); an area light's power is π L A per
    // side, and its material is `doubleSided`, so both sides emit.
    assert_eq!(scene.lights().len(), 1);
    let radiance = Vec3::new(1.0, 0.705_882_4, 0.235_294_1) * 17.0;
    let expected = 2.0 * PI * radiance * (0.47 * 0.38);
    let power = scene.lights()[0].power();
    assert!(close(power, expected, 1e-3), "{power} vs {expected}");

    // The box stands 10 m from the file's origin, farther than it is large: the loader
    // re-centres it on its bounds' centre. Points below are the file's, mapped through the
    // offset it keeps.
    let offset = scene.origin_offset();
    assert!((offset.z + 10.0).abs() < 0.1, "{offset}");
    let to_scene = |p: Vec3| (p.as_dvec3() - offset).as_vec3();
    let to_file = |p: Vec3| (p.as_dvec3() + offset).as_vec3();

    // Straight up from the floor's centre a ray meets the light's underside, emitting.
    let up = Ray::new(to_scene(Vec3::new(0.0, -0.9, -10.03)), Vec3::Y);
    let hit = scene.intersect(&up, f32::INFINITY, RayKind::Other).unwrap();
    let at = to_file(hit.position);
    assert!((at.y - 0.98).abs() < 1e-3, "{at:?}");
    assert!(close(scene.emission(&hit), radiance, 1e-4));

    // No camera in the file: the default one looks along −z through the open side
    // (z = −9.01); its central ray meets the inside of the box (z down to the back wall at
    // −11.04), and the ray through the upper left meets the back wall itself.
    let camera = scene.camera();
    assert!(to_file(camera.position()).z > -9.01);
    let ray = camera.ray(0.5, 0.5, 1.0);
    let hit = scene.intersect(&ray, f32::INFINITY, RayKind::Camera).unwrap();
    let at = to_file(hit.position);
    assert!((-11.05..-9.0).contains(&at.z), "{at:?}");
    let ray = camera.ray(0.35, 0.35, 1.0);
    let hit = scene.intersect(&ray, f32::INFINITY, RayKind::Camera).unwrap();
    let at = to_file(hit.position);
    assert!((at.z + 11.04).abs() < 1e-3, "{at:?}");
    // The image corners see the box too: the box fills the frame.
    for (u, v) in [(0.1, 0.1), (0.9, 0.1), (0.1, 0.9), (0.9, 0.9)] {
        assert!(
            scene
                .intersect(&camera.ray(u, v, 1.0), f32::INFINITY, RayKind::Camera)
                .is_some(),
            "corner ({u}, {v}) sees nothing"
        );
    }
}

#[test]
fn known_scene_light_powers_follow_the_photometric_conversion() {
    let scene = load_scene(&Path::new(SCENES).join("known.gltf")).unwrap();
    // The emissive triangle (legs 1, area 0.5) first, then the three punctual lights.
    let powers: Vec<Vec3> = scene.lights().iter().map(|l| l.power()).collect();
    assert_eq!(powers.len(), 4);
    assert!(close(powers[0], PI * Vec3::new(8.0, 4.0, 2.0) * 0.5, 1e-5));
    // Point: 683 cd × colour → (1, 0.5, 0.25) W/sr, power 4π I.
    assert!(close(powers[1], 4.0 * PI * Vec3::new(1.0, 0.5, 0.25), 1e-5));
    // Spot: 1366 cd → 2 W/sr in a cone of 0.4 rad: power 2π (1 − cos 0.4) · 2.
    let spot = 2.0 * PI * (1.0 - 0.4f32.cos()) * 2.0;
    assert!(close(powers[2], Vec3::splat(spot), 1e-5));
    // The file's camera is used: at (0, 1, 5) looking along −z.
    assert!(close(scene.camera().position(), Vec3::new(0.0, 1.0, 5.0), 1e-6));
    assert!(close(scene.camera().forward(), Vec3::NEG_Z, 1e-6));
}

#[test]
fn unlit_file_gets_a_headlight_or_an_error() {
    let file = Path::new(SCENES).join("valid_percent_encoded.gltf");
    let scene = load_scene(&file).unwrap();
    assert_eq!(scene.lights().len(), 1);
    // Irradiance 1 W/m² at the bounds' centre: power 4π d².
    let center = (Vec3::new(0.0, 0.0, 0.0) + Vec3::new(1.0, 1.0, 0.0)) * 0.5;
    let d2 = scene.camera().position().distance_squared(center);
    assert!(close(scene.lights()[0].power(), Vec3::splat(4.0 * PI * d2), 1e-4));

    let options = GltfOptions {
        default_light: false,
        ..GltfOptions::default()
    };
    let err = load_scene_with(&file, &options).unwrap_err();
    assert!(matches!(err, GltfError::Scene { .. }), "{err}");
}
