//! Cost of cutting faces where they meet (the contact partition's arrangement): how it grows
//! with the faces and with the meetings. A floor of n triangles alone (nothing meets: the cost
//! every scene pays under the default partition), the same floor pierced by 200 small boxes (a
//! few thousand piercing and in-plane meetings), and the whole split of the `split-rooms-100`
//! scale scene (240,000 triangles) against its crease-angle partition.
//!
//! `cargo bench --bench arrangement -- --warm-up-time 1 --measurement-time 3`

use criterion::{BatchSize, BenchmarkId, Criterion, Throughput, criterion_group, criterion_main};
use photon_maps::geom::glam::{Vec3, vec3};
use photon_maps::geom::{Aabb, ArrangementOptions, split_polygons_at_intersections};
use photon_maps::trace::{Contact, CreaseAngle, Partitioner, scenes};
use std::hint::black_box;

/// A 1 m floor in y = 0 of `2 · side²` triangles, facing up.
fn floor(side: usize) -> Vec<Vec<Vec3>> {
    let step = 1.0 / side as f32;
    let mut out = Vec::with_capacity(2 * side * side);
    for i in 0..side {
        for j in 0..side {
            let p = |a: usize, b: usize| vec3(a as f32 * step, 0.0, b as f32 * step);
            out.push(vec![p(i, j), p(i, j + 1), p(i + 1, j + 1)]);
            out.push(vec![p(i, j), p(i + 1, j + 1), p(i + 1, j)]);
        }
    }
    out
}

/// `count` boxes 2 cm × 1 cm × 2 cm on a jittered grid over the floor, sunk 5 mm into it.
fn boxes(count: usize) -> Vec<Vec<Vec3>> {
    let per_row = (count as f32).sqrt().ceil() as usize;
    let mut out = Vec::new();
    for k in 0..count {
        let (i, j) = (k % per_row, k / per_row);
        let jitter = ((k * 7919) % 97) as f32 / 97.0 * 0.01;
        let lo = vec3(
            (i as f32 + 0.3) / per_row as f32 + jitter,
            -0.005,
            (j as f32 + 0.3) / per_row as f32,
        );
        let hi = lo + vec3(0.02, 0.01, 0.02);
        out.extend(Aabb::new(lo, hi).face_quads().iter().map(|q| q.to_vec()));
    }
    out
}

fn bench_arrangement(c: &mut Criterion) {
    let options = ArrangementOptions::new(1e-5 * 1.5, 2e-3 * 1.5);
    let mut group = c.benchmark_group("arrangement");
    group.sample_size(10);
    for side in [50, 150, 346] {
        let polygons = floor(side);
        group.throughput(Throughput::Elements(polygons.len() as u64));
        group.bench_with_input(
            BenchmarkId::new("floor alone", polygons.len()),
            &polygons,
            |b, p| b.iter(|| black_box(split_polygons_at_intersections(p, &[], &options).unwrap())),
        );
        let mut pierced = polygons.clone();
        pierced.extend(boxes(200));
        let meetings = split_polygons_at_intersections(&pierced, &[], &options)
            .unwrap()
            .counts
            .meetings();
        group.bench_with_input(
            BenchmarkId::new(
                format!("floor and 200 boxes ({meetings} meetings)"),
                pierced.len(),
            ),
            &pierced,
            |b, p| b.iter(|| black_box(split_polygons_at_intersections(p, &[], &options).unwrap())),
        );
    }
    group.finish();

    let mut group = c.benchmark_group("partition split-rooms-100");
    group.sample_size(10);
    let scene = scenes::build("split-rooms-100").unwrap();
    // The scene is cloned outside the timing: partitioning takes it by value.
    group.bench_function("crease partition", |b| {
        b.iter_batched(
            || scene.clone(),
            |scene| black_box(CreaseAngle::default().partition(scene).unwrap()),
            BatchSize::LargeInput,
        )
    });
    group.bench_function("contact split and partition", |b| {
        b.iter_batched(
            || scene.clone(),
            |scene| black_box(Contact::default().partition(scene).unwrap()),
            BatchSize::LargeInput,
        )
    });
    group.finish();
}

criterion_group!(benches, bench_arrangement);
criterion_main!(benches);
