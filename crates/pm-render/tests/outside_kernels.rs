//! A distance-weighted kernel written outside pm-render with only public items: Epanechnikov's
//! kernel, the worked example of the estimator docs, against the closed form on a plane lit
//! uniformly by a directional light, with photons traced and mapped by the library.

use pm_render::prelude::*;
use std::f32::consts::PI;

/// Epanechnikov's kernel over the k nearest photons, `K(d) = 2/(π r²) · (1 − d²/r²)`.
struct Epanechnikov;

impl Estimator for Epanechnikov {
    fn estimate(
        &self,
        at: SurfacePoint,
        map: MapView<'_>,
        options: &EstimatorOptions,
        weight: &dyn PhotonWeight,
        scratch: &mut EstimatorScratch,
    ) -> Vec3 {
        let Some(r) = find_nearest::<Euclidean>(at, map, options, scratch) else {
            return Vec3::ZERO;
        };
        gather_found(at, map.tree, options, weight, scratch);
        let r2 = r * r;
        let weighted: Vec3 = scratch
            .photons()
            .iter()
            .map(|p| p.power * (1.0 - p.distance_squared / r2).max(0.0))
            .sum();
        weighted * (2.0 / (PI * r2))
    }
}

/// The irradiance on the floor of a 2 m × 2 m plane under a directional light straight down:
/// the light's own irradiance, the same everywhere (the plane reflects light upwards, where
/// nothing returns it).
const IRRADIANCE: Vec3 = Vec3::new(2.0, 1.0, 0.5);

/// The photon map of that plane, traced and built by the library.
fn lit_plane(photons: u32) -> PhotonMaps {
    let floor = [
        vec3(-1.0, 0.0, -1.0),
        vec3(-1.0, 0.0, 1.0),
        vec3(1.0, 0.0, 1.0),
        vec3(1.0, 0.0, -1.0),
    ];
    let scene = Scene::builder()
        .mesh(&floor, &[[0u32, 1, 2, 3]], Surface::diffuse(Vec3::splat(0.5)))
        .light(DirectionalLight::new(Vec3::NEG_Y, IRRADIANCE))
        .build()
        .unwrap();
    let assignment: MapAssignment = SingleMap.partition(scene.clone()).unwrap().assignment().clone();
    let options = TraceOptions {
        photons,
        seed: 3,
        ..TraceOptions::default()
    };
    let traced = trace_photons(&scene, &assignment, &options).unwrap();
    PhotonMaps::build(&scene, &assignment, traced).unwrap()
}

#[test]
fn epanechnikov_outside_the_crate_matches_the_closed_form_on_a_uniformly_lit_plane() {
    let maps = lit_plane(60_000);
    let map = maps.map(0);
    assert!(
        map.tree().len() > 30_000,
        "{} photons on the plane",
        map.tree().len()
    );
    let view = MapView {
        tree: map.tree(),
        polygons: map.geometry(),
    };
    let options = EstimatorOptions {
        k: 64,
        ..EstimatorOptions::with_max_distance(0.5)
    };
    let mut scratch = EstimatorScratch::new();
    // 20 × 20 points at least 0.2 m (about three gather radii) from the plane's edges.
    let mut sum = Vec3::ZERO;
    let mut square_deviation = 0.0f32;
    let n = 20;
    for i in 0..n {
        for j in 0..n {
            let x = -0.8 + 1.6 * (i as f32 + 0.5) / n as f32;
            let z = -0.8 + 1.6 * (j as f32 + 0.5) / n as f32;
            let at = SurfacePoint::front(vec3(x, 0.0, z), Vec3::Y);
            let e = Epanechnikov.irradiance(at, view, &options, &mut scratch);
            square_deviation += (e.x / IRRADIANCE.x - 1.0).powi(2);
            sum += e;
        }
    }
    let mean = sum / (n * n) as f32;
    // With photons scattered as a Poisson process, each estimate deviates by about
    // √(1/(k − 2) + 1/(3(k − 1))) ≈ 14 % (the k-th radius, then the weights), and the mean of
    // 400 by about 0.7 %: the mean is unbiased, so it lies within 2 % of the closed form.
    let error = (mean / IRRADIANCE - 1.0).abs().max_element();
    let rms = (square_deviation / (n * n) as f32).sqrt();
    eprintln!(
        "mean {mean}, {:.2} % off; rms deviation {:.1} %",
        100.0 * error,
        100.0 * rms
    );
    assert!(
        error < 0.02,
        "mean {mean} against {IRRADIANCE}: {:.2} % off",
        100.0 * error
    );
    assert!((0.09..0.2).contains(&rms), "rms deviation {:.1} %", 100.0 * rms);
}

#[test]
fn epanechnikov_without_the_power_scale_would_be_visibly_wrong() {
    // The decoded powers are watts: the kernel's estimate is the irradiance whatever scale the
    // map encodes its photons with (here far from 1 W, so a forgotten scale could not pass).
    let maps = lit_plane(20_000);
    let tree = maps.map(0).tree();
    let scale = tree.power_scale().watts();
    assert!(!(0.5..2.0).contains(&scale), "power scale {scale} W");
    let view = MapView {
        tree,
        polygons: maps.map(0).geometry(),
    };
    let options = EstimatorOptions::with_max_distance(0.5);
    let mut scratch = EstimatorScratch::new();
    let at = SurfacePoint::front(Vec3::ZERO, Vec3::Y);
    let e = Epanechnikov.irradiance(at, view, &options, &mut scratch);
    assert!(
        (e / IRRADIANCE - 1.0).abs().max_element() < 0.5,
        "{e} against {IRRADIANCE}"
    );
    let total: Vec3 = scratch.photons().iter().map(|p| p.power).sum();
    let exact: Vec3 = scratch
        .neighbours()
        .iter()
        .map(|n| tree.get(n.index).power(tree.power_scale()))
        .sum();
    assert!((total - exact).abs().max_element() <= 1e-6 * exact.max_element());
}
