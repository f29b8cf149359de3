//! Leaks: in `lit-unlit-rooms` and `touching-rooms` the room at x > 1.02 has no light, so its
//! true radiance is exactly zero. With crease maps every pixel showing it must be exactly 0 for
//! all three estimators in `lit-unlit-rooms`; with a single map the disc estimator gathers
//! photons through the wall and shows light. In `touching-rooms` the floor and ceiling run under
//! and over the dividing wall, so crease maps still leak and only contact maps keep it black.

use photon_maps::render::{EstimatorKind, Mode, RenderSettings, Renderer};
use photon_maps::trace::{Contact, CreaseAngle, Partitioner, Scene, SingleMap, scenes};

#[path = "support/dark_room.rs"]
mod dark_room;

const W: u32 = 64;
const H: u32 = 32;
/// Pixels of the image (`W × H`) that show only the dark room.
fn dark_room_pixels(scene: &Scene) -> Vec<usize> {
    dark_room::dark_room_pixels(scene, W, H)
}

fn settings() -> RenderSettings {
    RenderSettings {
        width: W,
        height: H,
        photons: 20_000,
        mode: Mode::PhotonMap,
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
        "the dark room should fill part of the image: {count} pixels"
    );
    for kind in EstimatorKind::ALL {
        let out = Renderer::new(kind, settings())
            .render(&CreaseAngle::default().partition(scene.clone()).unwrap(), &())
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
        .render(&SingleMap.partition(scene.clone()).unwrap(), &())
        .unwrap();
    let lit = dark.iter().filter(|&&i| out.image.pixels()[i].x > 0.0).count();
    assert!(
        lit > 0,
        "the basic variant is expected to leak near the shared wall"
    );
}

#[test]
fn touching_rooms_leak_through_the_shared_floor_with_crease_maps() {
    let scene = scenes::build("touching-rooms").unwrap();
    let dark = dark_room_pixels(&scene);
    for kind in EstimatorKind::ALL {
        let out = Renderer::new(kind, settings())
            .render(&CreaseAngle::default().partition(scene.clone()).unwrap(), &())
            .unwrap();
        let lit = dark.iter().filter(|&&i| out.image.pixels()[i].x > 0.0).count();
        assert!(
            lit > 0,
            "{kind}: the shared floor map should carry light into the dark room"
        );
    }
}

#[test]
fn touching_rooms_contact_maps_keep_the_dark_room_exactly_black() {
    let contact = Contact::default()
        .partition(scenes::build("touching-rooms").unwrap())
        .unwrap();
    let dark = dark_room_pixels(contact.scene());
    assert!(dark.len() > (W * H / 20) as usize, "{} dark pixels", dark.len());
    for kind in EstimatorKind::ALL {
        let out = Renderer::new(kind, settings()).render(&contact, &()).unwrap();
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
