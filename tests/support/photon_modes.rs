//! Every photon mode the glossy tests run, each as "render this seed": one-shot photon-map,
//! shadow-rays and final gather, progressive (photon-map, shadow-rays, final gather) and SPPM,
//! on the estimators they read through. Include it with
//! `#[path = "support/photon_modes.rs"] mod photon_modes;` (from `tests/`).
#![allow(dead_code)]

use photon_maps::render::progressive::{
    ProgressiveRenderer, ProgressiveSettings, SppmRenderer, SppmSettings,
};
use photon_maps::render::{EstimatorKind, FinalGatherOptions, Image, Mode, RenderSettings, Renderer};
use photon_maps::trace::{Partitioned, Scene};

/// The glossy tests' settings: a `width × height` image of `samples_per_pixel`, `photons`
/// photon paths, 2 threads and 4 gather rays per final-gather point.
pub fn small_settings(
    (width, height): (u32, u32),
    photons: u32,
    samples_per_pixel: u32,
    mode: Mode,
    seed: u64,
) -> RenderSettings {
    RenderSettings {
        width,
        height,
        photons,
        samples_per_pixel,
        mode,
        seed,
        threads: 2,
        final_gather: FinalGatherOptions {
            gather_rays: 4,
            ..FinalGatherOptions::default()
        },
        ..RenderSettings::default()
    }
}

/// An image's bits, to compare two images bit for bit.
pub fn image_bits(image: &Image) -> Vec<u32> {
    image
        .pixels()
        .iter()
        .flat_map(|p| p.to_array().map(f32::to_bits))
        .collect()
}

/// A mode's name and how it renders the scene for a seed.
pub type Case<'a> = (&'static str, Box<dyn Fn(u64) -> Image + 'a>);

/// The settings of a mode for a seed, as the test wants them.
pub type SettingsFor<'a> = &'a dyn Fn(Mode, u64) -> RenderSettings;

/// Passes of the progressive modes and SPPM.
pub const PROGRESSIVE_PASSES: u64 = 4;
pub const SPPM_PASSES: u64 = 8;

/// Which modes [`every_mode`] lists: SPPM's one global map is not leak-free, so leak tests
/// leave it out.
#[derive(Clone, Copy, PartialEq, Eq)]
pub enum Sppm {
    Included,
    Excluded,
}

fn one_shot(partitioned: &Partitioned, kind: EstimatorKind, settings: RenderSettings) -> Image {
    Renderer::new(kind, settings)
        .render(partitioned, &())
        .unwrap()
        .image
}

/// The progressive mode's accumulated image after `passes` passes.
pub fn progressive(
    partitioned: &Partitioned,
    kind: EstimatorKind,
    settings: RenderSettings,
    passes: u64,
) -> Image {
    ProgressiveRenderer::new(kind, ProgressiveSettings::new(settings, passes))
        .render(partitioned, &())
        .unwrap()
        .accumulation
        .mean()
}

fn sppm(scene: &Scene, settings: RenderSettings) -> Image {
    SppmRenderer::new(SppmSettings::new(settings, SPPM_PASSES))
        .render(scene, &())
        .unwrap()
        .image
}

/// Every photon mode on `partitioned` (SPPM on `partitioned`'s scene when included).
pub fn every_mode<'a>(
    partitioned: &'a Partitioned,
    settings: SettingsFor<'a>,
    with_sppm: Sppm,
) -> Vec<Case<'a>> {
    use EstimatorKind::{Disc, GeometryBall, GeometryCube};
    let one = |name, kind, mode| -> Case<'a> {
        (
            name,
            Box::new(move |s| one_shot(partitioned, kind, settings(mode, s))),
        )
    };
    let passes = |name, kind, mode| -> Case<'a> {
        (
            name,
            Box::new(move |s| progressive(partitioned, kind, settings(mode, s), PROGRESSIVE_PASSES)),
        )
    };
    let mut cases = vec![
        one("photon-map disc", Disc, Mode::PhotonMap),
        one("photon-map cube", GeometryCube, Mode::PhotonMap),
        one("shadow-rays cube", GeometryCube, Mode::ShadowRays),
        one("shadow-rays ball", GeometryBall, Mode::ShadowRays),
        one("final-gather cube", GeometryCube, Mode::FinalGather),
        one("final-gather disc", Disc, Mode::FinalGather),
        passes("progressive cube", GeometryCube, Mode::PhotonMap),
        passes("progressive shadow-rays disc", Disc, Mode::ShadowRays),
        passes("progressive final-gather cube", GeometryCube, Mode::FinalGather),
    ];
    if with_sppm == Sppm::Included {
        let scene = partitioned.scene();
        cases.push((
            "sppm",
            Box::new(move |s| sppm(scene, settings(Mode::PhotonMap, s))),
        ));
    }
    cases
}
