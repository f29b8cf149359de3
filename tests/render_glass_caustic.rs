//! A smooth glass sphere focuses a caustic: a 320-triangle icosphere of glass (index 1.5) with
//! per-vertex normals, hung over a floor at its paraxial back focal distance and lit straight
//! down by a directional light of irradiance E₀. Photons refracted about the interpolated
//! normal meet in a bright spot whose irradiance is over 50 E₀ and within 25 % of the exact
//! (analytic) sphere's; the same mesh without normals bends light at each flat facet like a
//! prism and spreads it into a speckled patch with a peak under half the smooth one's. Seen
//! through the ball (eye rays refracted by the render modes), the smooth mesh's image is
//! within a third of the faceted one's difference from the exact sphere's.

use photon_maps::render::{EstimatorKind, Image, Mode, RenderSettings, Renderer};
use photon_maps::trace::glam::{Vec2, Vec3};
use photon_maps::trace::{
    Camera, DirectionalLight, Partitioner, Photon, Scene, SingleMap, Surface, TraceOptions, VertexAttributes,
    trace_photons,
};
use std::f32::consts::PI;

#[path = "../crates/pm-trace/tests/common/mod.rs"]
mod common;

/// A unit icosphere at the origin: the icosahedron subdivided `levels` times.
fn icosphere(levels: u32) -> (Vec<Vec3>, Vec<[u32; 3]>) {
    common::icosphere(Vec3::ZERO, 1.0, levels)
}

/// Sphere radius and index of refraction.
const RADIUS: f32 = 0.25;
const IOR: f32 = 1.5;
/// Irradiance of the light on the unoccluded floor, W/m².
const E0: f32 = 1.0;
/// Radius of the disc the peak irradiance is measured over, m.
const SPOT: f32 = 0.01;

/// What hangs over the floor.
#[derive(Clone, Copy, PartialEq)]
enum Ball {
    None,
    /// The exact sphere (the analytic shape), the reference.
    Analytic,
    /// A 320-triangle icosphere with per-vertex normals.
    Smooth,
    /// The same icosphere without normals.
    Faceted,
}

/// The floor (2 m square at y = 0, white 0.8), the light, and the glass ball, its centre at
/// the paraxial focus height: a ball lens focuses parallel light `n R / (2 (n − 1))` from its
/// centre.
fn scene(ball: Ball) -> Scene {
    let floor = [
        Vec3::new(-1.0, 0.0, -1.0),
        Vec3::new(-1.0, 0.0, 1.0),
        Vec3::new(1.0, 0.0, 1.0),
        Vec3::new(1.0, 0.0, -1.0),
    ];
    let builder = Scene::builder()
        .mesh(&floor, &[[0u32, 1, 2, 3]], Surface::diffuse(Vec3::splat(0.8)))
        .light(DirectionalLight::new(Vec3::NEG_Y, Vec3::splat(E0)));
    let centre = Vec3::new(0.0, IOR * RADIUS / (2.0 * (IOR - 1.0)), 0.0);
    let (unit, triangles) = icosphere(2);
    let positions: Vec<Vec3> = unit.iter().map(|&p| centre + RADIUS * p).collect();
    let attributes = VertexAttributes {
        normals: (ball == Ball::Smooth).then(|| unit.clone()),
        ..VertexAttributes::default()
    };
    let builder = match ball {
        Ball::None => builder,
        Ball::Analytic => builder.sphere(centre, RADIUS, Surface::glass(IOR)),
        Ball::Smooth | Ball::Faceted => {
            builder.attributed_mesh(&positions, &triangles, Surface::glass(IOR), attributes)
        }
    };
    builder.build().unwrap()
}

/// The photons stored on the floor (y ≈ 0).
fn floor_photons(scene: &Scene, photons: u32) -> Vec<Photon> {
    let maps = SingleMap.partition(scene.clone()).unwrap().assignment().clone();
    let options = TraceOptions {
        photons,
        seed: 5,
        ..TraceOptions::default()
    };
    let traced = trace_photons(scene, &maps, &options).unwrap();
    traced
        .photons_per_map()
        .iter()
        .flatten()
        .filter(|p| p.position.y.abs() < 1e-4)
        .copied()
        .collect()
}

