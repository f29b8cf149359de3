//! Emission seen through the delta chain: an emitting mirror in front of the camera shows its
//! emission in every mode, as the path tracer always showed it (the photon-map, shadow-ray,
//! final-gather and SPPM modes used to drop it and read only the diffuse hit behind).

use photon_maps::render::glam::Vec3;
use photon_maps::render::progressive::{SppmRenderer, SppmSettings};
use photon_maps::render::{EstimatorKind, Image, Mode, RenderSettings, Renderer};
use photon_maps::trace::{Camera, CreaseAngle, Partitioner, PointLight, RayKind, Scene, Surface};

const EMISSION: Vec3 = Vec3::new(3.0, 2.0, 1.0);

/// A closed diffuse sphere lit by a point light, and a small mirror sphere (reflectance 0.5)
/// that emits `emission` right in front of the camera.
fn scene(emission: Vec3) -> Scene {
    let mirror = Surface {
        emission,
        ..Surface::mirror(Vec3::splat(0.5))
    };
    Scene::builder()
        .sphere(Vec3::ZERO, 2.0, Surface::diffuse(Vec3::splat(0.5)))
        .sphere(Vec3::new(0.0, 0.0, -0.6), 0.3, mirror)
        .light(PointLight::new(Vec3::new(0.0, 1.0, 0.0), Vec3::splat(30.0)))
        .camera(Camera::new(Vec3::new(0.0, 0.0, 1.0), Vec3::NEG_Z, Vec3::Y, 0.8))
        .build()
        .unwrap()
}

fn render(scene: &Scene, mode: Mode) -> Image {
    let s = RenderSettings {
        width: 16,
        height: 16,
        photons: 5_000,
        mode,
        seed: 9,
        threads: 2,
        ..RenderSettings::default()
    };
    Renderer::new(EstimatorKind::Disc, s)
        .render(&CreaseAngle::default().partition(scene.clone()).unwrap(), &())
        .unwrap()
        .image
}

/// Pixels whose centre ray meets the mirror first (and leaves through it).
fn mirror_pixels(scene: &Scene) -> Vec<usize> {
    let mut out = Vec::new();
    for y in 0..16u32 {
        for x in 0..16u32 {
            let ray = scene
                .camera()
                .ray((x as f32 + 0.5) / 16.0, (y as f32 + 0.5) / 16.0, 1.0);
            let hit = scene.intersect(&ray, f32::INFINITY, RayKind::Camera).unwrap();
            // Well inside the mirror's silhouette: the jittered samples hit it too.
            if hit.position.z > -0.35 && (hit.position - Vec3::new(0.0, 0.0, -0.6)).length() < 0.31 {
                out.push((y * 16 + x) as usize);
            }
        }
    }
    out
}

/// The mirror's emission, seen straight on, plus at most 2 % more: the light it sheds on the
/// big sphere, which the mirror then reflects (path-traced and gathered rays that meet the
/// mirror count it; photons do not, as the mirror is not a light).
fn assert_emission_added(added: Vec3, what: &str) {
    assert!(
        added.cmple(EMISSION * 1.02).all() && added.cmpge(EMISSION - 1e-3).all(),
        "{what} adds {added}, expected {EMISSION} (up to 2 % more)"
    );
}

#[test]
fn every_mode_shows_an_emitting_mirror_s_emission() {
    let (lit, dark) = (scene(EMISSION), scene(Vec3::ZERO));
    let pixels = mirror_pixels(&lit);
    assert!(pixels.len() >= 8, "{} mirror pixels", pixels.len());
    for mode in Mode::ALL {
        // The same seed draws the same samples: the emission is the only difference.
        let (a, b) = (render(&lit, mode), render(&dark, mode));
        for &i in &pixels {
            let added = a.pixels()[i] - b.pixels()[i];
            assert_emission_added(added, &format!("{mode}: pixel {i}"));
        }
    }
    let sppm = |scene: &Scene| {
        let s = RenderSettings {
            width: 16,
            height: 16,
            photons: 5_000,
            seed: 9,
            threads: 2,
            ..RenderSettings::default()
        };
        SppmRenderer::new(SppmSettings::new(s, 2))
            .render(scene, &())
            .unwrap()
            .image
    };
    let (a, b) = (sppm(&lit), sppm(&dark));
    for &i in &pixels {
        assert_emission_added(a.pixels()[i] - b.pixels()[i], &format!("sppm: pixel {i}"));
    }
}
