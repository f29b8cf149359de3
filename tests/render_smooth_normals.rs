//! Shading normals: a coarse UV sphere with per-vertex normals, lit by a point light and
//! path traced, matches the analytic sphere of the same radius away from the silhouette and
//! the terminator, and clearly better than the same mesh without normals (faceted).

use glam::Vec3;
use photon_maps::render::{EstimatorKind, Image, Mode, RenderSettings, Renderer};
use photon_maps::trace::{Camera, CreaseAngle, PointLight, Scene, SceneBuilder, Surface, VertexAttributes};
use std::f32::consts::PI;

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
        .render(scene, &CreaseAngle::default(), &())
        .unwrap()
        .image
}

/// Mean per-pixel relative difference to `reference` over pixels well lit in the reference
/// whose 3×3 neighbourhoods are covered in both images (away from the silhouette).
fn mean_relative_difference(image: &Image, reference: &Image) -> (f32, usize) {
    let peak = reference.pixels().iter().map(|p| p.x).fold(0.0, f32::max);
    let covered = |img: &Image, x: u32, y: u32| {
        (x.saturating_sub(1)..=(x + 1).min(img.width() - 1)).all(|i| {
            (y.saturating_sub(1)..=(y + 1).min(img.height() - 1)).all(|j| img.get(i, j).unwrap().x > 0.0)
        })
    };
    let (mut sum, mut n) = (0.0, 0);
    for y in 0..reference.height() {
        for x in 0..reference.width() {
            let r = reference.get(x, y).unwrap().x;
            if r < 0.2 * peak || !covered(reference, x, y) || !covered(image, x, y) {
                continue;
            }
            sum += (image.get(x, y).unwrap().x - r).abs() / r;
            n += 1;
        }
    }
    (sum / n.max(1) as f32, n)
}

#[test]
fn smooth_uv_sphere_matches_the_analytic_sphere_and_beats_the_faceted_one() {
    let surface = Surface::diffuse(Vec3::splat(0.7));
    let (positions, triangles) = uv_sphere();
    let analytic = render(&lit(Scene::builder().sphere(Vec3::ZERO, 1.0, surface)));
    let faceted = render(&lit(Scene::builder().mesh(&positions, &triangles, surface)));
    let smooth = render(&lit(Scene::builder().attributed_mesh(
        &positions,
        &triangles,
        surface,
        VertexAttributes {
            normals: Some(positions.clone()),
            ..VertexAttributes::default()
        },
    )));
    let (smooth_error, n) = mean_relative_difference(&smooth, &analytic);
    let (faceted_error, _) = mean_relative_difference(&faceted, &analytic);
    assert!(n > 300, "only {n} pixels compared");
    assert!(
        smooth_error < 0.03,
        "smooth sphere differs by {smooth_error} on average"
    );
    assert!(
        faceted_error > 2.0 * smooth_error,
        "faceted {faceted_error} vs smooth {smooth_error}"
    );
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
