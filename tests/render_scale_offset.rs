//! Walls hold at every scale and distance from the origin that f32 can draw them at: two
//! closed rooms (inward boxes) side by side, their walls 2 % of a room apart, one lit by a
//! point light. From 1 µm rooms to 1 km rooms at the origin, and a 1 m
//! room 1 km away, the dark room is exactly black in every mode (the path tracer included), and
//! the lit room's mean is the 1 m room's within noise. Ray offsets scale with each hit's own
//! rounding error, not with the scene's size.

use photon_maps::render::glam::Vec3;
use photon_maps::render::{EstimatorKind, FinalGatherOptions, Image, Mode, RenderSettings, Renderer};
use photon_maps::trace::scenes::box_mesh::{Facing, box_mesh};
use photon_maps::trace::{Camera, CreaseAngle, Partitioner, PointLight, Scene, Surface};

/// The rooms, `size` metres each, the lit room's corner at `offset`; the camera stands in the
/// lit room (`Room::Lit`) or the dark one, looking at its far wall.
fn rooms(size: f32, offset: Vec3, room: Room) -> Scene {
    let at = |p: Vec3| offset + p * size;
    let white = Surface::diffuse(Vec3::splat(0.7));
    let (lit, lit_faces) = box_mesh(at(Vec3::ZERO), at(Vec3::new(0.99, 1.0, 1.0)), Facing::Inward);
    let (dark, dark_faces) = box_mesh(
        at(Vec3::new(1.01, 0.0, 0.0)),
        at(Vec3::new(2.0, 1.0, 1.0)),
        Facing::Inward,
    );
    // Intensity ∝ size² keeps every radiance the same at every scale.
    let light = PointLight::new(at(Vec3::new(0.5, 0.7, 0.5)), Vec3::splat(2.0 * size * size));
    let (eye, look) = match room {
        Room::Lit => (Vec3::new(0.2, 0.5, 0.5), Vec3::new(0.9, 0.4, 0.5)),
        Room::Dark => (Vec3::new(1.8, 0.5, 0.5), Vec3::new(1.1, 0.4, 0.5)),
    };
    Scene::builder()
        .mesh(&lit, &lit_faces, white)
        .mesh(&dark, &dark_faces, white)
        .light(light)
        .camera(Camera::new(at(eye), at(look), Vec3::Y, 1.4))
        .build()
        .unwrap()
}

#[derive(Clone, Copy)]
enum Room {
    Lit,
    Dark,
}

fn render(scene: &Scene, mode: Mode, spp: u32, seed: u64) -> Image {
    let s = RenderSettings {
        width: 16,
        height: 16,
        samples_per_pixel: spp,
        photons: 4_000,
        k: 30,
        mode,
        seed,
        threads: 2,
        final_gather: FinalGatherOptions {
            gather_rays: 4,
            ..FinalGatherOptions::default()
        },
        ..RenderSettings::default()
    };
    Renderer::new(EstimatorKind::GeometryCube, s)
        .render(&CreaseAngle::default().partition(scene.clone()).unwrap(), &())
        .unwrap()
        .image
}

/// (size, offset of the rooms' corner) of every case.
const CASES: [(f32, f32); 7] = [
    (1e-6, 0.0),
    (1e-3, 0.0),
    (1.0, 0.0),
    (1e3, 0.0),
    (1e-6, 1e-3),
    (1.0, 100.0),
    (1.0, 1000.0),
];

#[test]
fn the_dark_room_is_exactly_black_at_every_scale_and_distance() {
    for (size, offset) in CASES {
        let scene = rooms(size, Vec3::splat(offset), Room::Dark);
        for mode in Mode::ALL {
            let image = render(&scene, mode, 2, 1);
            let lit = image.pixels().iter().filter(|p| **p != Vec3::ZERO).count();
            assert_eq!(
                lit, 0,
                "{mode}: {lit} lit pixels in the dark room of size {size} m at {offset} m"
            );
        }
    }
}

#[test]
fn the_lit_room_is_the_same_at_every_scale_and_distance() {
    let mean = |size: f32, offset: f32, seed: u64| {
        render(
            &rooms(size, Vec3::splat(offset), Room::Lit),
            Mode::PathTrace,
            64,
            seed,
        )
        .mean()
        .element_sum()
    };
    // The path tracer's own noise at 1 m: two seeds' means differ by about √2 standard errors.
    let (a, b) = (mean(1.0, 0.0, 1), mean(1.0, 0.0, 2));
    let standard_error = (a - b).abs() / 2f32.sqrt();
    let reference = (a + b) / 2.0;
    assert!(reference > 0.05, "the lit room is lit: {reference}");
    for (size, offset) in CASES {
        let m = mean(size, offset, 3);
        // Against the mean of two: combined standard error √1.5 of one; five of those, and
        // 0.5 % of the mean for a noise estimate that is itself one draw.
        let allowed = 5.0 * 1.5f32.sqrt() * standard_error + 0.005 * reference;
        assert!(
            (m - reference).abs() < allowed,
            "size {size} m at {offset} m: mean {m} against {reference} (allowed {allowed})"
        );
    }
}
