//! Photon power is stored relative to each map's own scale, so a render does not depend on the
//! absolute power a photon carries: the Cornell box (about 7·10⁻⁴ W per photon at 10⁴ photons,
//! 2·10⁻⁶ W at 3·10⁶) agrees with the path tracer at every photon count, and a scene lit at
//! 10⁻⁶ W, 1 W or 10¹² W renders the same image up to that factor.

use glam::Vec3;
use photon_maps::render::{EstimatorKind, Image, Mode, RenderSettings, Rendered, Renderer};
use photon_maps::trace::{CreaseAngle, Scene, scenes};
use std::f32::consts::PI;

#[path = "support/furnace_sphere.rs"]
mod furnace_sphere;
use furnace_sphere::furnace_sphere;
use photon_maps::trace::Partitioner;

const SIZE: u32 = 48;

fn render(scene: &Scene, mode: Mode, photons: u32, spp: u32, seed: u64) -> Rendered {
    let settings = RenderSettings {
        width: SIZE,
        height: SIZE,
        samples_per_pixel: spp,
        photons,
        mode,
        seed,
        ..RenderSettings::default()
    };
    Renderer::new(EstimatorKind::GeometryCube, settings)
        .render(&CreaseAngle::default().partition(scene.clone()).unwrap(), &())
        .expect("renders")
}

fn mean(image: &Image) -> [f64; 3] {
    image.mean().as_dvec3().to_array()
}

#[test]
fn cornell_box_matches_the_path_tracer_from_ten_thousand_to_three_million_photons() {
    let scene = scenes::build("cornell-box").expect("built-in scene");
    // The reference: two path-traced renders with different seeds. Their half difference
    // estimates the standard error of their mean.
    let pt: Vec<[f64; 3]> = [1, 2]
        .map(|seed| mean(&render(&scene, Mode::PathTrace, 1, 256, seed).image))
        .to_vec();
    let reference: [f64; 3] = std::array::from_fn(|c| (pt[0][c] + pt[1][c]) / 2.0);
    let reference_se: [f64; 3] = std::array::from_fn(|c| (pt[0][c] - pt[1][c]).abs() / 2.0);
    eprintln!("path traced {:?} and {:?}", pt[0], pt[1]);
    for c in 0..3 {
        assert!(
            reference_se[c] < 0.003 * reference[c],
            "the reference is too noisy: channel {c} {:?}",
            pt
        );
    }
    // 16 samples per pixel average out the pixels on the light's edges (the light is 400
    // times brighter than the walls).
    for photons in [10_000, 100_000, 1_000_000, 3_000_000] {
        let out = render(&scene, Mode::PhotonMap, photons, 16, 1);
        assert_eq!(out.stats.photon_channels_below_range, 0);
        let m = mean(&out.image);
        eprintln!("{photons} photons: mean {m:?}, path traced {reference:?}");
        for c in 0..3 {
            let relative = m[c] / reference[c] - 1.0;
            assert!(
                relative.abs() < 0.03,
                "{photons} photons, channel {c}: mean {} vs path traced {} ({:+.2} %)",
                m[c],
                reference[c],
                100.0 * relative
            );
        }
    }
    // At 10⁶ photons: independent replicates (seeds) give the standard error of the
    // photon-mapped mean; it must agree with the reference within 4 combined standard errors.
    let replicates: Vec<[f64; 3]> = (10..15)
        .map(|seed| mean(&render(&scene, Mode::PhotonMap, 1_000_000, 16, seed).image))
        .collect();
    let r = replicates.len() as f64;
    for c in 0..3 {
        let values: Vec<f64> = replicates.iter().map(|m| m[c]).collect();
        let avg = values.iter().sum::<f64>() / r;
        let var = values.iter().map(|v| (v - avg).powi(2)).sum::<f64>() / (r - 1.0);
        let se = (var / r + reference_se[c].powi(2)).sqrt();
        let apart = (avg - reference[c]).abs() / se;
        eprintln!(
            "1M photons channel {c}: replicates {values:?}, mean {avg:.5} vs path traced {:.5}: {apart:.2} standard errors ({se:.5}) apart",
            reference[c]
        );
        assert!(
            apart < 4.0,
            "1M photons channel {c}: mean of {r} replicates {avg:.5} vs path traced {:.5} is {apart:.2} standard errors ({se:.5}) apart",
            reference[c]
        );
    }
}

/// pbrt's furnace: a closed diffuse sphere (albedo 0.5) around a point light; radiance is
/// `power / (4π²)` per channel everywhere.
fn furnace(power: Vec3) -> Scene {
    furnace_sphere(power)
}

#[test]
fn light_power_from_a_microwatt_to_a_terawatt_scales_the_image_and_nothing_else() {
    let colour = Vec3::new(1.0, 0.5, 0.25) * 4.0 * PI * PI;
    let unit = render(&furnace(colour), Mode::PhotonMap, 60_000, 1, 3);
    let m = unit.image.mean();
    // A sanity check of the scene (tests/render_analytic.rs checks the estimators' accuracy).
    assert!(
        ((m - Vec3::new(1.0, 0.5, 0.25)) / Vec3::new(1.0, 0.5, 0.25))
            .abs()
            .max_element()
            < 0.05,
        "the furnace's radiance is its power / 4π²: {m}"
    );
    for factor in [1e-6f32, 1e12] {
        let out = render(&furnace(colour * factor), Mode::PhotonMap, 60_000, 1, 3);
        assert_eq!(out.stats.photon_channels_below_range, 0);
        let mut worst = 0.0f32;
        for (scaled, one) in out.image.pixels().iter().zip(unit.image.pixels()) {
            for c in 0..3 {
                let relative = (scaled[c] / factor / one[c] - 1.0).abs();
                worst = worst.max(relative);
                assert!(
                    relative <= 0.01,
                    "light × {factor:e}: pixel {scaled} / {factor:e} vs {one}"
                );
            }
        }
        eprintln!("light × {factor:e}: worst pixel differs by {worst:.2e} (relative) after scaling");
    }
}
