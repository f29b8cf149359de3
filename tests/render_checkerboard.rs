//! A checkerboard base-colour texture (a PNG written here, loaded through the glTF loader) of
//! known mean albedo ρ̄ against closed forms, with error bars from independent seeds:
//!
//! - **photon tracing**: a closed cube, every face textured, a point light of power Φ at its
//!   centre. The checkerboard has an even number of texels per side and each face maps a whole
//!   number of texture periods, so mirroring a face about its centre line swaps the two colours
//!   while leaving the light's irradiance unchanged: the irradiance-weighted mean albedo of the
//!   first bounce is exactly ρ̄. With paths cut after their second surface interaction, the
//!   second-interaction photons carry `ρ̄ Φ` and the first interaction absorbs `(1 − ρ̄) Φ`, per
//!   channel (the colours differ per channel, so Russian roulette *and* the stored power's
//!   colour are tested).
//! - **rendering**: a large textured floor under a directional light of irradiance E₀ seen
//!   straight down, the view spanning exactly one texture period. The path tracer's image mean
//!   is `ρ̄ E₀ / π`; the photon map's (PhotonMap mode, Jensen's disc with k photons) is that times
//!   `k / (k − 1)`, the k-nearest estimate's bias on uniformly scattered photons
//!   (`π r_k² λ` is Gamma(k)-distributed, so `E[k / (π r_k²)] = λ k / (k − 1)`).

#[path = "support/gltf_writer.rs"]
mod gltf_writer;

use gltf_writer::{Quad, png_rgb, srgb_to_linear, temp_dir, write_quads_gltf};
use photon_maps::render::{EstimatorKind, Mode, RenderSettings, Renderer};
use photon_maps::trace::glam::{DVec3, Vec2, Vec3};
use photon_maps::trace::gltf::{GltfOptions, LUMENS_PER_WATT, load_scene_with};
use photon_maps::trace::{Partitioner, PhotonKind, Scene, SingleMap, TraceOptions, trace_photons};

/// The two texel colours (sRGB codes) and the material's base-colour factor.
const WHITE: [u8; 3] = [250, 190, 40];
const BLACK: [u8; 3] = [20, 90, 220];
const FACTOR: [f64; 3] = [0.9, 0.8, 1.0];
/// Texels per side of the checkerboard (even: mirroring swaps the colours).
const TEXELS: u32 = 8;

fn checker_png() -> Vec<u8> {
    let texels: Vec<[u8; 3]> = (0..TEXELS * TEXELS)
        .map(|i| {
            if (i % TEXELS + i / TEXELS).is_multiple_of(2) {
                WHITE
            } else {
                BLACK
            }
        })
        .collect();
    png_rgb(TEXELS, TEXELS, &texels)
}

/// The area-mean albedo, per channel: the factor times the mean of the two linear colours
/// (bilinear filtering of a periodic texture keeps its mean).
fn mean_albedo() -> DVec3 {
    let lin = |c: [u8; 3]| DVec3::new(srgb_to_linear(c[0]), srgb_to_linear(c[1]), srgb_to_linear(c[2]));
    DVec3::from(FACTOR) * 0.5 * (lin(WHITE) + lin(BLACK))
}

/// Lambertian in glTF's terms (metallic 0, specular factor 0): the albedo is the texel times the
/// factor, with no Fresnel layer.
fn material() -> String {
    format!(
        r#"{{"pbrMetallicRoughness":{{"baseColorFactor":[{},{},{},1],"metallicFactor":0,"baseColorTexture":{{"index":0}}}},
            "extensions":{{"KHR_materials_specular":{{"specularFactor":0}}}}}}"#,
        FACTOR[0], FACTOR[1], FACTOR[2]
    )
}

fn options() -> GltfOptions {
    GltfOptions {
        light_scale: LUMENS_PER_WATT,
        default_light: false,
        ..GltfOptions::default()
    }
}

