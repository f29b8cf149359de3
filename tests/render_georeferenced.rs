//! Georeferenced models render as they do at the origin: the lit and unlit rooms (solid 2 cm
//! slabs, and two rooms sharing a zero-thickness wall, double- and single-sided) written as a
//! glTF file whose accessors hold 1 m rooms and whose root node translates them by 0, 1 km,
//! 100 km or 6,400 km and scales them to 1 m, 1 mm or 1 µm. The loader composes the nodes
//! in f64 and re-centres the scene before it becomes f32, so the sealed room is exactly black
//! in every mode and the lit room's mean is the origin's within noise; the offset it removed
//! is the scene's `origin_offset`, and maps the scene back onto the file's coordinates.

#[path = "support/example.rs"]
mod example;
#[path = "support/georeferenced_rooms.rs"]
mod georeferenced_rooms;
#[path = "support/scratch.rs"]
mod scratch;

use georeferenced_rooms::{Placement, Room, Walls, write_rooms};
use photon_maps::render::glam::{DVec3, Vec3};
use photon_maps::render::progressive::{
    ProgressiveRenderer, ProgressiveSettings, SppmRenderer, SppmSettings,
};
use photon_maps::render::{EstimatorKind, FinalGatherOptions, Image, Mode, RenderSettings, Renderer};
use photon_maps::trace::gltf::load_scene;
use photon_maps::trace::{Contact, CreaseAngle, Partitioner, Scene};
use proptest::prelude::*;
use scratch::Scratch;
use std::sync::OnceLock;
use std::sync::atomic::{AtomicUsize, Ordering};

/// Translations of the root node along x, metres: the origin, 1 km, 100 km, 6,400 km.
const OFFSETS: [f32; 4] = [0.0, 1e3, 1e5, 6.4e6];
/// Scales of the root node: 1 m, 1 mm and 1 µm rooms.
const SCALES: [f32; 3] = [1.0, 1e-3, 1e-6];

/// Loads the rooms, written to a folder of their own (tests run in parallel threads).
fn load(walls: Walls, room: Room, placement: Placement) -> Scene {
    static FILES: AtomicUsize = AtomicUsize::new(0);
    let dir = Scratch::new(&format!("rooms-{}", FILES.fetch_add(1, Ordering::Relaxed)));
    load_scene(&write_rooms(&dir.0, walls, room, placement)).unwrap()
}

/// A translation along (1, 0.6, −0.8) of `distance` metres: off every axis.
fn along_diagonal(distance: f32) -> [f32; 3] {
    [distance, 0.6 * distance, -0.8 * distance]
}

fn settings(mode: Mode, spp: u32, seed: u64) -> RenderSettings {
    RenderSettings {
        width: 12,
        height: 12,
        samples_per_pixel: spp,
        photons: 3_000,
        k: 30,
        mode,
        seed,
        threads: 2,
        final_gather: FinalGatherOptions {
            gather_rays: 4,
            ..FinalGatherOptions::default()
        },
        ..RenderSettings::default()
    }
}

/// The images of every mode: the four one-shot modes, progressive photon-map and final
/// gather (two passes each), and SPPM (two passes).
fn every_mode(scene: &Scene) -> Vec<(String, Image)> {
    let partitioned = Contact::default().partition(scene.clone()).unwrap();
    let mut out = Vec::new();
    for mode in Mode::ALL {
        let image = Renderer::new(EstimatorKind::GeometryCube, settings(mode, 2, 1))
            .render(&partitioned, &())
            .unwrap()
            .image;
        out.push((mode.to_string(), image));
    }
    for mode in [Mode::PhotonMap, Mode::FinalGather] {
        let progressive = ProgressiveSettings::new(settings(mode, 1, 1), 2);
        let image = ProgressiveRenderer::new(EstimatorKind::GeometryCube, progressive)
            .render(&partitioned, &())
            .unwrap()
            .accumulation
            .mean();
        out.push((format!("progressive {mode}"), image));
    }
    let image = SppmRenderer::new(SppmSettings::new(settings(Mode::PhotonMap, 1, 1), 2))
        .render(scene, &())
        .unwrap()
        .image;
    out.push(("sppm".to_owned(), image));
    out
}

