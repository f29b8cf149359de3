//! Multiple importance sampling of direct light (power heuristic): in a box lit by a large
//! ceiling panel, the path tracer with MIS and the same light opted out of MIS (shadow rays
//! alone, the estimator used before) agree in standard errors of independent replicates, and
//! MIS has the lower pixel variance; the final gather (which weighs its gather rays against
//! its shadow rays) agrees with both.

use photon_maps::render::glam::{Vec3, vec3};
use photon_maps::render::{EstimatorKind, FinalGatherOptions, Image, Mode, RenderSettings, Renderer};
use photon_maps::trace::Partitioner;
use photon_maps::trace::light::{EmittedRay, LightSample};
use photon_maps::trace::{AreaLight, Camera, CreaseAngle, Light, Rng, Scene, Surface};

/// An area light that does not offer its density (the trait's default): renderers then light
/// by shadow rays alone.
#[derive(Clone, Debug)]
struct WithoutMis(AreaLight);

impl Light for WithoutMis {
    fn power(&self) -> Vec3 {
        self.0.power()
    }
    fn emit(&self, rng: &mut Rng) -> EmittedRay {
        self.0.emit(rng)
    }
    fn sample_incident(&self, point: Vec3, normal: Vec3, rng: &mut Rng) -> Option<LightSample> {
        self.0.sample_incident(point, normal, rng)
    }
}

/// A closed 1 m box of albedo 0.6 with a 0.8 × 0.8 m panel of radiance 2 just under its
/// ceiling, facing down; the camera inside, looking at a corner.
fn scene(mis: bool) -> Scene {
    let corners: Vec<Vec3> = (0..8)
        .map(|i| vec3((i & 1) as f32, ((i >> 1) & 1) as f32, ((i >> 2) & 1) as f32))
        .collect();
    // Inward-facing quads: floor, ceiling, x = 0, x = 1, z = 0, z = 1.
    let faces = [
        [0u32, 4, 5, 1],
        [2, 3, 7, 6],
        [0, 2, 6, 4],
        [1, 5, 7, 3],
        [0, 1, 3, 2],
        [4, 6, 7, 5],
    ];
    let (corner, u, v) = (vec3(0.1, 0.999, 0.1), vec3(0.8, 0.0, 0.0), vec3(0.0, 0.0, 0.8));
    let radiance = Vec3::splat(2.0);
    let panel = Surface {
        emission: radiance,
        ..Surface::diffuse(Vec3::ZERO)
    };
    let quad = [corner, corner + u, corner + u + v, corner + v];
    let light = AreaLight::quad(corner, u, v, radiance);
    let builder = Scene::builder()
        .mesh(&corners, &faces, Surface::diffuse(Vec3::splat(0.6)))
        .mesh(&quad, &[[0u32, 1, 2, 3]], panel)
        .camera(Camera::new(
            vec3(0.8, 0.5, 0.8),
            vec3(-1.0, -0.3, -1.0).normalize(),
            Vec3::Y,
            1.4,
        ));
    let builder = if mis {
        builder.light(light)
    } else {
        builder.light(WithoutMis(light))
    };
    builder.build().unwrap()
}

const SIZE: u32 = 24;

fn render(scene: &Scene, mode: Mode, spp: u32, seed: u64) -> Image {
    let settings = RenderSettings {
        width: SIZE,
        height: SIZE,
        samples_per_pixel: spp,
        photons: 100_000,
        mode,
        seed,
        final_gather: FinalGatherOptions {
            gather_rays: 16,
            ..FinalGatherOptions::default()
        },
        ..RenderSettings::default()
    };
    Renderer::new(EstimatorKind::GeometryCube, settings)
        .render(&CreaseAngle::default().partition(scene.clone()).unwrap(), &())
        .unwrap()
        .image
}

/// Mean and standard error of the image mean over replicates, and the mean pixel variance
/// between replicates.
fn replicates(images: &[Image]) -> (f64, f64, f64) {
    let n = images.len() as f64;
    let means: Vec<f64> = images
        .iter()
        .map(|im| im.mean().element_sum() as f64 / 3.0)
        .collect();
    let mean = means.iter().sum::<f64>() / n;
    let se = (means.iter().map(|m| (m - mean).powi(2)).sum::<f64>() / (n - 1.0) / n).sqrt();
    let pixels = images[0].pixels().len();
    let variance = (0..pixels)
        .map(|i| {
            let values: Vec<f64> = images
                .iter()
                .map(|im| im.pixels()[i].element_sum() as f64 / 3.0)
                .collect();
            let m = values.iter().sum::<f64>() / n;
            values.iter().map(|v| (v - m).powi(2)).sum::<f64>() / (n - 1.0)
        })
        .sum::<f64>()
        / pixels as f64;
    (mean, se, variance)
}

#[test]
fn mis_agrees_with_shadow_rays_alone_and_has_less_variance() {
    let (with, without) = (scene(true), scene(false));
    let seeds = 1..9;
    let mis: Vec<Image> = seeds
        .clone()
        .map(|s| render(&with, Mode::PathTrace, 16, s))
        .collect();
    let nee: Vec<Image> = seeds.map(|s| render(&without, Mode::PathTrace, 16, s)).collect();
    let (m1, se1, v1) = replicates(&mis);
    let (m2, se2, v2) = replicates(&nee);
    let z = (m1 - m2) / (se1 * se1 + se2 * se2).sqrt();
    eprintln!(
        "path tracer with MIS {m1:.5} ± {se1:.5} (pixel variance {v1:.5}); shadow rays alone {m2:.5} ± {se2:.5} ({v2:.5}); z = {z:.2}"
    );
    assert!(
        z.abs() < 4.0,
        "MIS and shadow rays alone differ by {z} standard errors"
    );
    assert!(v1 < 0.8 * v2, "MIS should lower the variance: {v1} vs {v2}");
    // The final gather, with and without MIS, against the path tracer (2 % at this noise),
    // and its pixel variance.
    let mut variances = Vec::new();
    for (scene, label) in [(&with, "with MIS"), (&without, "without")] {
        let images: Vec<Image> = (20..24).map(|s| render(scene, Mode::FinalGather, 2, s)).collect();
        let (fg, se, v) = replicates(&images);
        eprintln!("final gather {label}: {fg:.5} ± {se:.5} (pixel variance {v:.6})");
        assert!((fg / m1 - 1.0).abs() < 0.02, "final gather {label}: {fg} vs {m1}");
        variances.push(v);
    }
    assert!(
        variances[0] < variances[1],
        "MIS should not add variance to the final gather: {variances:?}"
    );
}
