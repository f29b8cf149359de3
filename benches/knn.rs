//! pm-kdtree against kiddo 6 `ImmutableKdTree` in the same run on identical data: build time,
//! and k-nearest queries per second (k = 50, 100; Euclidean and Chebyshev; 100k and 1M
//! points; uniform in a cube and photon-like on the five walls of a box), one thread.
//!
//! Run: `cargo bench --bench knn -- --warm-up-time 1 --measurement-time 2` (add a filter such
//! as `knn/uniform/100000` to run a part). Criterion prints queries/s as elem/s.

use criterion::{BenchmarkId, Criterion, Throughput, criterion_group, criterion_main};
use glam::Vec3;
use kiddo::{Chebyshev as KChebyshev, ImmutableKdTree, SquaredEuclidean};
use photon_maps::kdtree::{
    Chebyshev, Euclidean, KindMask, Metric, Neighbours, Photon, PhotonKind, PhotonTree,
};
use std::hint::black_box;
use std::num::NonZero;

const QUERIES: usize = 1000;

/// SplitMix64, so both trees see the same points on every run.
struct Rng(u64);
impl Rng {
    fn f32(&mut self) -> f32 {
        self.0 = self.0.wrapping_add(0x9e37_79b9_7f4a_7c15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xbf58_476d_1ce4_e5b9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94d0_49bb_1331_11eb);
        ((z ^ (z >> 31)) >> 40) as f32 / (1u64 << 24) as f32
    }
    fn point(&mut self, cloud: &str) -> [f32; 3] {
        let (a, b) = (self.f32(), self.f32());
        if cloud == "uniform" {
            return [a, b, self.f32()];
        }
        // Photon-like: uniform on the five walls of the unit box open at z = 0.
        match (self.f32() * 5.0) as u32 {
            0 => [a, 0.0, b],
            1 => [a, 1.0, b],
            2 => [0.0, a, b],
            3 => [1.0, a, b],
            _ => [a, b, 1.0],
        }
    }
}

fn cloud(name: &str, n: usize, seed: u64) -> Vec<[f32; 3]> {
    let mut rng = Rng(seed);
    (0..n).map(|_| rng.point(name)).collect()
}

fn photons(points: &[[f32; 3]]) -> Vec<Photon> {
    points
        .iter()
        .map(|&p| Photon {
            position: Vec3::from(p),
            power: Vec3::splat(1e-3),
            direction: Vec3::NEG_Y,
            kind: PhotonKind::Indirect,
        })
        .collect()
}

fn pm_queries<M: Metric>(tree: &PhotonTree, queries: &[[f32; 3]], k: usize, out: &mut Neighbours) -> f32 {
    let mut sum = 0.0;
    for q in queries {
        tree.nearest_k::<M>(Vec3::from(*q), k, f32::INFINITY, KindMask::ALL, out);
        sum += out.extent();
    }
    sum
}

fn bench_queries(c: &mut Criterion) {
    for name in ["uniform", "walls"] {
        for n in [100_000, 1_000_000] {
            let points = cloud(name, n, 1);
            let queries = cloud(name, QUERIES, 2);
            let pm = PhotonTree::build(photons(&points)).expect("finite points");
            let kd = ImmutableKdTree::<f32, 3>::new_from_slice(&points).expect("kiddo builds");
            if name == "uniform" {
                println!(
                    "pm-kdtree memory at n = {n}: {:.2} bytes per photon including the tree",
                    pm.memory_bytes() as f64 / n as f64
                );
            }
            for metric in ["euclidean", "chebyshev"] {
                for k in [50usize, 100] {
                    let mut g = c.benchmark_group(format!("knn/{name}/{n}/{metric}/k{k}"));
                    g.throughput(Throughput::Elements(QUERIES as u64));
                    g.sample_size(10);
                    let mut out = Neighbours::with_capacity(k);
                    let nz = NonZero::new(k).expect("k > 0");
                    g.bench_function(BenchmarkId::from_parameter("pm"), |b| {
                        b.iter(|| match metric {
                            "euclidean" => black_box(pm_queries::<Euclidean>(&pm, &queries, k, &mut out)),
                            _ => black_box(pm_queries::<Chebyshev>(&pm, &queries, k, &mut out)),
                        })
                    });
                    g.bench_function(BenchmarkId::from_parameter("kiddo"), |b| {
                        b.iter(|| {
                            let mut sum = 0.0;
                            for q in &queries {
                                let found = match metric {
                                    "euclidean" => {
                                        kd.query(q).nearest_n::<SquaredEuclidean<f32>>(nz).execute()
                                    }
                                    _ => kd.query(q).nearest_n::<KChebyshev<f32>>(nz).execute(),
                                };
                                sum += found.last().map_or(0.0, |r| r.distance);
                            }
                            black_box(sum)
                        })
                    });
                    g.finish();
                }
            }
        }
    }
}

fn bench_build(c: &mut Criterion) {
    for name in ["uniform", "walls"] {
        for n in [100_000, 1_000_000] {
            let points = cloud(name, n, 1);
            // pm's build includes encoding the photons into 20 bytes (power, direction).
            let photons = photons(&points);
            let mut g = c.benchmark_group(format!("build/{name}/{n}"));
            g.throughput(Throughput::Elements(n as u64));
            g.sample_size(10);
            g.bench_function("pm", |b| {
                b.iter_batched(
                    || photons.clone(),
                    |p| black_box(PhotonTree::build(p).expect("finite").len()),
                    criterion::BatchSize::LargeInput,
                )
            });
            g.bench_function("kiddo", |b| {
                b.iter(|| {
                    black_box(ImmutableKdTree::<f32, 3>::new_from_slice(&points).expect("kiddo builds"))
                })
            });
            g.bench_function("kiddo_parallel", |b| {
                b.iter(|| {
                    black_box(
                        ImmutableKdTree::<f32, 3>::new_from_slice_parallel(&points).expect("kiddo builds"),
                    )
                })
            });
            g.finish();
        }
    }
}

criterion_group!(benches, bench_queries, bench_build);
criterion_main!(benches);