/// Pixels of `image` that are not exactly black.
fn lit_pixels(image: &Image) -> usize {
    image.pixels().iter().filter(|p| **p != Vec3::ZERO).count()
}

#[test]
fn the_sealed_room_is_exactly_black_at_every_distance_and_scale_in_every_mode() {
    let mut renders = 0;
    for walls in Walls::ALL {
        for offset in OFFSETS {
            for scale in SCALES {
                let placement = Placement {
                    translation: along_diagonal(offset),
                    scale,
                };
                let scene = load(walls, Room::Dark, placement);
                for (mode, image) in every_mode(&scene) {
                    let lit = lit_pixels(&image);
                    assert_eq!(
                        lit, 0,
                        "{walls:?} {mode}: {lit} lit pixels in the dark room at {offset} m, scale {scale}"
                    );
                    renders += 1;
                }
            }
        }
    }
    assert_eq!(renders, 3 * 4 * 3 * 7);
}

/// Samples per pixel of the lit room's renders (16 × 16 pixels): one render's mean has a
/// standard error near 0.4 %, so a 7 % darkening is 15 of them.
const LIT_SPP: u32 = 512;

/// The path tracer's mean over the lit room's image.
fn lit_mean(walls: Walls, placement: Placement, seed: u64) -> f64 {
    let scene = load(walls, Room::Lit, placement);
    let partitioned = CreaseAngle::default().partition(scene).unwrap();
    let mut settings = settings(Mode::PathTrace, LIT_SPP, seed);
    (settings.width, settings.height) = (16, 16);
    let image = Renderer::new(EstimatorKind::GeometryCube, settings)
        .render(&partitioned, &())
        .unwrap()
        .image;
    f64::from(image.mean().element_sum())
}

/// Seeds of the reference renders at the origin.
const REFERENCE_SEEDS: u64 = 6;

/// The lit room at the origin at 1 m, over [`REFERENCE_SEEDS`] seeds: the mean of the
/// per-seed means and the standard error of one seed's mean (their sample standard
/// deviation). Computed once per wall kind for every test of the process.
fn origin_reference(walls: Walls) -> (f64, f64) {
    static REFERENCES: OnceLock<Vec<(f64, f64)>> = OnceLock::new();
    let references = REFERENCES.get_or_init(|| {
        let at_origin = Placement {
            translation: [0.0; 3],
            scale: 1.0,
        };
        Walls::ALL
            .iter()
            .map(|&w| {
                let means: Vec<f64> = (1..=REFERENCE_SEEDS).map(|s| lit_mean(w, at_origin, s)).collect();
                let n = means.len() as f64;
                let mean = means.iter().sum::<f64>() / n;
                let variance = means.iter().map(|m| (m - mean).powi(2)).sum::<f64>() / (n - 1.0);
                (mean, variance.sqrt())
            })
            .collect()
    });
    references[Walls::ALL.iter().position(|&w| w == walls).unwrap()]
}

/// The standard error of a one-seed mean's difference from the reference: √(1 + 1/6) of one
/// seed's, that floored at 0.2 % of the mean (an estimate from six draws can come out small
/// by chance).
fn difference_error(reference: f64, standard_error: f64) -> f64 {
    (1.0 + 1.0 / REFERENCE_SEEDS as f64).sqrt() * standard_error.max(0.002 * reference)
}

/// Standard errors of the difference allowed: one case in about 1.7 million fails by chance.
const ALLOWED_ERRORS: f64 = 5.0;

#[test]
fn the_lit_room_reads_the_origins_mean_at_every_distance_and_scale() {
    let mut seed = 100;
    for walls in Walls::ALL {
        let (reference, standard_error) = origin_reference(walls);
        assert!(reference > 0.05, "{walls:?}: the lit room is lit: {reference}");
        let error = difference_error(reference, standard_error);
        for offset in OFFSETS {
            for scale in SCALES {
                let placement = Placement {
                    translation: along_diagonal(offset),
                    scale,
                };
                // A seed of its own, none of the reference's: independent noise.
                seed += 1;
                let m = lit_mean(walls, placement, seed);
                let z = (m - reference) / error;
                eprintln!(
                    "{walls:?} at {offset} m, scale {scale}: {m:.5} against {reference:.5} ± {standard_error:.5} ({z:+.2} standard errors)"
                );
                assert!(
                    z.abs() < ALLOWED_ERRORS,
                    "{walls:?} at {offset} m, scale {scale}: mean {m} against {reference} ({z:+.2} standard errors)"
                );
            }
        }
    }
}

