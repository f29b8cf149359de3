//! Glossy surfaces keep the leak-free and deterministic promises of the diffuse ones:
//! - the two rooms of `lit-unlit-rooms` with every surface glossy (rough metals and rough
//!   dielectrics in glTF 2.0's metallic-roughness model, one metal smooth enough to be sampled
//!   through): the unlit room is exactly 0 in every leak-free photon mode, with crease and
//!   with contact maps, while the lit room is lit;
//! - `glossy-cornell-box` renders bit for bit alike on 1 and 3 threads in every photon mode,
//!   SPPM included, and in the path tracer.

use photon_maps::render::{EstimatorKind, Mode, RenderSettings, Renderer};
use photon_maps::trace::bsdf::MetallicRoughness;
use photon_maps::trace::glam::Vec3;
use photon_maps::trace::scenes::box_mesh::{Facing, box_mesh};
use photon_maps::trace::{Camera, Contact, CreaseAngle, Partitioner, PointLight, Scene, Surface, scenes};

#[path = "support/dark_room.rs"]
mod dark_room;
#[path = "support/photon_modes.rs"]
mod photon_modes;
use photon_modes::{Sppm, every_mode, image_bits, small_settings};

const W: u32 = 48;
const H: u32 = 24;

fn glossy(base: Vec3, metallic: f32, roughness: f32) -> Surface {
    Surface::metallic_roughness(MetallicRoughness::new(base, metallic, roughness).unwrap())
}

/// `lit-unlit-rooms` (two 1 m rooms 0.02 m apart, a point light in the left one) with glossy
/// faces: metals at roughness 0.35 and 0.5, a metal at 0.15 (below the near-specular
/// threshold, so camera paths and photons pass through it as off a mirror), and dielectrics
/// (a Fresnel layer over a diffuse base) at 0.3, 0.6 and 1.
fn glossy_lit_unlit_rooms() -> Scene {
    let white = Vec3::splat(0.75);
    let surfaces = [
        glossy(white, 1.0, 0.35),
        glossy(white, 0.0, 0.3),
        glossy(Vec3::new(0.9, 0.6, 0.3), 1.0, 0.15),
        glossy(white, 0.0, 0.6),
        glossy(Vec3::new(0.8, 0.8, 0.9), 1.0, 0.5),
        glossy(white, 0.0, 1.0).hidden_from_camera(),
    ];
    let mut builder = Scene::builder();
    for x0 in [0.0, 1.02] {
        let (corners, faces) = box_mesh(
            Vec3::new(x0, 0.0, 0.0),
            Vec3::new(x0 + 1.0, 1.0, 1.0),
            Facing::Inward,
        );
        builder = builder.mesh_per_face(&corners, &faces, &surfaces);
    }
    builder
        .light(PointLight::new(Vec3::new(0.8, 0.5, 0.5), Vec3::splat(50.0)))
        .camera(Camera::new(
            Vec3::new(1.01, 0.5, -2.2),
            Vec3::new(1.01, 0.5, 0.5),
            Vec3::Y,
            50f32.to_radians(),
        ))
        .build()
        .unwrap()
}

fn settings(mode: Mode, seed: u64) -> RenderSettings {
    small_settings((W, H), 20_000, 2, mode, seed)
}

#[test]
fn the_unlit_room_of_the_glossy_rooms_is_exactly_black_in_every_leak_free_mode() {
    let scene = glossy_lit_unlit_rooms();
    let dark = dark_room::dark_room_pixels(&scene, W, H);
    assert!(dark.len() > (W * H / 20) as usize, "{} dark pixels", dark.len());
    let crease = CreaseAngle::default().partition(scene.clone()).unwrap();
    let contact = Contact::default().partition(scene).unwrap();
    for (maps, partitioned) in [("crease", &crease), ("contact", &contact)] {
        for (name, render) in every_mode(partitioned, &settings, Sppm::Excluded) {
            let image = render(5);
            for &i in &dark {
                assert_eq!(
                    image.pixels()[i].to_array(),
                    [0.0; 3],
                    "{name}, {maps} maps: pixel {i} of the unlit room is lit"
                );
            }
            assert!(
                image.mean().x > 0.0,
                "{name}, {maps} maps: the lit room must be lit"
            );
        }
    }
}

/// The test above can fail: with one map for the whole scene, light gathered across the
/// dividing wall shows in the unlit room.
#[test]
fn one_map_lets_light_into_the_unlit_glossy_room() {
    use photon_maps::trace::SingleMap;
    let scene = glossy_lit_unlit_rooms();
    let dark = dark_room::dark_room_pixels(&scene, W, H);
    let single = SingleMap.partition(scene).unwrap();
    let image = Renderer::new(EstimatorKind::Disc, settings(Mode::PhotonMap, 5))
        .render(&single, &())
        .unwrap()
        .image;
    let lit = dark.iter().filter(|&&i| image.pixels()[i].x > 0.0).count();
    assert!(lit > 0, "one map should leak near the dividing wall");
}

#[test]
fn the_glossy_cornell_box_renders_alike_on_any_thread_count() {
    let crease = CreaseAngle::default()
        .partition(scenes::build("glossy-cornell-box").unwrap())
        .unwrap();
    let on_threads = |threads: usize| {
        move |mode: Mode, seed: u64| RenderSettings {
            width: 16,
            height: 16,
            photons: 5_000,
            threads,
            ..settings(mode, seed)
        }
    };
    let (one, three) = (on_threads(1), on_threads(3));
    let mut cases_one = every_mode(&crease, &one, Sppm::Included);
    let cases_three = every_mode(&crease, &three, Sppm::Included);
    let path_trace = |settings: RenderSettings| {
        Renderer::new(EstimatorKind::Disc, settings)
            .render(&crease, &())
            .unwrap()
            .image
    };
    cases_one.push((
        "path tracer",
        Box::new(move |s| path_trace(one(Mode::PathTrace, s))),
    ));
    let mut cases_three = cases_three;
    cases_three.push((
        "path tracer",
        Box::new(move |s| path_trace(three(Mode::PathTrace, s))),
    ));
    for ((name, a), (_, b)) in cases_one.iter().zip(&cases_three) {
        assert_eq!(
            image_bits(&a(9)),
            image_bits(&b(9)),
            "{name}: 1 and 3 threads differ"
        );
    }
}
