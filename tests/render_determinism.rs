//! Determinism: every pixel sample and photon path has its own random stream, so any number of
//! worker threads (1 to 64, more threads than tiles or cores included) gives bit-identical
//! images, also at the smallest image size.

use photon_maps::render::{EstimatorKind, Mode, RenderSettings, Renderer};
use photon_maps::trace::Partitioner;
use photon_maps::trace::{CreaseAngle, scenes};

#[test]
fn one_to_sixty_four_threads_give_bit_identical_images() {
    let scene = scenes::build("cornell-box").unwrap();
    for (mode, kind, spp) in [
        (Mode::PhotonMap, EstimatorKind::GeometryCube, 1),
        (Mode::ShadowRays, EstimatorKind::Disc, 2),
        (Mode::FinalGather, EstimatorKind::GeometryBall, 1),
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
                .render(&CreaseAngle::default().partition(scene.clone()).unwrap(), &())
                .unwrap()
                .image
        };
        let a = render(1);
        assert!(a.mean().x > 0.0);
        for threads in [2, 7, 64] {
            assert_eq!(
                bits(&a),
                bits(&render(threads)),
                "{mode} {kind}: images differ between 1 and {threads} threads"
            );
        }
    }
}

fn bits(image: &photon_maps::render::Image) -> Vec<u32> {
    image
        .pixels()
        .iter()
        .flat_map(|p| p.to_array().map(f32::to_bits))
        .collect()
}

#[test]
fn a_one_pixel_image_renders_the_same_on_one_and_sixty_four_threads() {
    let scene = scenes::build("cornell-box").unwrap();
    for mode in [Mode::PhotonMap, Mode::PathTrace] {
        let render = |threads| {
            let s = RenderSettings {
                width: 1,
                height: 1,
                samples_per_pixel: 16,
                photons: 2_000,
                mode,
                threads,
                seed: 5,
                ..RenderSettings::default()
            };
            Renderer::new(EstimatorKind::GeometryCube, s)
                .render(&CreaseAngle::default().partition(scene.clone()).unwrap(), &())
                .unwrap()
                .image
        };
        let one = render(1);
        assert_eq!((one.width(), one.height()), (1, 1));
        // The pixel looks at the back wall's middle: lit, finite.
        let p = one.pixels()[0];
        assert!(p.is_finite() && p.min_element() > 0.0, "{mode}: {p}");
        assert_eq!(bits(&one), bits(&render(64)), "{mode}");
    }
}