/// Mean and standard error of the mean of replicates, per channel.
fn mean_and_error(samples: &[DVec3]) -> (DVec3, DVec3) {
    let n = samples.len() as f64;
    let mean = samples.iter().copied().sum::<DVec3>() / n;
    let var = samples.iter().map(|&s| (s - mean) * (s - mean)).sum::<DVec3>() / (n - 1.0);
    (mean, (var / n).map(f64::sqrt))
}

/// Asserts `measured` is within 4 standard errors of `truth` per channel, and that the error
/// bar is tight enough (below `max_relative_error` of the truth) for the test to mean something.
fn assert_within_noise(label: &str, samples: &[DVec3], truth: DVec3, max_relative_error: f64) {
    let (mean, error) = mean_and_error(samples);
    let sigmas = (mean - truth).abs() / error;
    println!(
        "{label}: {mean:.5} ± {error:.5} (standard error over {} seeds), closed form {truth:.5}: {sigmas:.2} standard errors apart",
        samples.len()
    );
    assert!(
        (error / truth).max_element() < max_relative_error,
        "{label}: error bar {error} too wide"
    );
    assert!(
        sigmas.max_element() < 4.0,
        "{label}: {mean} vs {truth} ({sigmas} standard errors)"
    );
}

/// A closed cube of side 2 centred at the origin, each face mapping the texture twice along
/// each side, lit by a point light at its centre.
fn checker_cube(dir: &std::path::Path) -> Scene {
    std::fs::write(dir.join("checker.png"), checker_png()).unwrap();
    let tiles = 2.0;
    let uvs = [
        Vec2::ZERO,
        Vec2::new(tiles, 0.0),
        Vec2::new(tiles, tiles),
        Vec2::new(0.0, tiles),
    ];
    let mut quads = Vec::new();
    for axis in 0..3 {
        for sign in [-1.0f32, 1.0] {
            // Corners of the face at coordinate `sign` along `axis`, wound to face inwards.
            let (a, b) = ((axis + 1) % 3, (axis + 2) % 3);
            let corner = |s: f32, t: f32| {
                let mut p = [0.0f32; 3];
                p[axis] = sign;
                p[a] = s;
                p[b] = t;
                Vec3::from(p)
            };
            let mut corners = [
                corner(-1.0, -1.0),
                corner(1.0, -1.0),
                corner(1.0, 1.0),
                corner(-1.0, 1.0),
            ];
            if sign > 0.0 {
                corners.reverse();
            }
            quads.push(Quad { corners, uvs });
        }
    }
    let light = r#"[{"type":"point","intensity":10,"color":[1,1,1]}]"#;
    let node = r#"{"translation":[0,0,0],"extensions":{"KHR_lights_punctual":{"light":0}}}"#.to_string();
    let file = write_quads_gltf(dir, &quads, &material(), "checker.png", &[node], light);
    load_scene_with(&file, &options()).unwrap()
}

#[test]
fn first_bounce_absorbs_one_minus_the_mean_albedo_of_the_checkerboard() {
    let dir = temp_dir("checker-cube");
    let scene = checker_cube(&dir);
    let phi = scene.lights()[0].power().as_dvec3();
    assert!(
        (phi - DVec3::splat(40.0 * std::f64::consts::PI))
            .abs()
            .max_element()
            < 1e-3
    );
    let maps = SingleMap.partition(scene.clone()).unwrap().assignment().clone();
    let rho = mean_albedo();
    let (mut absorbed, mut reflected) = (Vec::new(), Vec::new());
    for seed in 0..8 {
        let options = TraceOptions {
            photons: 40_000,
            seed,
            pass: 0,
            max_bounces: 2,
        };
        let traced = trace_photons(&scene, &maps, &options).unwrap();
        let power = |kind: PhotonKind| {
            traced
                .photons(0)
                .iter()
                .filter(|p| p.kind == kind)
                .map(|p| p.power.as_dvec3())
                .sum::<DVec3>()
        };
        let (direct, indirect) = (power(PhotonKind::Direct), power(PhotonKind::Indirect));
        // Every path's first hit is on the closed cube: the direct photons carry all of Φ.
        assert!(
            ((direct - phi) / phi).abs().max_element() < 1e-4,
            "{direct} vs {phi}"
        );
        absorbed.push(direct - indirect);
        reflected.push(indirect);
    }
    assert_within_noise("first-bounce reflected power (W)", &reflected, rho * phi, 0.01);
    assert_within_noise(
        "first-bounce absorbed power (W)",
        &absorbed,
        (DVec3::ONE - rho) * phi,
        0.01,
    );
    std::fs::remove_dir_all(&dir).ok();
}

