//! glTF emission against closed forms: an emissive-textured quad's power is the texture's
//! integral times strength and photon tracing delivers it to a closed black box; light units
//! keep an emitter and a lamp at their authored ratio; `doubleSided` doubles an emitter and
//! `doubleSided: false` culls its back for camera rays; a broken emissive texture in use is a
//! typed error. Every file is generated here (PNG by the png crate, in data URIs).

use std::f64::consts::PI;
use std::path::{Path, PathBuf};

use photon_maps::trace::glam::{DVec3, Vec3};
use photon_maps::trace::gltf::{GltfOptions, LightUnits, load_scene_with, read_content};
use photon_maps::trace::{Partitioner, Ray, RayKind, Scene, SingleMap, TraceOptions, trace_photons};

#[path = "support/gltf_data_uri.rs"]
mod gltf_data_uri;
#[path = "support/unit_cube_room.rs"]
mod unit_cube_room;
use gltf_data_uri::{emitter_quad, gltf, png, png_image, room};

/// A perfect absorber: black, metallic 0 and `KHR_materials_specular`'s factor 0 (without it
/// Appendix B keeps a dielectric's 4 % Fresnel layer, and the walls would reflect).
const BLACK: &str = r#"{"pbrMetallicRoughness":{"baseColorFactor":[0,0,0,1],"metallicFactor":0},"extensions":{"KHR_materials_specular":{"specularFactor":0}}}"#;

fn emissive(factor: [f32; 3], strength: f32, texture: bool, double_sided: bool) -> String {
    let texture = if texture {
        r#","emissiveTexture":{"index":0}"#
    } else {
        ""
    };
    format!(
        r#"{{"pbrMetallicRoughness":{{"baseColorFactor":[0,0,0,1],"metallicFactor":0}},"emissiveFactor":{factor:?}{texture},"doubleSided":{double_sided},"extensions":{{"KHR_materials_emissive_strength":{{"emissiveStrength":{strength}}},"KHR_materials_specular":{{"specularFactor":0}}}}}}"#
    )
}

/// The IEC 61966-2-1 decoding of an 8-bit code, written out here.
fn linear(code: u8) -> f64 {
    let c = code as f64 / 255.0;
    if c <= 0.04045 {
        c / 12.92
    } else {
        ((c + 0.055) / 1.055).powf(2.4)
    }
}

