//! Determinism: the traced photons are bit-identical with 1 and 2 threads and across runs.

use pm_trace::{CreaseAngle, Partitioner, Photon, TraceOptions, TracedPhotons, scenes, trace_photons};

fn bits(traced: &TracedPhotons) -> Vec<Vec<[u32; 10]>> {
    let b = |p: &Photon| {
        [
            p.position.x.to_bits(),
            p.position.y.to_bits(),
            p.position.z.to_bits(),
            p.power.x.to_bits(),
            p.power.y.to_bits(),
            p.power.z.to_bits(),
            p.direction.x.to_bits(),
            p.direction.y.to_bits(),
            p.direction.z.to_bits(),
            p.kind as u32,
        ]
    };
    traced
        .photons_per_map()
        .iter()
        .map(|m| m.iter().map(b).collect())
        .collect()
}

#[test]
fn photons_are_bit_identical_for_one_and_two_threads_and_across_runs() {
    let scene = scenes::build("cornell-box").unwrap();
    let maps = CreaseAngle::default()
        .partition(scene.clone())
        .unwrap()
        .assignment()
        .clone();
    // Not a multiple of the chunk size, so the last chunk is partial.
    let options = TraceOptions {
        photons: 30_001,
        seed: 42,
        max_bounces: 64,
        pass: 0,
    };
    let run = |threads: usize| {
        let pool = rayon::ThreadPoolBuilder::new()
            .num_threads(threads)
            .build()
            .unwrap();
        pool.install(|| trace_photons(&scene, &maps, &options).unwrap())
    };
    let one = bits(&run(1));
    let two = bits(&run(2));
    let again = bits(&run(2));
    // Three threads: waves of another size (they scale with the thread count).
    let three = bits(&run(3));
    assert!(one.iter().map(Vec::len).sum::<usize>() > 30_000);
    assert!(one == two, "1 vs 2 threads differ");
    assert!(two == again, "two runs differ");
    assert!(one == three, "1 vs 3 threads differ");
    // A different seed gives different photons (the comparison can fail).
    let other = bits(&trace_photons(&scene, &maps, &TraceOptions { seed: 43, ..options }).unwrap());
    assert!(other != one);
}

#[test]
fn pass_zero_is_the_plain_trace_and_other_passes_are_fresh_photons() {
    use pm_trace::Rng;
    let scene = scenes::build("accordion").unwrap();
    let maps = CreaseAngle::default()
        .partition(scene.clone())
        .unwrap()
        .assignment()
        .clone();
    let options = TraceOptions {
        photons: 3_000,
        seed: 9,
        ..TraceOptions::default()
    };
    assert_eq!(options.pass, 0, "pass 0 is the default");
    assert_eq!(Rng::new(9, 17), Rng::for_pass(9, 0, 17));
    let plain = bits(&trace_photons(&scene, &maps, &options).unwrap());
    let pass = |pass| bits(&trace_photons(&scene, &maps, &TraceOptions { pass, ..options }).unwrap());
    assert!(pass(0) == plain);
    let (one, two) = (pass(1), pass(2));
    assert!(one != plain && two != plain && one != two, "passes share photons");
    // The same pass is the same photons wherever it is traced.
    assert!(pass(1) == one);
}