#[test]
fn the_origin_offset_maps_the_scene_back_onto_the_files_coordinates() {
    let placement = Placement {
        translation: along_diagonal(6.4e6),
        scale: 1e-3,
    };
    let scene = load(Walls::SolidSlabs, Room::Lit, placement);
    // The file's world, computed here in f64 from the numbers its text states (not the f32s
    // they were printed from): root translation + scale × local point.
    let (t, scale) = (placement.translation_in_file(), placement.scale_in_file());
    let world = |local: [f32; 3]| DVec3::from(t) + scale * DVec3::from(local.map(f64::from));
    let slab = f64::from(georeferenced_rooms::SLAB);
    // Bounds: x from −slab to 2 + 2·slab, y and z from −slab to 1 + slab.
    let centre = (world([-0.02, -0.02, -0.02]) + world([2.04, 1.02, 1.02])) * 0.5;
    let offset = scene.origin_offset();
    let f64_ulps = 4.0 * f64::EPSILON * 6.4e6 * 1.5;
    assert!(
        (offset - centre).abs().max_element() < f64_ulps + 1e-12 * slab,
        "origin offset {offset} against the bounds' centre {centre}"
    );
    // The camera and the lamp, mapped back, stand where the file puts them, to f32's
    // precision at the model's own size (not at 6,400 km).
    let tolerance = 4.0 * f64::from(f32::EPSILON) * 2.0 * scale;
    let eye = offset + scene.camera().position().as_dvec3();
    assert!(
        (eye - world([0.8, 0.5, 0.5])).abs().max_element() < tolerance,
        "eye {eye}"
    );
    // The bounds, mapped back, are the slabs' own.
    let b = scene.bounds();
    let (lo, hi) = (offset + b.min.as_dvec3(), offset + b.max.as_dvec3());
    assert!(
        (lo - world([-0.02, -0.02, -0.02])).abs().max_element() < tolerance,
        "{lo}"
    );
    assert!(
        (hi - world([2.04, 1.02, 1.02])).abs().max_element() < tolerance,
        "{hi}"
    );
    // Re-centred: the scene's coordinates are the model's size, not the offset's.
    assert!(f64::from(b.min.abs().max(b.max.abs()).max_element()) < 2.0 * scale);
}

#[test]
fn a_model_around_its_origin_is_not_moved() {
    let scene = load(
        Walls::SharedWallDoubleSided,
        Room::Lit,
        Placement {
            translation: [0.0; 3],
            scale: 1.0,
        },
    );
    assert_eq!(scene.origin_offset(), DVec3::ZERO);
    // Bit for bit where the file puts it.
    assert_eq!(scene.bounds().min, Vec3::ZERO);
    assert_eq!(scene.bounds().max, Vec3::new(2.0, 1.0, 1.0));
    assert_eq!(scene.camera().position(), Vec3::new(0.8, 0.5, 0.5));
}

