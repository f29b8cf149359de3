//! The repository's glossy textured room (examples/scenes/glossy-textured-room, written by its
//! make_glossy_textured_room.py): the textured room's geometry with a varnished tiled floor
//! (metallic-roughness, normal and specular textures, no NORMAL or TANGENT), a glossy red
//! wall and a brushed-aluminium wall. Its materials reach the BSDF as the file says, the
//! floor's normal map bevels each tile's edges, and the progressive mode (consistent) and the
//! one-shot photon-map and shadow-ray modes agree with the path tracer on a view of the floor,
//! the metal wall and the red wall.

use photon_maps::prelude::*;
use photon_maps::render::progressive::{ProgressiveRenderer, ProgressiveSettings};
use photon_maps::trace::gltf::{GltfOptions, load_scene, read_content};
use photon_maps::trace::{Material, Ray, RayKind};
use std::path::{Path, PathBuf};

fn file() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("examples/scenes/glossy-textured-room/glossy-textured-room.gltf")
}

/// Where a ray straight down meets the floor at `(x, z)`.
fn floor_hit(scene: &Scene, x: f32, z: f32) -> Hit {
    scene
        .intersect(&Ray::new(vec3(x, 1.0, z), Vec3::NEG_Y), 10.0, RayKind::Other)
        .expect("the floor")
}

#[test]
fn the_floors_textures_reach_its_bsdf_and_normal() {
    let content = read_content(&file(), &GltfOptions::default()).unwrap();
    assert!(content.warnings.is_empty(), "{:?}", content.warnings);
    let scene = load_scene(&file()).unwrap();
    // The floor's texture repeats 4 × 4 over its 4 m: one repeat (2 × 2 tiles) a metre, each
    // tile half a metre, its grout the first and last 1/64 m of each tile.
    let tile = floor_hit(&scene, 0.25, 0.25);
    let grout = floor_hit(&scene, 0.5 + 0.25 / 64.0, 0.25);
    let at = |hit| {
        let Material::MetallicRoughness(m) = scene.material(hit) else {
            panic!("the floor is a metallic-roughness material");
        };
        m.at_point(&scene.shading_point(hit))
    };
    let (t, g) = (at(&tile), at(&grout));
    assert_eq!(t.metallic(), 0.0);
    assert!((t.roughness() - 38.0 / 255.0).abs() < 0.01, "{}", t.roughness());
    assert!(g.roughness() > 0.95, "{}", g.roughness());
    assert!((t.specular() - 1.0).abs() < 1e-6 && (g.specular() - 64.0 / 255.0).abs() < 0.01);
    // The tile's face points straight up; the grout's edge leans along x (its bevel, 0.45 at
    // the texel's centre, here halfway to the next texel's by the bilinear filter).
    let up = scene.shading_normal_at(&tile);
    assert!(up.y > 0.9999, "{up}");
    let bevel = scene.shading_normal_at(&grout);
    assert!(bevel.x.abs() > 0.2 && bevel.z.abs() < 0.01, "{bevel}");
}

/// A view of the floor's far right, the aluminium wall and the red wall behind.
fn view() -> Scene {
    load_scene(&file())
        .unwrap()
        .with_camera(Camera::new(
            vec3(1.2, 1.5, 3.7),
            vec3(3.4, 0.3, 1.2),
            Vec3::Y,
            1.2,
        ))
        .unwrap()
}

const SIZE: u32 = 24;
const SEEDS: u64 = 6;

fn settings(mode: Mode, seed: u64) -> RenderSettings {
    RenderSettings {
        width: SIZE,
        height: SIZE,
        photons: 200_000,
        samples_per_pixel: 4,
        k: 100,
        mode,
        seed,
        threads: 2,
        ..RenderSettings::default()
    }
}

/// The image mean (channels summed) over `seeds` seeds, and its standard error.
fn mean_over_seeds(render: impl Fn(u64) -> Image, seeds: u64) -> (f64, f64) {
    let values: Vec<f64> = (0..seeds)
        .map(|s| {
            let m = render(3 + 7919 * s).mean();
            f64::from(m.x + m.y + m.z)
        })
        .collect();
    let n = values.len() as f64;
    let mean = values.iter().sum::<f64>() / n;
    let var = values.iter().map(|v| (v - mean).powi(2)).sum::<f64>() / (n - 1.0);
    (mean, (var / n).sqrt())
}

#[test]
fn photon_modes_agree_with_the_path_tracer_on_the_glossy_room() {
    let scene = CreaseAngle::default().partition(view()).unwrap();
    let render = |mode: Mode| {
        let scene = &scene;
        move |seed| {
            Renderer::new(GeometryCube, settings(mode, seed))
                .render(scene, &())
                .unwrap()
                .image
        }
    };
    let (truth, truth_se) = mean_over_seeds(
        |seed| {
            Renderer::new(
                GeometryCube,
                RenderSettings {
                    samples_per_pixel: 256,
                    ..settings(Mode::PathTrace, seed)
                },
            )
            .render(&scene, &())
            .unwrap()
            .image
        },
        SEEDS,
    );
    let progressive = |seed| {
        let per_pass = RenderSettings {
            photons: 50_000,
            ..settings(Mode::ShadowRays, seed)
        };
        ProgressiveRenderer::new(
            EstimatorKind::GeometryCube,
            ProgressiveSettings::new(per_pass, 16),
        )
        .render(&scene, &())
        .unwrap()
        .accumulation
        .mean()
    };
    // Measured (6 seeds): see the assertion below for what each mode must meet.
    for (name, (mean, se), consistent) in [
        (
            "photon-map",
            mean_over_seeds(render(Mode::PhotonMap), SEEDS),
            false,
        ),
        (
            "shadow-rays",
            mean_over_seeds(render(Mode::ShadowRays), SEEDS),
            false,
        ),
        ("progressive", mean_over_seeds(progressive, SEEDS), true),
    ] {
        let z = (mean - truth) / (se * se + truth_se * truth_se).sqrt();
        let relative = mean / truth - 1.0;
        eprintln!(
            "{name}: {mean:.5} ± {se:.5} against {truth:.5} ± {truth_se:.5}: {:+.2} % (z {z:+.1})",
            100.0 * relative
        );
        assert!(z.abs() < 4.0, "{name}: {:+.2} % (z {z:+.1})", 100.0 * relative);
        assert!(
            consistent || relative.abs() < 0.05,
            "{name}: {:+.2} %",
            100.0 * relative
        );
    }
}
