//! Irradiance from photon counts against closed forms: point light over a floor (solid angle
//! of a disc), directional light (E₀ cos θ), quad area light (rectangle form factor). Also
//! the shadow-ray samples of each light against the same closed forms.

use pm_trace::glam::Vec3;
use pm_trace::{AreaLight, DirectionalLight, Light, PointLight, Scene, SingleMap, Surface, TraceOptions};
use pm_trace::{Partitioner, PhotonKind, Rng, trace_photons};
use std::f64::consts::PI;

/// A black 20 m × 20 m floor at y = 0 with `light`.
fn floor_scene(light: impl Light + 'static) -> Scene {
    let h = 10.0;
    let floor = [
        Vec3::new(-h, 0.0, -h),
        Vec3::new(-h, 0.0, h),
        Vec3::new(h, 0.0, h),
        Vec3::new(h, 0.0, -h),
    ];
    Scene::builder()
        .mesh(&floor, &[[0u32, 1, 2, 3]], Surface::diffuse(Vec3::ZERO))
        .light(light)
        .build()
        .unwrap()
}

/// Direct photons landing where `inside` holds: (count, power per photon).
fn count_direct(scene: &Scene, n: u32, inside: impl Fn(Vec3) -> bool) -> (u64, f64) {
    let maps = SingleMap.partition(scene.clone()).unwrap().assignment().clone();
    let traced = trace_photons(
        scene,
        &maps,
        &TraceOptions {
            photons: n,
            seed: 11,
            max_bounces: 4,
            pass: 0,
        },
    )
    .unwrap();
    let photons = traced.photons(0);
    let count = photons
        .iter()
        .filter(|p| p.kind == PhotonKind::Direct && inside(p.position))
        .count() as u64;
    (count, scene.lights()[0].power().x as f64 / n as f64)
}

fn assert_within_3_se(count: u64, expected_count: f64, what: &str) {
    let se = expected_count.sqrt();
    assert!(
        (count as f64 - expected_count).abs() < 3.0 * se,
        "{what}: {count} photons, expected {expected_count:.1} ± {se:.1}"
    );
}

#[test]
fn point_light_photon_count_in_a_disc_matches_the_solid_angle() {
    let (h, r, n) = (1.0f64, 0.1f64, 1_000_000u32);
    let scene = floor_scene(PointLight::new(Vec3::new(0.0, h as f32, 0.0), Vec3::splat(100.0)));
    let (count, _) = count_direct(&scene, n, |p| p.x * p.x + p.z * p.z < (r * r) as f32);
    // Fraction of directions within the disc: (1 − h/√(h² + r²)) / 2.
    let fraction = (1.0 - h / (h * h + r * r).sqrt()) / 2.0;
    assert_within_3_se(count, n as f64 * fraction, "point light");
    // And the irradiance it implies is Φ/(4πh²) up to the disc's (r/h)² falloff.
    let e = count as f64 * 100.0 / n as f64 / (PI * r * r);
    let e0 = 100.0 / (4.0 * PI * h * h);
    assert!(
        (e / e0 - 1.0).abs() < 3.0 / (n as f64 * fraction).sqrt() + 0.015,
        "{e} vs {e0}"
    );
}

#[test]
fn directional_light_irradiance_is_e0_cos_theta() {
    let theta = 40f64.to_radians();
    let e0 = 5.0f64;
    let dir = Vec3::new(theta.sin() as f32, -theta.cos() as f32, 0.0);
    let scene = floor_scene(DirectionalLight::new(dir, Vec3::splat(e0 as f32)));
    let n = 1_000_000;
    let half = 2.0f32;
    let (count, per_photon) = count_direct(&scene, n, |p| p.x.abs() < half && p.z.abs() < half);
    let area = (2.0 * half as f64).powi(2);
    let expected = e0 * theta.cos() * area / per_photon;
    assert_within_3_se(count, expected, "directional light");
}

/// Form factor from a point to a parallel rectangle `a × b` whose corner is straight above
/// at height `h`, times π: irradiance / radiance.
fn rectangle_corner_e_over_l(a: f64, b: f64, h: f64) -> f64 {
    let (x, y) = (a / h, b / h);
    let sx = (1.0 + x * x).sqrt();
    let sy = (1.0 + y * y).sqrt();
    0.5 * (x / sx * (y / sx).atan() + y / sy * (x / sy).atan())
}