/// A 4 m floor under a straight-down directional light of irradiance `E0`, the camera 1 m
/// above it looking down with a 1 m wide view, texture coordinates = world x, z + 2 (so the
/// view spans exactly one texture period).
fn checker_floor(dir: &std::path::Path, e0: f32) -> Scene {
    std::fs::write(dir.join("checker.png"), checker_png()).unwrap();
    let corners = [
        Vec3::new(-2.0, 0.0, -2.0),
        Vec3::new(-2.0, 0.0, 2.0),
        Vec3::new(2.0, 0.0, 2.0),
        Vec3::new(2.0, 0.0, -2.0),
    ];
    let uvs = corners.map(|c| Vec2::new(c.x + 2.0, c.z + 2.0));
    // Both the light and the camera look down their node's −z: rotate −90° about x.
    let down = "\"rotation\":[-0.70710677,0,0,0.70710677]";
    let yfov = 2.0 * 0.5f32.atan();
    let nodes = [
        format!(r#"{{{down},"extensions":{{"KHR_lights_punctual":{{"light":0}}}}}}"#),
        format!(r#"{{{down},"translation":[0,1,0],"camera":0}}"#),
    ];
    let light = format!(r#"[{{"type":"directional","intensity":{e0},"color":[1,1,1]}}]"#);
    let file = write_quads_gltf(
        dir,
        &[Quad { corners, uvs }],
        &material(),
        "checker.png",
        &nodes,
        &light,
    );
    // The writer has no camera array: add one.
    let json = std::fs::read_to_string(&file).unwrap().replacen(
        "\"materials\"",
        &format!(r#""cameras":[{{"type":"perspective","perspective":{{"yfov":{yfov},"aspectRatio":1,"znear":0.01}}}}],"materials""#),
        1,
    );
    std::fs::write(&file, json).unwrap();
    load_scene_with(&file, &options()).unwrap()
}

#[test]
fn rendered_mean_is_the_mean_albedo_over_pi_times_the_irradiance() {
    let dir = temp_dir("checker-floor");
    let e0 = 3.0;
    let scene = checker_floor(&dir, e0);
    let rho = mean_albedo();
    let k = 100;
    let (mut traced, mut mapped) = (Vec::new(), Vec::new());
    for seed in 0..6 {
        let settings = RenderSettings {
            width: 48,
            height: 48,
            photons: 200_000,
            k,
            seed,
            mode: Mode::PhotonMap,
            ..RenderSettings::default()
        };
        let render = |settings: RenderSettings| {
            Renderer::new(EstimatorKind::Disc, settings)
                .render(&SingleMap.partition(scene.clone()).unwrap(), &())
                .unwrap()
                .image
                .mean()
                .as_dvec3()
        };
        mapped.push(render(settings));
        traced.push(render(RenderSettings {
            mode: Mode::PathTrace,
            samples_per_pixel: 2,
            ..settings
        }));
    }
    let truth = rho * e0 as f64 / std::f64::consts::PI;
    assert_within_noise("path-traced image mean (W/(m² sr))", &traced, truth, 0.01);
    let bias = k as f64 / (k as f64 - 1.0);
    assert_within_noise(
        "photon-mapped image mean (W/(m² sr))",
        &mapped,
        truth * bias,
        0.01,
    );
    std::fs::remove_dir_all(&dir).ok();
}
