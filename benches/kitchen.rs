//! The obvhs kitchen, a real modelled interior (56,939 triangles exported from Blender, every
//! vertex repeated per face, objects resting on counters): what the contact split costs
//! beside the crease partition, and photon paths per second with each partition's maps on 1
//! and 2 threads; and a whole final-gather render with the contact maps, whose gather rays it
//! counts. These are the numbers issue 34 set targets for (a split within 3× the crease
//! partition's time, 2 M paths/s on 2 threads, gather rays to match); the render example's
//! `--stats-json` gives the same phases for one run, this gives them with criterion's
//! statistics.
//!
//! Needs the kitchen converted to glTF: `python3 scripts/kitchen-gltf.py` writes
//! `target/kitchen/kitchen.gltf` from the obvhs crate in the cargo registry (or set
//! `PM_KITCHEN_GLTF`). Without it the bench says so and measures nothing.
//!
//! `cargo bench --bench kitchen -- --warm-up-time 1 --measurement-time 5`

#[path = "../tests/support/kitchen.rs"]
mod kitchen;

use criterion::{BatchSize, BenchmarkId, Criterion, Throughput, criterion_group, criterion_main};
use photon_maps::render::{EstimatorKind, FinalGatherOptions, Mode, RenderSettings, Renderer};
use photon_maps::trace::{Contact, CreaseAngle, Partitioner, TraceOptions, trace_photons};
use std::hint::black_box;
use std::time::Duration;

/// Photon paths per traced batch: about 0.1 s on 2 threads.
const PATHS: u32 = 100_000;

/// The contact gap the kitchen studies use (`--contact-gap 0.0001`: 0.8 mm of its 7.9 m
/// diagonal), beside the default.
const FINE_GAP: f32 = 1e-4;

fn pool(threads: usize) -> rayon::ThreadPool {
    rayon::ThreadPoolBuilder::new()
        .num_threads(threads)
        .build()
        .expect("thread pool")
}

fn bench_kitchen(c: &mut Criterion) {
    let path = kitchen::kitchen_path();
    let Some(scene) = kitchen::load_kitchen(&path) else {
        return;
    };
    let fine = Contact {
        relative_gap: FINE_GAP,
        ..Contact::default()
    };
    let partitioners: [(&str, Box<dyn Partitioner + Sync>); 3] = [
        ("crease", Box::new(CreaseAngle::default())),
        ("contact gap 1e-4", Box::new(fine)),
        ("contact default gap", Box::new(Contact::default())),
    ];
    let two = pool(2);

    // What each partition makes of the kitchen, so that a time can be read per map or per
    // meeting.
    let mut partitioned = Vec::new();
    for (name, partitioner) in &partitioners {
        let split = two
            .install(|| partitioner.partition(scene.clone()))
            .expect("the kitchen partitions");
        let meetings = split.record().map_or(0, |r| r.counts().meetings());
        let pairs = split.record().map_or(0, |r| r.counts().candidate_pairs);
        eprintln!(
            "kitchen, {name}: {} parts, {} maps, {meetings} meetings from {pairs} candidate pairs",
            split.scene().part_count(),
            split.assignment().map_count(),
        );
        partitioned.push((*name, split));
    }

    let mut g = c.benchmark_group("kitchen_setup");
    g.sample_size(10).measurement_time(Duration::from_secs(5));
    g.bench_function("load", |b| {
        b.iter(|| two.install(|| black_box(photon_maps::trace::gltf::load_scene(&path).expect("load"))))
    });
    for (name, partitioner) in &partitioners {
        g.bench_function(BenchmarkId::new("partition", name), |b| {
            b.iter_batched(
                || scene.clone(),
                |s| two.install(|| black_box(partitioner.partition(s).expect("partition"))),
                BatchSize::LargeInput,
            )
        });
    }
    g.finish();

    let options = TraceOptions {
        photons: PATHS,
        seed: 1,
        max_bounces: 64,
        pass: 0,
    };
    let mut g = c.benchmark_group("kitchen_trace");
    g.sample_size(10).measurement_time(Duration::from_secs(5));
    g.throughput(Throughput::Elements(u64::from(PATHS)));
    for (name, split) in partitioned.iter().take(2) {
        let (scene, maps) = (split.scene(), split.assignment());
        for threads in [1usize, 2] {
            let pool = pool(threads);
            g.bench_function(BenchmarkId::new(*name, format!("{threads} threads")), |b| {
                b.iter(|| pool.install(|| black_box(trace_photons(scene, maps, &options).expect("trace"))))
            });
        }
    }
    g.finish();

    // A final-gather render as `render --mode final-gather --size 160x90 --spp 4 --photons
    // 100000 --contact-gap 0.0001` makes it: tracing, maps, the cache and the image. Its
    // throughput counts the render phase's gather rays, though the time is the whole render's.
    let settings = RenderSettings {
        width: 160,
        height: 90,
        samples_per_pixel: 4,
        photons: 100_000,
        mode: Mode::FinalGather,
        seed: 1,
        threads: 2,
        // The render example's default (the library's is 64).
        final_gather: FinalGatherOptions {
            gather_rays: 4,
            ..Default::default()
        },
        ..Default::default()
    };
    let renderer = Renderer::new(EstimatorKind::GeometryCube, settings);
    let contact = &partitioned[1].1;
    let first = renderer.render(contact, &()).expect("the kitchen renders");
    eprintln!(
        "kitchen, final gather: {} gather rays, {:.2} M/s in the render phase ({:.3} s of {:.3} s)",
        first.stats.gather_rays,
        first.stats.gather_rays_per_second() / 1e6,
        first.stats.render.as_secs_f64(),
        first.stats.total().as_secs_f64(),
    );
    let mut g = c.benchmark_group("kitchen_final_gather");
    g.sample_size(10).measurement_time(Duration::from_secs(5));
    g.throughput(Throughput::Elements(first.stats.gather_rays));
    g.bench_function("160x90, 4 spp, 100k photons, contact gap 1e-4", |b| {
        b.iter(|| black_box(renderer.render(contact, &()).expect("render")))
    });
    g.finish();
}

criterion_group!(benches, bench_kitchen);
criterion_main!(benches);
