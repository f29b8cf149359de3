//! Shading normals: a coarse UV sphere and a 320-triangle icosphere with per-vertex normals,
//! lit by a point light and path traced, match the analytic sphere of the same radius pixel
//! by pixel away from the silhouette and the terminator (mean and 95th percentile of the
//! relative difference), and clearly better than the same meshes without normals (faceted).

use glam::Vec3;
use photon_maps::render::{EstimatorKind, Image, Mode, RenderSettings, Renderer};
use photon_maps::trace::Partitioner;
use photon_maps::trace::{Camera, CreaseAngle, PointLight, Scene, SceneBuilder, Surface, VertexAttributes};
use std::f32::consts::PI;

#[path = "../crates/pm-trace/tests/common/mod.rs"]
mod common;

/// A unit icosphere at the origin: the icosahedron subdivided `levels` times.
fn icosphere(levels: u32) -> (Vec<Vec3>, Vec<[u32; 3]>) {
    common::icosphere(Vec3::ZERO, 1.0, levels)
}

const STACKS: u32 = 10;
const SLICES: u32 = 20;

/// A unit UV sphere: its vertices (on the sphere, so also its normals) and triangles,
/// counter-clockwise seen from outside.
fn uv_sphere() -> (Vec<Vec3>, Vec<[u32; 3]>) {
    let mut positions = vec![Vec3::Y];
    for i in 1..STACKS {
        let theta = PI * i as f32 / STACKS as f32;
        for j in 0..SLICES {
            let phi = 2.0 * PI * j as f32 / SLICES as f32;
            positions.push(Vec3::new(
                theta.sin() * phi.cos(),
                theta.cos(),
                -theta.sin() * phi.sin(),
            ));
        }
    }
    positions.push(-Vec3::Y);
    let south = positions.len() as u32 - 1;
    let ring = |i: u32, j: u32| 1 + (i - 1) * SLICES + j % SLICES;
    let mut triangles = Vec::new();
    for j in 0..SLICES {
        triangles.push([0, ring(1, j), ring(1, j + 1)]);
        triangles.push([south, ring(STACKS - 1, j + 1), ring(STACKS - 1, j)]);
    }
    for i in 1..STACKS - 1 {
        for j in 0..SLICES {
            let (a, b, c, d) = (ring(i, j), ring(i, j + 1), ring(i + 1, j), ring(i + 1, j + 1));
            triangles.push([a, c, d]);
            triangles.push([a, d, b]);
        }
    }
    (positions, triangles)
}

fn lit(builder: SceneBuilder) -> Scene {
    builder
        .light(PointLight::new(Vec3::new(2.0, 3.0, 4.0), Vec3::splat(30.0)))
        .camera(Camera::new(Vec3::new(0.0, 0.0, 4.0), Vec3::ZERO, Vec3::Y, 0.7))
        .build()
        .expect("valid scene")
}

fn render(scene: &Scene) -> Image {
    let settings = RenderSettings {
        width: 48,
        height: 48,
        photons: 1000,
        samples_per_pixel: 2,
        mode: Mode::PathTrace,
        seed: 3,
        ..RenderSettings::default()
    };
    Renderer::new(EstimatorKind::Disc, settings)
        .render(&CreaseAngle::default().partition(scene.clone()).unwrap(), &())
        .unwrap()
        .image
}

/// Per-pixel relative differences to `reference` over pixels well lit in the reference whose
/// 3×3 neighbourhoods are covered in both images (away from the silhouette), sorted.
fn relative_differences(image: &Image, reference: &Image) -> Vec<f32> {
    let peak = reference.pixels().iter().map(|p| p.x).fold(0.0, f32::max);
    let covered = |img: &Image, x: u32, y: u32| {
        (x.saturating_sub(1)..=(x + 1).min(img.width() - 1)).all(|i| {
            (y.saturating_sub(1)..=(y + 1).min(img.height() - 1)).all(|j| img.get(i, j).unwrap().x > 0.0)
        })
    };
    let mut out = Vec::new();
    for y in 0..reference.height() {
        for x in 0..reference.width() {
            let r = reference.get(x, y).unwrap().x;
            if r < 0.2 * peak || !covered(reference, x, y) || !covered(image, x, y) {
                continue;
            }
            out.push((image.get(x, y).unwrap().x - r).abs() / r);
        }
    }
    out.sort_by(f32::total_cmp);
    out
}