#[test]
fn quad_area_light_irradiance_matches_the_rectangle_form_factor() {
    let (side, h, r, n) = (0.5f64, 1.0f64, 0.05f64, 2_000_000u32);
    let s = side as f32;
    let corner = Vec3::new(-s / 2.0, h as f32, -s / 2.0);
    // Edges x then z: x × z = −y, so it faces the floor.
    let light = AreaLight::quad(corner, Vec3::new(s, 0.0, 0.0), Vec3::new(0.0, 0.0, s), Vec3::ONE);
    let e_center = 4.0 * rectangle_corner_e_over_l(side / 2.0, side / 2.0, h);
    let scene = floor_scene(light);
    let (count, per_photon) = count_direct(&scene, n, |p| p.x * p.x + p.z * p.z < (r * r) as f32);
    // The irradiance falls off by O((r/h)²) ≈ 0.25 % over the disc: below 3 SE (≈ 5 %).
    let expected = e_center * PI * r * r / per_photon;
    assert_within_3_se(count, expected, "area light");
}

/// Mean of `radiance_over_pdf · cos` over shadow samples towards `light` at `point` facing up.
fn sampled_irradiance(light: &dyn Light, point: Vec3, samples: u32) -> f64 {
    let mut rng = Rng::new(3, 3);
    let mut sum = 0.0f64;
    for _ in 0..samples {
        if let Some(s) = light.sample_incident(point, Vec3::Y, &mut rng) {
            sum += (s.radiance_over_pdf.x * s.direction.dot(Vec3::Y).max(0.0)) as f64;
        }
    }
    sum / samples as f64
}

#[test]
fn shadow_ray_samples_give_the_closed_form_irradiance() {
    let point = PointLight::new(Vec3::new(0.3, 2.0, 0.0), Vec3::splat(50.0));
    let d2: f64 = 0.09 + 4.0;
    let expected = 50.0 / (4.0 * PI * d2) * (2.0 / d2.sqrt());
    assert!((sampled_irradiance(&point, Vec3::ZERO, 10) / expected - 1.0).abs() < 1e-5);

    let mut sun = DirectionalLight::new(Vec3::new(1.0, -1.0, 0.0), Vec3::splat(2.0));
    sun.attach(&pm_geom::Aabb::cube(Vec3::ZERO, 1.0));
    let expected = 2.0 * std::f64::consts::FRAC_1_SQRT_2;
    assert!((sampled_irradiance(&sun, Vec3::ZERO, 10) / expected - 1.0).abs() < 1e-5);
    // Its power is E₀ times the area of its emission disc, which covers the bounds.
    assert!(sun.power().x as f64 >= 2.0 * PI * 3.0);

    let quad = AreaLight::quad(
        Vec3::new(-0.25, 1.0, -0.25),
        Vec3::new(0.5, 0.0, 0.0),
        Vec3::new(0.0, 0.0, 0.5),
        Vec3::ONE,
    );
    let expected = 4.0 * rectangle_corner_e_over_l(0.25, 0.25, 1.0);
    let samples = 200_000;
    let got = sampled_irradiance(&quad, Vec3::ZERO, samples);
    // cos⁴-shaped integrand over a small light: relative spread well under 10 %.
    assert!((got / expected - 1.0).abs() < 0.002, "{got} vs {expected}");
}

#[test]
fn spot_light_photons_stay_in_the_cone_and_shadow_samples_give_its_intensity() {
    use pm_trace::SpotLight;
    let cone = 30f32.to_radians();
    let h = 1.0f32;
    let spot = SpotLight::new(Vec3::new(0.0, h, 0.0), Vec3::NEG_Y, cone, Vec3::splat(20.0));
    let scene = floor_scene(spot);
    let n = 100_000;
    let reach = h * cone.tan() * 1.0001;
    let (count, _) = count_direct(&scene, n, |p| p.x * p.x + p.z * p.z <= reach * reach);
    assert_eq!(count, n as u64, "every photon lands inside the cone's footprint");
    // Intensity Φ / (2π (1 − cos θ)) inside, nothing outside.
    let intensity = 20.0 / (2.0 * PI * (1.0 - (cone as f64).cos()));
    let mut rng = Rng::new(0, 0);
    let s = spot.sample_incident(Vec3::ZERO, Vec3::Y, &mut rng).unwrap();
    assert!((s.radiance_over_pdf.x as f64 / intensity - 1.0).abs() < 1e-5);
    assert!(
        spot.sample_incident(Vec3::new(1.0, 0.0, 0.0), Vec3::Y, &mut rng)
            .is_none()
    );
}
