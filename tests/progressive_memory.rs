//! A progressive render holds one pass's photons plus the running sum, whatever the pass
//! count: the peak heap of 20 passes is that of 2 passes (to within a fraction of one pass's
//! photons, which vary from pass to pass), where keeping every pass's photons would add 18
//! passes' worth. The same for the SPPM baseline. Heap measured by a counting allocator, so
//! this file holds one test (the allocator counts every thread of the binary).

#[path = "support/tracking_allocator.rs"]
mod tracking_allocator;

use photon_maps::kdtree::Photon;
use photon_maps::render::progressive::{
    ProgressiveRenderer, ProgressiveSettings, ProgressiveStats, SppmRenderer, SppmSettings,
};
use photon_maps::render::{EstimatorKind, Mode, RenderSettings};
use photon_maps::trace::Partitioner;
use photon_maps::trace::{CreaseAngle, Scene, scenes};
use tracking_allocator::{peak, reset_peak};

const SIZE: u32 = 16;

fn settings() -> RenderSettings {
    RenderSettings {
        width: SIZE,
        height: SIZE,
        photons: 3_000,
        mode: Mode::ShadowRays,
        threads: 2,
        seed: 9,
        ..RenderSettings::default()
    }
}

/// Peak heap bytes above what was live before, and the run's figures.
fn measure(f: impl FnOnce() -> ProgressiveStats) -> (usize, ProgressiveStats) {
    let before = reset_peak();
    let stats = f();
    (peak() - before, stats)
}

fn progressive(scene: &Scene, passes: u64) -> ProgressiveStats {
    let s = ProgressiveSettings::new(settings(), passes);
    ProgressiveRenderer::new(EstimatorKind::GeometryCube, s)
        .render(&CreaseAngle::default().partition(scene.clone()).unwrap(), &())
        .unwrap()
        .stats
}

fn sppm(scene: &Scene, passes: u64) -> ProgressiveStats {
    SppmRenderer::new(SppmSettings::new(settings(), passes))
        .render(scene, &())
        .unwrap()
        .stats
}

/// Checks that 20 passes peak no higher than 2 passes plus half of one pass's photons as
/// traced (full-precision photons, before they go into trees), and that the figures the
/// renderer reports are right.
fn check(name: &str, run: impl Fn(u64) -> ProgressiveStats) {
    run(1); // warm up: the thread pool's and the allocator's first-use buffers
    let (two, s2) = measure(|| run(2));
    let (twenty, s20) = measure(|| run(20));
    assert_eq!((s2.passes, s20.passes), (2, 20), "{name}");
    let per_pass = (s20.photons_stored / 20) as usize * size_of::<Photon>();
    assert!(
        twenty <= two + per_pass / 2,
        "{name}: peak heap grew with passes: 2 passes {two} B, 20 passes {twenty} B (one pass's photons {per_pass} B)"
    );
    // The peak holds at least one pass's trees and the sum: the counting works.
    assert!(
        two as u64 >= s2.pass_tree_bytes + s2.accumulation_bytes,
        "{name}: {two} B"
    );
    // The reported tree bytes are one pass's photons at about 20 bytes each, not 20 passes'.
    let stored_per_pass = s20.photons_stored / 20;
    assert!(
        s20.pass_tree_bytes < 24 * stored_per_pass * 11 / 10,
        "{name}: {} tree bytes for {stored_per_pass} photons a pass",
        s20.pass_tree_bytes
    );
}

#[test]
fn peak_heap_does_not_grow_with_the_pass_count() {
    let scene = scenes::build("cornell-box").unwrap();
    check("progressive", |passes| progressive(&scene, passes));
    check("sppm", |passes| sppm(&scene, passes));
}
