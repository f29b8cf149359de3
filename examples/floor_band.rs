//! The floor beside a box resting on it, against the path tracer: the glTF Cornell box's two
//! blocks are meshes of their own standing on the floor, so the crease maps count the floor
//! under each block (where no photon lands) in the floor's area, and the floor next to the
//! blocks reads dark; the contact maps (the default) cut the footprints out. Prints the mean of
//! the floor band within `--band` of a block's base after 16, 64, 256 and 1,024 progressive
//! passes, for both partitions, relative to a path-traced reference whose own standard error
//! (from independent replicates) it also prints.
//!
//! `cargo run --release --example floor_band -- [SCENE.gltf]` (default: the Cornell box of the
//! shared glTF corpus, `../shared/gltf-corpus/cornell/007Renderer/cornell_box.gltf`). For
//! replicates: `FLOOR_BAND_SEEDS=8,9,10` (progressive seeds, default 7), `FLOOR_BAND_MAPS=contact`
//! (default both), and `FLOOR_BAND_TRUTH=MEAN,SE` to reuse a reference printed before.

use clap::Parser;
use photon_maps::render::progressive::{ProgressiveRenderer, ProgressiveSettings};
use photon_maps::render::{EstimatorKind, Mode, RenderSettings, Renderer};
use photon_maps::trace::glam::{DVec3, Vec3};
use photon_maps::trace::{Contact, CreaseAngle, Partitioner, RayKind, Scene};
use std::path::PathBuf;

/// The floor band beside the glTF Cornell box's blocks: crease against contact maps, per
/// progressive pass count, against the path tracer. Prints a table; writes nothing.
#[derive(Parser, Debug)]
struct Args {
    /// The glTF scene.
    #[arg(default_value = "../shared/gltf-corpus/cornell/007Renderer/cornell_box.gltf")]
    scene: PathBuf,
}

const SIZE: u32 = 128;
const CHECKPOINTS: [u64; 5] = [0, 16, 64, 256, 1024];
const REFERENCE_REPLICATES: u64 = 4;
const REFERENCE_SPP: u32 = 4096;

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let path = Args::parse().scene;
    let scene = photon_maps::trace::gltf::load_scene(&path)?;
    let bounds = scene.bounds();
    // "1 cm" in the 0.55 m Cornell box (diagonal 0.95 m), scaled to the file's units.
    let band = 0.0105 * bounds.diagonal();
    let pixels = band_pixels(&scene, band);
    println!(
        "{}: diagonal {:.3}, band {:.4} (1.05 % of the diagonal), {} band pixels of {}",
        path.display(),
        bounds.diagonal(),
        band,
        pixels.len(),
        SIZE * SIZE
    );
    let settings = RenderSettings {
        width: SIZE,
        height: SIZE,
        photons: RenderSettings::default().photons,
        seed: 7,
        ..RenderSettings::default()
    };

    let (truth, truth_se) = match std::env::var("FLOOR_BAND_TRUTH") {
        Ok(given) => {
            let (m, e) = given.split_once(',').ok_or("FLOOR_BAND_TRUTH=MEAN,SE")?;
            (m.parse::<f64>()?, e.parse::<f64>()?)
        }
        Err(_) => reference(&scene, settings, &pixels)?,
    };
    println!(
        "path-traced band luminance {truth:.5} ± {truth_se:.5} ({:.2} %)",
        100.0 * truth_se / truth
    );
    let seeds: Vec<u64> = std::env::var("FLOOR_BAND_SEEDS")
        .unwrap_or_else(|_| "7".to_owned())
        .split(',')
        .map(str::parse)
        .collect::<Result<_, _>>()?;
    let wanted = std::env::var("FLOOR_BAND_MAPS").unwrap_or_else(|_| "crease,contact".to_owned());
    let partitions: [(&str, Box<dyn Partitioner>); 2] = [
        ("crease", Box::new(CreaseAngle::default())),
        ("contact", Box::new(Contact::default())),
    ];
    println!("| maps | seed | passes | band error | in reference SEs |");
    println!("|---|---|---|---|---|");
    for (name, partition) in partitions {
        if !wanted.split(',').any(|w| w == name) {
            continue;
        }
        let partitioned = partition.partition(scene.clone())?;
        for &seed in &seeds {
            let settings = RenderSettings { seed, ..settings };
            let mut sum = vec![DVec3::ZERO; (SIZE * SIZE) as usize];
            for w in CHECKPOINTS.windows(2) {
                let progressive = ProgressiveSettings {
                    first_pass: w[0],
                    ..ProgressiveSettings::new(settings, w[1] - w[0])
                };
                let out = ProgressiveRenderer::new(EstimatorKind::GeometryCube, progressive)
                    .render(&partitioned, &())?;
                for (s, x) in sum.iter_mut().zip(out.accumulation.sums().parts().0) {
                    *s += *x;
                }
                let mean = band_luminance(sum.iter().map(|s| *s / w[1] as f64), &pixels);
                let error = mean / truth - 1.0;
                println!(
                    "| {name} | {seed} | {} | {:+.2} % | {:+.1} |",
                    w[1],
                    100.0 * error,
                    (mean - truth) / truth_se
                );
            }
        }
    }
    Ok(())
}

