//! The repository's own textured glTF scene (examples/scenes/textured-room, written by its
//! make_textured_room.py) loads and renders: the photon map's image mean matches the path
//! tracer's within 2 % per channel, looking at the textured floor, the red wall and the
//! white walls (the emissive panel, whose pixels both modes show alike, is out of view).

use photon_maps::prelude::*;
use photon_maps::trace::gltf::load_scene;
use std::path::Path;

fn room() -> Scene {
    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("examples/scenes/textured-room/textured-room.gltf");
    load_scene(&path).expect("the repository's scene loads")
}

#[test]
fn textured_room_loads_with_its_texture_panel_and_camera() {
    let scene = room();
    assert_eq!(scene.lights().len(), 1, "the emissive panel is the only light");
    // The panel: 1.2 m × 1.2 m of radiance 6 × (1, 0.9, 0.75), power π L A.
    let power = scene.lights()[0].power();
    let want = std::f32::consts::PI * 6.0 * 1.44 * Vec3::new(1.0, 0.9, 0.75);
    assert!(
        (power - want).abs().max_element() < 1e-3 * want.max_element(),
        "{power} against {want}"
    );
    // The file's camera, near the front wall (not an automatic one framing the bounds).
    let camera = scene.camera();
    assert!(
        (camera.position() - vec3(2.0, 1.3, 3.95)).length() < 1e-4,
        "{}",
        camera.position()
    );
    assert!(
        camera.forward().z < -0.99,
        "looking at the back wall: {}",
        camera.forward()
    );
}

#[test]
fn textured_room_photon_map_matches_the_path_tracer() {
    // Looking down at the floor's far left, where it meets the red wall.
    let scene = room()
        .with_camera(Camera::new(
            vec3(2.6, 1.6, 3.6),
            vec3(0.8, 0.0, 1.0),
            Vec3::Y,
            1.2,
        ))
        .unwrap();
    // k = 200: the k-nearest estimate's own upward bias, about k / (k − 1), stays near 0.5 %.
    let settings = RenderSettings {
        width: 32,
        height: 32,
        photons: 300_000,
        k: 200,
        seed: 5,
        ..RenderSettings::default()
    };
    let photon_map = Renderer::new(GeometryCube, settings)
        .render(&CreaseAngle::default().partition(scene.clone()).unwrap(), &())
        .unwrap()
        .image
        .mean();
    let path_traced = Renderer::new(
        GeometryCube,
        RenderSettings {
            mode: Mode::PathTrace,
            samples_per_pixel: 256,
            ..settings
        },
    )
    .render(&CreaseAngle::default().partition(scene.clone()).unwrap(), &())
    .unwrap()
    .image
    .mean();
    let error = (photon_map / path_traced - 1.0).abs().max_element();
    eprintln!(
        "photon map {photon_map}, path traced {path_traced}: {:.2} %",
        100.0 * error
    );
    assert!(
        error < 0.02,
        "photon map {photon_map}, path traced {path_traced}: {:.2} % apart",
        100.0 * error
    );
    // The floor's texture and the red wall show: the image is not grey.
    assert!(path_traced.x > 1.3 * path_traced.z, "{path_traced}");
}
