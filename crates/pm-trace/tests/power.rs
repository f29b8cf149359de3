//! Power conservation: photons carry exactly the lights' power, and with Russian roulette on
//! albedo ρ the stored power is Φ/(1−ρ) in expectation.

mod common;

use pm_trace::glam::{DVec3, Vec3};
use pm_trace::{Partitioner, scenes};
use pm_trace::{PhotonKind, PhotonMaps, PointLight, Scene, SingleMap, Surface, TraceOptions, trace_photons};

fn closed_box(albedo: f32, power: Vec3) -> Scene {
    let (corners, faces) = common::unit_box();
    Scene::builder()
        .mesh(&corners, &faces, Surface::diffuse(Vec3::splat(albedo)))
        .light(PointLight::new(Vec3::new(0.3, 0.6, 0.4), power))
        .build()
        .unwrap()
}

#[test]
fn black_box_stores_exactly_the_light_power_as_direct_photons() {
    let power = Vec3::new(10.0, 20.0, 5.0);
    let scene = closed_box(0.0, power);
    let maps = SingleMap.partition(scene.clone()).unwrap().assignment().clone();
    let traced = trace_photons(
        &scene,
        &maps,
        &TraceOptions {
            photons: 100_000,
            seed: 9,
            max_bounces: 16,
            pass: 0,
        },
    )
    .unwrap();
    assert_eq!(traced.stats().total_stored(), 100_000);
    assert_eq!(traced.stats().stored[0][PhotonKind::Direct as usize], 100_000);
    let stored = common::stored_power(&traced, Some(PhotonKind::Direct));
    assert!(
        ((stored - power.as_dvec3()) / power.as_dvec3())
            .abs()
            .max_element()
            < 1e-5,
        "{stored} vs {power}"
    );
    // After the 20-byte encoding, within its precision (0.5 % per photon, so also in sum).
    let built = PhotonMaps::build(&scene, &maps, traced).unwrap();
    built.validate().unwrap();
    let tree = built.map(0).tree();
    let decoded: DVec3 = (0..tree.len() as u32).map(|i| tree.power(i).as_dvec3()).sum();
    assert!(
        ((decoded - power.as_dvec3()) / power.as_dvec3())
            .abs()
            .max_element()
            < 5e-3,
        "{decoded} vs {power}"
    );
}

#[test]
fn grey_box_stores_power_over_one_minus_albedo_within_three_standard_errors() {
    // Each stored photon carries Φ/N; a path stores K ~ Geometric(1 − ρ) photons:
    // E[K] = 1/(1 − ρ), Var[K] = ρ/(1 − ρ)². Total stored = Φ/N · ΣK.
    let rho = 0.5f32;
    let n = 200_000u32;
    let power = Vec3::splat(3.0);
    let scene = closed_box(rho, power);
    let maps = SingleMap.partition(scene.clone()).unwrap().assignment().clone();
    let traced = trace_photons(
        &scene,
        &maps,
        &TraceOptions {
            photons: n,
            seed: 5,
            max_bounces: 200,
            pass: 0,
        },
    )
    .unwrap();
    let stored = common::stored_power(&traced, None).x as f64;
    let phi = power.x as f64;
    let expected = phi / (1.0 - rho as f64);
    let se = phi / n as f64 * (n as f64 * rho as f64).sqrt() / (1.0 - rho as f64);
    assert!(
        (stored - expected).abs() < 3.0 * se,
        "{stored} vs {expected} ± {se}"
    );
    assert!(traced.stats().stored[0][PhotonKind::Indirect as usize] > 0);
}

#[test]
fn cornell_box_photons_share_the_light_power() {
    let scene = scenes::build("cornell-box").unwrap();
    let total: Vec3 = scene.lights().iter().map(|l| l.power()).sum();
    // Light quad 0.13 × 0.105 m of radiance (17, 12, 4): Φ = π L A.
    let expected = Vec3::new(17.0, 12.0, 4.0) * (std::f32::consts::PI * 0.13 * 0.105);
    assert!(((total - expected) / expected).abs().max_element() < 1e-4);
    let maps = SingleMap.partition(scene.clone()).unwrap().assignment().clone();
    let traced = trace_photons(
        &scene,
        &maps,
        &TraceOptions {
            photons: 20_000,
            seed: 1,
            max_bounces: 64,
            pass: 0,
        },
    )
    .unwrap();
    // Every direct photon carries Φ/N (single light).
    for p in traced.photons(0).iter().filter(|p| p.kind == PhotonKind::Direct) {
        assert!(
            ((p.power - expected / 20_000.0) / expected * 20_000.0)
                .abs()
                .max_element()
                < 1e-4
        );
    }
}

#[test]
fn lossless_glass_and_mirror_spheres_pass_all_power_on_as_caustics() {
    // Black closed box: every path ends at its first diffuse hit, so the stored power is the
    // light's power exactly, whatever the specular bounces on the way.
    let power = Vec3::splat(6.0);
    let (corners, faces) = common::unit_box();
    for sphere in [Surface::glass(1.5), Surface::mirror(Vec3::ONE)] {
        let scene = Scene::builder()
            .mesh(&corners, &faces, Surface::diffuse(Vec3::ZERO))
            .sphere(Vec3::new(0.5, 0.35, 0.5), 0.2, sphere)
            .light(PointLight::new(Vec3::new(0.5, 0.8, 0.5), power))
            .build()
            .unwrap();
        let maps = SingleMap.partition(scene.clone()).unwrap().assignment().clone();
        let n = 50_000;
        let traced = trace_photons(
            &scene,
            &maps,
            &TraceOptions {
                photons: n,
                seed: 2,
                max_bounces: 64,
                pass: 0,
            },
        )
        .unwrap();
        let stats = traced.stats();
        assert_eq!(stats.stored[0][PhotonKind::Indirect as usize], 0);
        // The sphere subtends (1 − cos asin(0.2/0.45))/2 ≈ 5.2 % of the light's directions.
        let caustic = stats.stored[0][PhotonKind::Caustic as usize] as f64 / n as f64;
        let expected = (1.0 - (1.0f64 - (0.2f64 / 0.45).powi(2)).sqrt()) / 2.0;
        let se = (expected * (1.0 - expected) / n as f64).sqrt();
        // Paths that never leave the glass (trapped by total internal reflection) are cut at
        // max_bounces; they are rare.
        assert!(
            (caustic - expected).abs() < 4.0 * se + 1e-3,
            "{sphere:?}: {caustic} vs {expected}"
        );
        let stored = common::stored_power(&traced, None);
        assert!(((stored.x - 6.0) / 6.0).abs() < 1e-3, "{sphere:?}: {stored}");
    }
}