/// Mean, 95th percentile and largest of sorted differences.
fn summary(d: &[f32]) -> (f32, f32, f32) {
    let mean = d.iter().sum::<f32>() / d.len().max(1) as f32;
    let p95 = d[(d.len() * 95 / 100).min(d.len() - 1)];
    (mean, p95, d[d.len() - 1])
}

/// Compares the smooth and faceted versions of a mesh with the analytic unit sphere: the
/// smooth one must differ little per pixel (mean under 3 %, 95 % of pixels under `p95_limit`),
/// the faceted one clearly more.
fn check_against_analytic(label: &str, positions: &[Vec3], triangles: &[[u32; 3]], p95_limit: f32) {
    let surface = Surface::diffuse(Vec3::splat(0.7));
    let analytic = render(&lit(Scene::builder().sphere(Vec3::ZERO, 1.0, surface)));
    let faceted = render(&lit(Scene::builder().mesh(positions, triangles, surface)));
    let smooth = render(&lit(Scene::builder().attributed_mesh(
        positions,
        triangles,
        surface,
        VertexAttributes {
            normals: Some(positions.to_vec()),
            ..VertexAttributes::default()
        },
    )));
    let smooth_d = relative_differences(&smooth, &analytic);
    let faceted_d = relative_differences(&faceted, &analytic);
    let (smooth_mean, smooth_p95, smooth_max) = summary(&smooth_d);
    let (faceted_mean, faceted_p95, faceted_max) = summary(&faceted_d);
    println!(
        "{label}: relative difference per pixel from the analytic sphere over {} pixels: smooth mean {smooth_mean:.4}, 95th percentile {smooth_p95:.4}, max {smooth_max:.4}; faceted mean {faceted_mean:.4}, 95th percentile {faceted_p95:.4}, max {faceted_max:.4}",
        smooth_d.len()
    );
    assert!(smooth_d.len() > 300, "only {} pixels compared", smooth_d.len());
    assert!(
        smooth_mean < 0.03,
        "smooth sphere differs by {smooth_mean} on average"
    );
    assert!(
        smooth_p95 < p95_limit,
        "smooth sphere: 5 % of pixels differ by over {smooth_p95}"
    );
    assert!(
        faceted_mean > 2.0 * smooth_mean && faceted_p95 > 2.0 * smooth_p95,
        "faceted {faceted_mean}/{faceted_p95} vs smooth {smooth_mean}/{smooth_p95}"
    );
}

#[test]
fn smooth_uv_sphere_matches_the_analytic_sphere_and_beats_the_faceted_one() {
    let (positions, triangles) = uv_sphere();
    check_against_analytic("UV sphere", &positions, &triangles, 0.06);
}

#[test]
fn smooth_icosphere_matches_the_analytic_sphere_per_pixel() {
    let (positions, triangles) = icosphere(2);
    check_against_analytic("icosphere", &positions, &triangles, 0.06);
}

#[test]
fn shading_normal_is_on_the_geometric_side_and_absent_without_normals() {
    let (positions, triangles) = uv_sphere();
    let surface = Surface::diffuse(Vec3::splat(0.7));
    // Normals pointing inwards (authored the wrong way round) are flipped to the ray's side.
    let inward: Vec<Vec3> = positions.iter().map(|&p| -p).collect();
    let scene = lit(Scene::builder().attributed_mesh(
        &positions,
        &triangles,
        surface,
        VertexAttributes {
            normals: Some(inward),
            ..VertexAttributes::default()
        },
    ));
    let ray = photon_maps::trace::Ray::new(Vec3::new(0.1, 0.2, 4.0), Vec3::NEG_Z);
    let hit = scene
        .intersect(&ray, f32::INFINITY, photon_maps::trace::RayKind::Camera)
        .unwrap();
    let n = scene.shading_normal_at(&hit);
    assert!(
        n.dot(hit.normal) > 0.9 && (n.length() - 1.0).abs() < 1e-4,
        "{n} vs {}",
        hit.normal
    );
    assert!(
        (n - hit.position.normalize()).length() < 0.05,
        "{n} at {}",
        hit.position
    );
    let plain = lit(Scene::builder().mesh(&positions, &triangles, surface));
    let hit = plain
        .intersect(&ray, f32::INFINITY, photon_maps::trace::RayKind::Camera)
        .unwrap();
    assert_eq!(plain.shading_normal_at(&hit), hit.normal);
}
