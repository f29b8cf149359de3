//! Determinism: every pixel sample and photon path has its own random stream, so one and two
//! worker threads give bit-identical images.

use photon_maps::render::{EstimatorKind, Mode, RenderSettings, Renderer};
use photon_maps::trace::{CreaseAngle, scenes};

#[test]
fn one_and_two_threads_give_bit_identical_images() {
    let scene = scenes::build("cornell-box").unwrap();
    for (mode, kind, spp) in [
        (Mode::Visualize, EstimatorKind::GeometryCube, 1),
        (Mode::ShadowRays, EstimatorKind::Disc, 2),
    ] {
        let render = |threads| {
            let s = RenderSettings {
                width: 40,
                height: 40,
                samples_per_pixel: spp,
                photons: 8_000,
                mode,
                threads,
                seed: 11,
                tile_size: 7,
                ..RenderSettings::default()
            };
            Renderer::new(kind, s)
                .render(&scene, &CreaseAngle::default(), &())
                .unwrap()
                .image
        };
        let (a, b) = (render(1), render(2));
        assert!(a.mean().x > 0.0);
        let bits = |im: &photon_maps::render::Image| {
            im.pixels()
                .iter()
                .flat_map(|p| p.to_array().map(f32::to_bits))
                .collect::<Vec<u32>>()
        };
        assert_eq!(
            bits(&a),
            bits(&b),
            "{mode} {kind}: images differ between 1 and 2 threads"
        );
    }
}