/// Irradiance (W/m²) at floor point `at`: the power of the photons within `radius`, over the
/// disc's area.
fn irradiance(photons: &[Photon], at: Vec2, radius: f32) -> f32 {
    let power: f32 = photons
        .iter()
        .filter(|p| Vec2::new(p.position.x, p.position.z).distance_squared(at) < radius * radius)
        .map(|p| p.power.x)
        .sum();
    power / (PI * radius * radius)
}

/// The largest irradiance over discs of radius [`SPOT`] centred on a 5 mm grid within 0.1 m of
/// the point under the sphere.
fn peak_irradiance(photons: &[Photon]) -> f32 {
    let near: Vec<Photon> = photons
        .iter()
        .filter(|p| p.position.x.abs() < 0.12 && p.position.z.abs() < 0.12)
        .copied()
        .collect();
    let mut peak = 0.0f32;
    for i in -20..=20 {
        for j in -20..=20 {
            let at = Vec2::new(i as f32, j as f32) * 0.005;
            peak = peak.max(irradiance(&near, at, SPOT));
        }
    }
    peak
}

#[test]
fn smooth_glass_sphere_focuses_a_caustic_far_brighter_than_the_open_floor() {
    let photons = 400_000;
    // Without the sphere the floor's photon irradiance is E₀ (a check on the measure itself,
    // over a disc wide enough to hold thousands of photons).
    let open = floor_photons(&scene(Ball::None), photons);
    let open_e = irradiance(&open, Vec2::ZERO, 0.1);
    let open_peak = peak_irradiance(&open);
    let [analytic, smooth, faceted] = [Ball::Analytic, Ball::Smooth, Ball::Faceted]
        .map(|b| peak_irradiance(&floor_photons(&scene(b), photons)));
    println!(
        "open floor E = {open_e:.3} W/m² (E₀ = {E0}); peak over {SPOT} m discs: open floor {open_peak:.2}, \
         analytic sphere {analytic:.1}, smooth icosphere {smooth:.1}, faceted icosphere {faceted:.1} W/m²"
    );
    assert!((open_e - E0).abs() < 0.05 * E0, "open floor {open_e}");
    assert!(smooth > 50.0 * E0, "smooth caustic peak only {smooth}");
    assert!(
        (smooth - analytic).abs() < 0.25 * analytic,
        "smooth {smooth} vs analytic {analytic}"
    );
    assert!(smooth > 2.0 * faceted, "smooth {smooth} vs faceted {faceted}");
}

/// The ball and the floor seen obliquely through it, photon-mapped (PhotonMap mode: specular bounces
/// from the eye, then the floor's photon estimate, caustic included).
fn view(ball: Ball) -> Image {
    let centre = Vec3::new(0.0, IOR * RADIUS / (2.0 * (IOR - 1.0)), 0.0);
    let scene = scene(ball)
        .with_camera(Camera::new(Vec3::new(0.0, 1.0, 1.2), centre, Vec3::Y, 0.45))
        .unwrap();
    let settings = RenderSettings {
        width: 64,
        height: 64,
        photons: 200_000,
        mode: Mode::PhotonMap,
        seed: 2,
        ..RenderSettings::default()
    };
    Renderer::new(EstimatorKind::Disc, settings)
        .render(&SingleMap.partition(scene.clone()).unwrap(), &())
        .unwrap()
        .image
}

/// Mean over pixels of the absolute difference of the channel sums.
fn mean_difference(a: &Image, b: &Image) -> f32 {
    let sum: f32 = a
        .pixels()
        .iter()
        .zip(b.pixels())
        .map(|(p, q)| (p.element_sum() - q.element_sum()).abs())
        .sum();
    sum / a.pixels().len() as f32
}

#[test]
fn seen_through_the_smooth_ball_the_floor_looks_as_through_the_exact_sphere() {
    let [analytic, smooth, faceted] = [Ball::Analytic, Ball::Smooth, Ball::Faceted].map(view);
    let (smooth_error, faceted_error) = (
        mean_difference(&smooth, &analytic),
        mean_difference(&faceted, &analytic),
    );
    let scale = analytic.mean().element_sum();
    println!(
        "mean |difference| from the analytic sphere's image: smooth {:.4}, faceted {:.4} (image mean {scale:.4})",
        smooth_error, faceted_error
    );
    assert!(
        smooth_error < 0.35 * faceted_error,
        "smooth {smooth_error} vs faceted {faceted_error}"
    );
}