/// The band's path-traced luminance and its standard error, from independent replicates.
fn reference(
    scene: &Scene,
    settings: RenderSettings,
    pixels: &[usize],
) -> Result<(f64, f64), Box<dyn std::error::Error>> {
    let mut replicates = Vec::new();
    for r in 0..REFERENCE_REPLICATES {
        let s = RenderSettings {
            mode: Mode::PathTrace,
            samples_per_pixel: REFERENCE_SPP,
            seed: 1000 + r,
            ..settings
        };
        let image = Renderer::new(EstimatorKind::GeometryCube, s)
            .render(&CreaseAngle::default().partition(scene.clone())?, &())?
            .image;
        replicates.push(band_luminance(
            image.pixels().iter().map(|p| p.as_dvec3()),
            pixels,
        ));
    }
    let truth = replicates.iter().sum::<f64>() / replicates.len() as f64;
    let spread =
        (replicates.iter().map(|x| (x - truth).powi(2)).sum::<f64>() / (replicates.len() - 1) as f64).sqrt();
    Ok((truth, spread / (replicates.len() as f64).sqrt()))
}

/// Pixels whose centre ray hits the floor within `band` of the base of something standing on
/// it (an edge of another face lying in the floor's plane).
fn band_pixels(scene: &Scene, band: f32) -> Vec<usize> {
    let floor_y = scene.bounds().min.y;
    let eps = 1e-4 * scene.bounds().diagonal();
    let mut bases: Vec<(Vec3, Vec3)> = Vec::new();
    for mesh in scene.meshes() {
        let m = mesh.half_edge_mesh();
        for face in m.faces() {
            if m.face_normal(face).y.abs() > 0.5 {
                continue; // the floor itself, and other horizontal faces
            }
            let polygon: Vec<Vec3> = m.face_polygon(face).collect();
            for i in 0..polygon.len() {
                let (a, b) = (polygon[i], polygon[(i + 1) % polygon.len()]);
                if (a.y - floor_y).abs() < eps && (b.y - floor_y).abs() < eps {
                    bases.push((a, b));
                }
            }
        }
    }
    let camera = scene.camera();
    (0..SIZE * SIZE)
        .filter(|&i| {
            let (x, y) = ((i % SIZE) as f32 + 0.5, (i / SIZE) as f32 + 0.5);
            let ray = camera.ray(x / SIZE as f32, y / SIZE as f32, 1.0);
            scene
                .intersect(&ray, f32::INFINITY, RayKind::Camera)
                .is_some_and(|h| {
                    (h.position.y - floor_y).abs() < eps
                        && h.normal.y > 0.9
                        && bases
                            .iter()
                            .any(|&(a, b)| distance_to_segment(h.position, a, b) <= band)
                })
        })
        .map(|i| i as usize)
        .collect()
}

fn distance_to_segment(p: Vec3, a: Vec3, b: Vec3) -> f32 {
    let ab = b - a;
    let t = ((p - a).dot(ab) / ab.length_squared().max(f32::MIN_POSITIVE)).clamp(0.0, 1.0);
    p.distance(a + ab * t)
}

/// Mean Rec. 709 luminance over `pixels`.
fn band_luminance(image: impl Iterator<Item = DVec3>, pixels: &[usize]) -> f64 {
    let image: Vec<DVec3> = image.collect();
    let weights = DVec3::new(0.2126, 0.7152, 0.0722);
    pixels.iter().map(|&i| image[i].dot(weights)).sum::<f64>() / pixels.len() as f64
}
