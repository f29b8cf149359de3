//! Photon tracing throughput on the Cornell box: emitted photon paths per second with 1 and
//! 2 threads (criterion reports Melem/s = millions of paths per second; the stored photons per
//! path are printed first), plus scene and BVH build and photon-map build times.
//!
//! Run: `cargo bench --bench trace -- --warm-up-time 1 --measurement-time 2`

use criterion::{BenchmarkId, Criterion, Throughput, criterion_group, criterion_main};
use photon_maps::trace::{CreaseAngle, Partitioner, PhotonMaps, TraceOptions, scenes, trace_photons};
use std::hint::black_box;
use std::time::Duration;

fn bench_trace(c: &mut Criterion) {
    let scene = scenes::build("cornell-box").expect("built-in scene");
    let maps = CreaseAngle::default()
        .partition(scene.clone())
        .unwrap()
        .assignment()
        .clone();
    let photons = 200_000;
    let options = TraceOptions {
        photons,
        seed: 1,
        max_bounces: 64,
        pass: 0,
    };
    // The throughput below counts emitted paths; each stores about 1.7 photons here.
    let stored = trace_photons(&scene, &maps, &options)
        .expect("trace")
        .stats()
        .total_stored();
    eprintln!(
        "cornell-box: {photons} paths store {stored} photons ({:.3} per path)",
        stored as f64 / photons as f64
    );
    let mut g = c.benchmark_group("trace_cornell_box");
    g.sample_size(10).measurement_time(Duration::from_secs(2));
    g.throughput(Throughput::Elements(photons as u64));
    for threads in [1usize, 2] {
        let pool = rayon::ThreadPoolBuilder::new()
            .num_threads(threads)
            .build()
            .expect("thread pool");
        g.bench_with_input(BenchmarkId::new("threads", threads), &threads, |b, _| {
            b.iter(|| pool.install(|| black_box(trace_photons(&scene, &maps, &options).expect("trace"))))
        });
    }
    g.finish();

    let mut g = c.benchmark_group("build_cornell_box");
    g.sample_size(10).measurement_time(Duration::from_secs(2));
    g.bench_function("scene_and_bvh", |b| {
        b.iter(|| black_box(scenes::build("cornell-box").expect("scene")))
    });
    let traced = trace_photons(
        &scene,
        &maps,
        &TraceOptions {
            photons: 100_000,
            ..options
        },
    )
    .expect("trace");
    g.bench_function("photon_maps_100k", |b| {
        b.iter(|| black_box(PhotonMaps::build(&scene, &maps, traced.clone()).expect("maps")))
    });
    g.finish();
}

criterion_group!(benches, bench_trace);
criterion_main!(benches);