#[test]
fn placements_past_what_f32_or_f64_can_hold_give_typed_results() {
    let dir = Scratch::new("huge");
    let try_load = |translation: f32, scale: f32| {
        let placement = Placement {
            translation: [translation, 0.0, 0.0],
            scale,
        };
        load_scene(&write_rooms(&dir.0, Walls::SolidSlabs, Room::Lit, placement))
    };
    // 10³⁰ m out, f64 cannot tell a metre apart (its step there is 1.4·10¹⁴ m): the rooms
    // collapse before re-centring. Whatever comes of that is a scene of finite coordinates or
    // an error, never a panic.
    match try_load(1e30, 1.0) {
        Ok(scene) => {
            assert!(scene.origin_offset().is_finite());
            assert!(scene.bounds().min.is_finite() && scene.bounds().max.is_finite());
        }
        Err(e) => assert!(!e.to_string().is_empty()),
    }
    // Rooms 10¹⁸ m large 10³⁰ m out: f64 holds them (its 1.4·10¹⁴ m step is far below the
    // 2·10¹⁶ m slabs) and re-centring brings them into f32, but the scene cannot take faces
    // that large (their areas overflow f32, so they are dropped, and then it has no geometry,
    // or they reach ±10¹⁸ m): an error, not a panic or a scene of infinities.
    let err = try_load(1e30, 1e18).map(|_| ()).unwrap_err();
    let message = err.to_string();
    assert!(
        message.contains("no geometry") || message.contains("1e18"),
        "{message}"
    );
}

#[test]
fn the_render_example_reports_the_origin_offset() {
    let dir = Scratch::new("cli");
    for (offset, moved) in [(6.4e6f32, true), (0.0, false)] {
        let placement = Placement {
            translation: along_diagonal(offset),
            scale: 1.0,
        };
        let file = write_rooms(&dir.0, Walls::SolidSlabs, Room::Lit, placement);
        let (out, json) = (dir.path("rooms.exr"), dir.path("rooms.json"));
        let args = [
            "--scene",
            file.to_str().unwrap(),
            "--mode",
            "path-trace",
            "--size",
            "8x8",
            "--samples-per-pixel",
            "1",
            "--out",
            &out,
            "--stats-json",
            &json,
        ];
        let Some(output) = example::run(&args) else {
            return;
        };
        example::assert_ok(&args, &output);
        let stats: serde_json::Value =
            serde_json::from_str(&std::fs::read_to_string(&json).unwrap()).unwrap();
        let reported: Vec<f64> = stats["origin_offset"]
            .as_array()
            .unwrap()
            .iter()
            .map(|v| v.as_f64().unwrap())
            .collect();
        // The slabs' bounds run from −0.02 to (2.04, 1.02, 1.02): their centre is
        // (1.01, 0.5, 0.5) past the root node's translation (as the file's text states it).
        let t = placement.translation_in_file();
        let expected = if moved {
            [t[0] + 1.01, t[1] + 0.5, t[2] + 0.5]
        } else {
            [0.0; 3]
        };
        for k in 0..3 {
            assert!(
                (reported[k] - expected[k]).abs() < 1e-6,
                "{offset} m: reported {reported:?}, expected {expected:?}"
            );
        }
        let summary = String::from_utf8_lossy(&output.stdout);
        assert_eq!(summary.contains("re-centred"), moved, "{summary}");
    }
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(6))]

    /// Random placements up to 10⁴ km out on every axis and scales from 1 µm to 10 km: the
    /// sealed room stays black in the path tracer and shadow-ray mode, and the lit room reads
    /// the origin's mean within noise.
    #[test]
    fn any_placement_keeps_the_rooms_apart(
        x in -1e7f32..1e7, y in -1e7f32..1e7, z in -1e7f32..1e7,
        log_scale in -6.0f32..4.0,
        walls in prop::sample::select(Walls::ALL.to_vec()),
    ) {
        let placement = Placement { translation: [x, y, z], scale: 10f32.powf(log_scale) };
        let dark = load(walls, Room::Dark, placement);
        let partitioned = CreaseAngle::default().partition(dark).unwrap();
        for mode in [Mode::PathTrace, Mode::ShadowRays] {
            let image = Renderer::new(EstimatorKind::GeometryCube, settings(mode, 2, 1))
                .render(&partitioned, &())
                .unwrap()
                .image;
            prop_assert_eq!(lit_pixels(&image), 0, "{:?} {} at {:?}", walls, mode, placement);
        }
        let (reference, standard_error) = origin_reference(walls);
        let m = lit_mean(walls, placement, 200);
        let z = (m - reference) / difference_error(reference, standard_error);
        prop_assert!(
            z.abs() < ALLOWED_ERRORS,
            "{:?} at {:?}: mean {} against {} ({:+.2} standard errors)", walls, placement, m, reference, z
        );
    }
}
