//! The photon modes' colour against the path tracer's on the Cornell box, whose light is
//! coloured (17, 12, 4): with power codes rounded to the nearest step every direct photon
//! stored green 0.174 % too high and blue 0.176 % too low; rounded stochastically (unbiased)
//! the progressive image's colour ratios G/R and B/R match the path tracer's within their
//! noise. About three minutes on two shared cores, so `#[ignore]`d:
//!
//! `cargo test --release --test power_colour_acceptance -- --ignored --nocapture`
//!
//! Measured (4 replicates each of 256 passes of 100,000 photons and of 2048 spp, 48²):
//! G/R +0.0053 % ± 0.0136 %, B/R +0.0520 % ± 0.0286 %, where nearest rounding's +0.174 % and
//! −0.176 % would stand 12.8 and 6.2 standard errors out.

use photon_maps::render::glam::DVec3;
use photon_maps::render::progressive::{ProgressiveRenderer, ProgressiveSettings};
use photon_maps::render::{EstimatorKind, Image, Mode, RenderSettings, Renderer};
use photon_maps::trace::Partitioner;
use photon_maps::trace::{CreaseAngle, scenes};

const SIZE: u32 = 48;

fn settings(mode: Mode, spp: u32, seed: u64) -> RenderSettings {
    RenderSettings {
        width: SIZE,
        height: SIZE,
        samples_per_pixel: spp,
        photons: 100_000,
        mode,
        seed,
        ..RenderSettings::default()
    }
}

fn mean(image: &Image) -> DVec3 {
    image.pixels().iter().map(|p| p.as_dvec3()).sum::<DVec3>() / image.pixels().len() as f64
}

/// (G/R, B/R) of an image's mean.
fn ratios(m: DVec3) -> [f64; 2] {
    [m.y / m.x, m.z / m.x]
}

#[test]
#[ignore]
fn progressive_colour_ratios_match_the_path_tracer() {
    let scene = scenes::build("cornell-box").unwrap();
    // Four independent replicates of each, for standard errors.
    let pt: Vec<[f64; 2]> = (0..4)
        .map(|seed| {
            let out = Renderer::new(
                EstimatorKind::GeometryCube,
                settings(Mode::PathTrace, 2048, 100 + seed),
            )
            .render(&CreaseAngle::default().partition(scene.clone()).unwrap(), &())
            .unwrap();
            ratios(mean(&out.image))
        })
        .collect();
    let pm: Vec<[f64; 2]> = (0..4)
        .map(|seed| {
            let s = ProgressiveSettings::new(settings(Mode::PhotonMap, 1, 200 + seed), 256);
            let out = ProgressiveRenderer::new(EstimatorKind::GeometryCube, s)
                .render(&CreaseAngle::default().partition(scene.clone()).unwrap(), &())
                .unwrap();
            ratios(mean(&out.accumulation.mean()))
        })
        .collect();
    let stats = |v: &[[f64; 2]], c: usize| {
        let n = v.len() as f64;
        let m = v.iter().map(|r| r[c]).sum::<f64>() / n;
        let se = (v.iter().map(|r| (r[c] - m).powi(2)).sum::<f64>() / (n - 1.0) / n).sqrt();
        (m, se)
    };
    for (c, name) in ["G/R", "B/R"].into_iter().enumerate() {
        let ((a, sa), (b, sb)) = (stats(&pm, c), stats(&pt, c));
        let offset = a / b - 1.0;
        let se = (sa * sa + sb * sb).sqrt() / b;
        println!(
            "{name}: progressive photon map {a:.6}, path tracer {b:.6}: {:+.4} % ± {:.4} % ({:.2} standard errors)",
            offset * 100.0,
            se * 100.0,
            offset / se
        );
        assert!(
            offset.abs() < 4.0 * se,
            "{name} off by {offset} ({se} standard error)"
        );
        assert!(se < 0.0005, "too noisy to see 0.05 %: {se}");
    }
}
