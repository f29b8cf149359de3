//! Leaks: in `lit-unlit-rooms` the right room has no light, so its true radiance is exactly
//! zero. With crease maps every pixel showing it must be exactly 0 for all three estimators;
//! with a single map the disc estimator gathers photons through the wall and shows light.

use photon_maps::render::{EstimatorKind, Mode, RenderSettings, Renderer};
use photon_maps::trace::{CreaseAngle, RayKind, Scene, SingleMap, scenes};

const W: u32 = 64;
const H: u32 = 32;
/// The dark room's interior starts here (room 1 m, wall 0.02 m); a margin keeps away from it.
const DARK_ROOM_X: f32 = 1.02 + 0.01;

/// Pixels whose four corner rays all hit the dark room: every sample inside shows it.
fn dark_room_pixels(scene: &Scene) -> Vec<usize> {
    let camera = scene.camera();
    let aspect = W as f32 / H as f32;
    let in_dark = |u: f32, v: f32| {
        let ray = camera.ray(u, v, aspect);
        scene
            .intersect(&ray, f32::INFINITY, RayKind::Camera)
            .is_some_and(|h| h.position.x > DARK_ROOM_X)
    };
    (0..W * H)
        .filter(|&i| {
            let (x, y) = ((i % W) as f32, (i / W) as f32);
            [(0.0, 0.0), (1.0, 0.0), (0.0, 1.0), (1.0, 1.0)]
                .iter()
                .all(|&(dx, dy)| in_dark((x + dx) / W as f32, (y + dy) / H as f32))
        })
        .map(|i| i as usize)
        .collect()
}

fn settings() -> RenderSettings {
    RenderSettings {
        width: W,
        height: H,
        photons: 20_000,
        mode: Mode::Visualize,
        seed: 3,
        ..RenderSettings::default()
    }
}

#[test]
fn crease_maps_keep_the_dark_room_exactly_black() {
    let scene = scenes::build("lit-unlit-rooms").unwrap();
    let dark = dark_room_pixels(&scene);
    let count = dark.len();
    assert!(
        count > (W * H / 20) as usize,
        "the dark room should fill part of the right half: {count} pixels"
    );
    for kind in EstimatorKind::ALL {
        let out = Renderer::new(kind, settings())
            .render(&scene, &CreaseAngle::default(), &())
            .unwrap();
        for &i in &dark {
            assert_eq!(
                out.image.pixels()[i].to_array(),
                [0.0; 3],
                "{kind}: pixel {i} leaks"
            );
        }
        assert!(out.image.mean().x > 0.0, "{kind}: the lit room must be lit");
    }
}

#[test]
fn single_map_disc_leaks_light_into_the_dark_room() {
    let scene = scenes::build("lit-unlit-rooms").unwrap();
    let dark = dark_room_pixels(&scene);
    let out = Renderer::new(EstimatorKind::Disc, settings())
        .render(&scene, &SingleMap, &())
        .unwrap();
    let lit = dark.iter().filter(|&&i| out.image.pixels()[i].x > 0.0).count();
    assert!(
        lit > 0,
        "the basic variant is expected to leak near the shared wall"
    );
}
