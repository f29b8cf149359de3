//! Golden images: a hash of the bits of small renders (48×48, seed 7, 20k photons) of the
//! built-in scenes in every mode, estimator and partition. A refactor must keep every hash;
//! a change of behaviour changes some, in a commit of its own that says why (with numbers
//! against the path tracer) and updates `tests/data/golden_hashes.txt`.
//!
//! On a mismatch the test prints every line as this build renders it; with
//! `PM_GOLDEN_OUT=FILE` it also writes them to FILE (never to the tracked file itself).

use photon_maps::render::progressive::{
    ProgressiveRenderer, ProgressiveSettings, SppmRenderer, SppmSettings,
};
use photon_maps::render::{EstimatorKind, FinalGatherOptions, Image, Mode, RenderSettings, Renderer};
use photon_maps::trace::{Contact, CreaseAngle, Partitioned, Partitioner, Scene, SingleMap, scenes};

const GOLDEN: &str = include_str!("data/golden_hashes.txt");

/// FNV-1a over the bits of every pixel channel, with the size first.
fn hash(image: &Image) -> u64 {
    let mut h = 0xcbf2_9ce4_8422_2325u64;
    let mut eat = |word: u32| {
        for byte in word.to_le_bytes() {
            h ^= u64::from(byte);
            h = h.wrapping_mul(0x0000_0100_0000_01b3);
        }
    };
    eat(image.width());
    eat(image.height());
    for p in image.pixels() {
        for c in p.to_array() {
            eat(c.to_bits());
        }
    }
    h
}

fn settings(mode: Mode) -> RenderSettings {
    RenderSettings {
        width: 48,
        height: 48,
        photons: 20_000,
        mode,
        seed: 7,
        threads: 2,
        tile_size: 16,
        final_gather: FinalGatherOptions {
            gather_rays: 9,
            ..FinalGatherOptions::default()
        },
        ..RenderSettings::default()
    }
}

/// Every variant's name and image for one scene, partitioned each way (`contact` holds the
/// scene split for contact maps).
fn render_all(
    scene: &Scene,
    single: &Partitioned,
    crease: &Partitioned,
    contact: &Partitioned,
) -> Vec<(String, Image)> {
    let mut out = Vec::new();
    let partitions = [("single", single), ("crease", crease), ("contact", contact)];
    for (pname, partitioned) in partitions {
        for kind in EstimatorKind::ALL {
            let image = Renderer::new(kind, settings(Mode::PhotonMap))
                .render(partitioned, &())
                .unwrap()
                .image;
            out.push((format!("photon-map {kind} {pname}"), image));
        }
        for mode in [Mode::ShadowRays, Mode::FinalGather] {
            let image = Renderer::new(EstimatorKind::GeometryCube, settings(mode))
                .render(partitioned, &())
                .unwrap()
                .image;
            out.push((format!("{mode} cube {pname}"), image));
        }
    }
    let image = Renderer::new(EstimatorKind::Disc, settings(Mode::PathTrace))
        .render(crease, &())
        .unwrap()
        .image;
    out.push(("path-trace".to_owned(), image));
    let image = Renderer::new(EstimatorKind::Disc, settings(Mode::PathTrace))
        .render(contact, &())
        .unwrap()
        .image;
    out.push(("path-trace contact".to_owned(), image));
    for (mode, kind, pname, partitioned) in [
        (Mode::PhotonMap, EstimatorKind::Disc, "crease", crease),
        (Mode::PhotonMap, EstimatorKind::GeometryCube, "contact", contact),
        (Mode::PhotonMap, EstimatorKind::GeometryBall, "single", single),
        (Mode::ShadowRays, EstimatorKind::GeometryCube, "crease", crease),
        (Mode::FinalGather, EstimatorKind::GeometryCube, "crease", crease),
        (Mode::FinalGather, EstimatorKind::Disc, "contact", contact),
    ] {
        let out_image = ProgressiveRenderer::new(kind, ProgressiveSettings::new(settings(mode), 3))
            .render(partitioned, &())
            .unwrap()
            .accumulation
            .mean();
        out.push((format!("progressive {mode} {kind} {pname}"), out_image));
    }
    let image = SppmRenderer::new(SppmSettings::new(settings(Mode::PhotonMap), 3))
        .render(scene, &())
        .unwrap()
        .image;
    out.push(("sppm".to_owned(), image));
    out
}

#[test]
fn every_mode_estimator_and_partition_renders_the_golden_bits() {
    let mut names: Vec<String> = scenes::NAMES.iter().map(|s| s.to_string()).collect();
    names.push("solid-rooms-pierce".to_owned());
    names.retain(|n| scenes::build(n).is_ok());
    assert!(names.len() >= 6, "the solid room scene is missing: {names:?}");
    let mut lines = Vec::new();
    for name in &names {
        let scene = scenes::build(name).unwrap();
        let single = SingleMap.partition(scene.clone()).unwrap();
        let crease = CreaseAngle::default().partition(scene.clone()).unwrap();
        let contact = Contact::default().partition(scene.clone()).unwrap();
        for (variant, image) in render_all(&scene, &single, &crease, &contact) {
            assert!(image.pixels().iter().all(|p| p.is_finite()), "{name} {variant}");
            lines.push(format!("{name} | {variant} | {:016x}", hash(&image)));
        }
    }
    let actual = lines.join("\n") + "\n";
    if let Ok(path) = std::env::var("PM_GOLDEN_OUT") {
        std::fs::write(&path, &actual).unwrap();
    }
    let expected: Vec<&str> = GOLDEN.lines().filter(|l| !l.starts_with('#')).collect();
    let differing: Vec<String> = lines
        .iter()
        .zip(&expected)
        .filter(|(a, e)| a != e)
        .map(|(a, e)| format!("  now  {a}\n  was  {e}"))
        .collect();
    assert!(
        differing.is_empty() && lines.len() == expected.len(),
        "{} of {} golden images differ ({} expected lines):\n{}\nall lines now:\n{actual}",
        differing.len(),
        lines.len(),
        expected.len(),
        differing.join("\n")
    );
}