fn write(name: &str, json: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("pm-gltf-emission-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let path = dir.join(name);
    std::fs::write(&path, json).unwrap();
    path
}

fn load(path: &Path, light_units: LightUnits) -> Scene {
    load_scene_with(
        path,
        &GltfOptions {
            light_units,
            ..GltfOptions::default()
        },
    )
    .unwrap()
}

/// Traces `n` photons (black walls: each stored once, at its first hit) and returns each
/// stored photon's position and power.
fn photons(scene: &Scene, n: u32, seed: u64) -> Vec<(Vec3, Vec3)> {
    let maps = SingleMap.partition(scene.clone()).unwrap().assignment().clone();
    let traced = trace_photons(
        scene,
        &maps,
        &TraceOptions {
            photons: n,
            seed,
            ..TraceOptions::default()
        },
    )
    .unwrap();
    traced.photons(0).iter().map(|p| (p.position, p.power)).collect()
}

/// 4 × 2 texels, every channel different.
const TEXELS: [u8; 24] = [
    255, 0, 0, 0, 255, 0, 0, 0, 255, 255, 255, 255, //
    10, 60, 120, 200, 100, 30, 90, 90, 90, 0, 0, 0,
];

fn texel_mean() -> DVec3 {
    let sum = TEXELS
        .chunks_exact(3)
        .map(|c| DVec3::new(linear(c[0]), linear(c[1]), linear(c[2])))
        .sum::<DVec3>();
    sum / 8.0
}

#[test]
fn emissive_textured_quad_power_is_the_texture_integral_times_strength() {
    // A 0.5 m quad in a black unit room, emissiveFactor × strength × the 4 × 2 texture mapped
    // once: Φ = π A · strength · factor ⊙ mean(texels), nearest or bilinear-repeat alike (a
    // periodic bilinear image keeps its texels' mean).
    let factor = [1.0f32, 0.8, 0.6];
    let strength = 5.0f32;
    let truth = Vec3::from(factor).as_dvec3() * texel_mean() * (PI * 0.25 * strength as f64);
    for (name, textures, tolerance) in [
        ("nearest", r#"[{"source":0,"sampler":0}]"#, 1e-5),
        ("bilinear", r#"[{"source":0}]"#, 2e-3),
    ] {
        let json = gltf(
            &[room([0.0; 3], 0), emitter_quad([0.5, 0.5, 0.5], 0.5, 1)],
            &[BLACK.into(), emissive(factor, strength, true, false)],
            textures,
            &[png_image(&png(4, 2, &TEXELS))],
            &[],
        );
        let json = json.replace(
            r#""scene":0}"#,
            r#""scene":0,"samplers":[{"magFilter":9728,"minFilter":9728}]}"#,
        );
        let scene = load(&write(&format!("{name}.gltf"), &json), LightUnits::Mixed);
        assert_eq!(scene.lights().len(), 1);
        let power = scene.lights()[0].power().as_dvec3();
        let error = ((power - truth) / truth).abs().max_element();
        println!("{name}: light power {power}, closed form {truth}, relative error {error:.2e}");
        assert!(error < tolerance, "{name}: {power} vs {truth}");
        // Photon tracing: every path ends in the black room; the stored power is the light's
        // power up to photon noise (weights follow the texture at each emission point).
        let n = 100_000u32;
        let stored = photons(&scene, n, 1);
        assert_eq!(stored.len(), n as usize, "every path is absorbed once");
        let (mut sum, mut sum2) = (DVec3::ZERO, DVec3::ZERO);
        for (_, p) in &stored {
            let p = p.as_dvec3();
            sum += p;
            sum2 += p * p;
        }
        let mean = sum / n as f64;
        // Standard error of the total: √N · the per-photon standard deviation.
        let se = ((sum2 / n as f64 - mean * mean).max(DVec3::ZERO) * n as f64).map(f64::sqrt);
        let sigmas = ((sum - truth) / se).abs();
        println!("{name}: stored {sum} ± {se} (1 SE), {sigmas} standard errors from the closed form");
        assert!(sigmas.max_element() < 4.0, "{name}: {sum} vs {truth} ± {se}");
    }
}

#[test]
fn light_units_keep_the_authored_emitter_to_lamp_ratio() {
    // Room A holds a 0.5 m emitter of luminance 100 cd/m² (π L A = 78.5 lm), room B, 3 m
    // away, a 10 cd point light (4π I = 125.7 lm). Photons land in each room in proportion to
    // its light's power.
    let json = gltf(
        &[
            room([0.0; 3], 0),
            room([3.0, 0.0, 0.0], 0),
            emitter_quad([0.5, 0.5, 0.5], 0.5, 1),
        ],
        &[BLACK.into(), emissive([1.0; 3], 100.0, false, false)],
        "[]",
        &[],
        &[([3.5, 0.5, 0.5], 10.0)],
    );
    let path = write("units.gltf", &json);
    let emitter = PI * 100.0 * 0.25;
    let lamp = 4.0 * PI * 10.0;
    for (units, e, l) in [
        (LightUnits::Mixed, emitter, lamp / 683.0),
        (LightUnits::Photometric, emitter / 683.0, lamp / 683.0),
        (LightUnits::Viewer, emitter, lamp),
    ] {
        let scene = load(&path, units);
        let powers: Vec<f64> = scene.lights().iter().map(|l| l.power().x as f64).collect();
        assert_eq!(powers.len(), 2);
        let (got_e, got_l) = (powers[0], powers[1]);
        assert!(
            ((got_e - e) / e).abs() < 1e-5 && ((got_l - l) / l).abs() < 1e-5,
            "{units:?}: {powers:?}"
        );
        let n = 100_000u32;
        let stored = photons(&scene, n, 3);
        let in_a = stored.iter().filter(|(p, _)| p.x < 2.0).count() as f64 / n as f64;
        let expected = e / (e + l);
        let se = (expected * (1.0 - expected) / n as f64)
            .sqrt()
            .max(0.5 / n as f64);
        println!(
            "{units:?}: emitter {got_e:.4} W, lamp {got_l:.4} W, ratio {:.4}; photons in the emitter's room {in_a:.4}, expected {expected:.4} ({:.2} SE)",
            got_e / got_l,
            (in_a - expected).abs() / se
        );
        assert!(
            (in_a - expected).abs() <= 4.0 * se,
            "{units:?}: {in_a} vs {expected} ± {se}"
        );
        if units != LightUnits::Mixed {
            assert!(((got_e / got_l) / (0.25 * 100.0 / (4.0 * 10.0)) - 1.0).abs() < 1e-5);
        }
    }
}

#[test]
fn double_sided_emitters_emit_from_both_sides_and_single_sided_backs_are_culled() {
    let radiance = 2.0f32;
    for double_sided in [false, true] {
        let json = gltf(
            &[room([0.0; 3], 0), emitter_quad([0.5, 0.5, 0.5], 0.5, 1)],
            &[BLACK.into(), emissive([1.0; 3], radiance, false, double_sided)],
            "[]",
            &[],
            &[],
        );
        let scene = load(
            &write(&format!("sided-{double_sided}.gltf"), &json),
            LightUnits::Mixed,
        );
        let sides = if double_sided { 2.0 } else { 1.0 };
        let truth = PI * radiance as f64 * 0.25 * sides;
        let power = scene.lights()[0].power().x as f64;
        assert!(
            ((power - truth) / truth).abs() < 1e-5,
            "double-sided {double_sided}: {power} vs {truth}"
        );
        // Photons below the quad: none from a single-sided one, half from a double-sided one.
        let n = 20_000u32;
        let below = photons(&scene, n, 3).iter().filter(|(p, _)| p.y < 0.5).count() as f64 / n as f64;
        let expected = if double_sided { 0.5 } else { 0.0 };
        assert!(
            (below - expected).abs() <= 4.0 * (0.25 / n as f64).sqrt(),
            "{below} vs {expected}"
        );
        // A camera ray from below meets the quad's back: culled when single-sided (it goes on
        // to the ceiling), seen and glowing when double-sided.
        let up = Ray {
            origin: Vec3::new(0.45, 0.1, 0.55),
            direction: Vec3::Y,
        };
        let hit = scene.intersect(&up, f32::INFINITY, RayKind::Camera).unwrap();
        if double_sided {
            assert!((hit.t - 0.4).abs() < 1e-4 && !hit.front_face);
            assert_eq!(scene.emission(&hit), Vec3::splat(radiance));
        } else {
            assert!(
                (hit.t - 0.9).abs() < 1e-4,
                "culled: reaches the ceiling, t {}",
                hit.t
            );
            let other = scene.intersect(&up, f32::INFINITY, RayKind::Other).unwrap();
            assert!((other.t - 0.4).abs() < 1e-4 && scene.emission(&other) == Vec3::ZERO);
        }
    }
}

#[test]
fn broken_emissive_texture_in_use_is_a_typed_error_and_missing_coordinates_warn() {
    let whole = png(4, 4, &[90; 48]);
    let truncated = &whole[..whole.len() / 2];
    let quad = emitter_quad([0.5, 0.5, 0.5], 0.5, 1);
    let json = gltf(
        &[room([0.0; 3], 0), quad],
        &[BLACK.into(), emissive([1.0; 3], 1.0, true, false)],
        r#"[{"source":0}]"#,
        &[png_image(truncated)],
        &[],
    );
    let err = load_scene_with(&write("broken.gltf", &json), &GltfOptions::default()).unwrap_err();
    assert_eq!(err.kind(), "image", "{err}");
    // A black emissive factor makes the (broken) texture irrelevant: it is not decoded.
    let json = gltf(
        &[room([0.0; 3], 0), emitter_quad([0.5, 0.5, 0.5], 0.5, 1)],
        &[BLACK.into(), emissive([0.0; 3], 1.0, true, false)],
        r#"[{"source":0}]"#,
        &[png_image(truncated)],
        &[([0.5, 0.8, 0.5], 1.0)],
    );
    let path = write("unlit-texture.gltf", &json);
    let content = read_content(&path, &GltfOptions::default()).unwrap();
    assert!(
        content
            .warnings
            .iter()
            .any(|w| w.contains("black emission factor")),
        "{:?}",
        content.warnings
    );
    load_scene_with(&path, &GltfOptions::default()).unwrap();
    // Without TEXCOORD_0 the texture is ignored with a warning and the factor emits alone.
    let mut bare = emitter_quad([0.5, 0.5, 0.5], 0.5, 1);
    bare.uvs = None;
    let json = gltf(
        &[room([0.0; 3], 0), bare],
        &[BLACK.into(), emissive([1.0; 3], 1.0, true, false)],
        r#"[{"source":0}]"#,
        &[png_image(&whole)],
        &[],
    );
    let path = write("no-uvs.gltf", &json);
    let content = read_content(&path, &GltfOptions::default()).unwrap();
    assert!(
        content
            .warnings
            .iter()
            .any(|w| w.contains("emissive texture ignored")),
        "{:?}",
        content.warnings
    );
    let power = load(&path, LightUnits::Mixed).lights()[0].power().x as f64;
    assert!((power - PI * 0.25).abs() < 1e-5);
}
