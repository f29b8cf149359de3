//! A renderer author's own radiance source, from outside the crates with public items only:
//! the render core follows camera rays through mirrors to the first diffuse hit, and the
//! author's source reads the radiance there.

use photon_maps::render::core::{PathVertex, RadianceSource, follow_delta_bounces};
use photon_maps::render::glam::Vec3;
use photon_maps::render::source::{DirectLight, PhotonMapSource};
use photon_maps::render::{EstimatorKind, EstimatorScratch, Mode, RenderSettings, Renderer};
use photon_maps::trace::PhotonMaps;
use photon_maps::trace::{
    Camera, CreaseAngle, Partitioner, PointLight, RayKind, Rng, Scene, Surface, TraceOptions, scenes,
    trace_photons,
};

/// Every diffuse surface reflects the same radiance: an "ambient" source.
struct Constant<'a> {
    scene: &'a Scene,
    radiance: Vec3,
}

impl RadianceSource for Constant<'_> {
    fn scene(&self) -> &Scene {
        self.scene
    }

    fn reflected(&self, _: &PathVertex, _: &mut Rng, _: &mut EstimatorScratch) -> Vec3 {
        self.radiance
    }
}

fn settings() -> RenderSettings {
    RenderSettings {
        width: 24,
        height: 24,
        samples_per_pixel: 2,
        photons: 10_000,
        seed: 3,
        threads: 2,
        ..RenderSettings::default()
    }
}

#[test]
fn a_constant_source_is_seen_directly_and_through_the_mirror() {
    // The Cornell box: its light quad emits, its sphere is a mirror of reflectance below one.
    let scene = scenes::build("cornell-box").unwrap();
    let constant = Vec3::new(0.25, 0.5, 0.75);
    let source = Constant {
        scene: &scene,
        radiance: constant,
    };
    let renderer = Renderer::new(EstimatorKind::Disc, settings());
    let image = renderer.render_source(&source, &()).unwrap();
    // Each pixel's samples, traced again here: a diffuse hit through mirror bounces carries the
    // constant times the bounces' reflectance, plus the emission of the surface hit.
    let (w, h) = (24u32, 24u32);
    let mut direct = 0;
    let mut mirrored = 0;
    for y in 0..h {
        for x in 0..w {
            let pixel = image.pixels()[(y * w + x) as usize];
            // The pixel's centre ray: classify what it sees.
            let ray = scene
                .camera()
                .ray((x as f32 + 0.5) / w as f32, (y as f32 + 0.5) / h as f32, 1.0);
            let mut rng = Rng::new(0, 0);
            let Some(vertex) = follow_delta_bounces(&scene, ray, RayKind::Camera, &mut rng, |_, _, _, _| {})
            else {
                continue;
            };
            let expected = vertex.throughput * (scene.emission(&vertex.hit) + constant);
            // Only pixels whose every sample sees the same kind of surface are exact.
            if (pixel - expected).abs().max_element() < 1e-5 {
                if vertex.bounces == 0 {
                    direct += 1;
                } else {
                    mirrored += 1;
                }
            }
        }
    }
    assert!(direct > 300, "{direct} pixels see the constant directly");
    assert!(mirrored > 5, "{mirrored} pixels see it through the mirror sphere");
}

/// The library's own photon-map source, rendered through `render_source`, is the photon-map
/// mode's image bit for bit: the mode is nothing but that choice of source.
#[test]
fn the_library_source_rendered_by_hand_is_the_mode_bit_for_bit() {
    let scene = Scene::builder()
        .sphere(Vec3::ZERO, 1.0, Surface::diffuse(Vec3::splat(0.5)))
        .light(PointLight::new(Vec3::ZERO, Vec3::splat(40.0)))
        .camera(Camera::new(Vec3::new(0.0, 0.0, 0.5), Vec3::NEG_Z, Vec3::Y, 1.2))
        .build()
        .unwrap();
    let s = RenderSettings {
        mode: Mode::PhotonMap,
        ..settings()
    };
    let renderer = Renderer::new(EstimatorKind::GeometryCube, s);
    let partitioned = CreaseAngle::default().partition(scene.clone()).unwrap();
    let by_mode = renderer.render(&partitioned, &()).unwrap().image;

    let assignment = partitioned.assignment();
    let traced = trace_photons(
        &scene,
        assignment,
        &TraceOptions {
            photons: s.photons,
            seed: s.seed,
            ..TraceOptions::default()
        },
    )
    .unwrap();
    let maps = PhotonMaps::build(&scene, assignment, traced).unwrap();
    let options = s.estimator_options(&scene.bounds());
    let source = PhotonMapSource {
        scene: &scene,
        maps: &maps,
        estimator: &EstimatorKind::GeometryCube,
        options: &options,
        pixel_angle: scene.camera().pixel_angle(s.height),
        direct: DirectLight::Photons,
    };
    let by_hand = renderer.render_source(&source, &()).unwrap();
    assert!(by_mode.mean().x > 0.1);
    assert_eq!(by_mode.pixels(), by_hand.pixels());
}
