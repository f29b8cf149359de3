//! Clipped-area throughput of pm-geom: triangles and quads against cubes from tiny to
//! enclosing (Sutherland–Hodgman with the inside/outside fast paths) and against balls
//! (exact polygon ∩ disc), and overlap queries on a `PolygonSet`. Reports polygons (or
//! queries) per second.
//!
//! `cargo bench --bench clip -- --warm-up-time 1 --measurement-time 2`

use criterion::{BenchmarkId, Criterion, Throughput, criterion_group, criterion_main};
use photon_maps::geom::glam::{Vec3, vec3};
use photon_maps::geom::{Aabb, Ball, ClipScratch, GatherVolume, PolygonSet, polygon_normal};
use std::hint::black_box;

/// Polygons per measured batch.
const BATCH: usize = 1024;

/// A small deterministic generator in [0, 1).
struct Lcg(u64);

impl Lcg {
    fn next(&mut self) -> f32 {
        self.0 = self
            .0
            .wrapping_mul(6364136223846793005)
            .wrapping_add(1442695040888963407);
        (self.0 >> 40) as f32 / (1u64 << 24) as f32
    }

    fn vec(&mut self) -> Vec3 {
        vec3(self.next(), self.next(), self.next()) * 2.0 - Vec3::ONE
    }
}

/// `BATCH` random polygons of `sides` vertices (regular, radius 0.5, random orientation),
/// each paired with a query centre on or near it, and its unit normal.
fn polygons(sides: usize, rng: &mut Lcg) -> Vec<(Vec<Vec3>, Vec3, Vec3)> {
    (0..BATCH)
        .map(|_| {
            let center = rng.vec() * 4.0;
            let normal = rng.vec().try_normalize().unwrap_or(Vec3::Y);
            let (u, v) = normal.any_orthonormal_pair();
            let poly: Vec<Vec3> = (0..sides)
                .map(|k| {
                    let a = std::f32::consts::TAU * k as f32 / sides as f32;
                    center + 0.5 * (u * a.cos() + v * a.sin())
                })
                .collect();
            let normal = polygon_normal(&poly).unwrap_or(normal);
            let query = center + 0.3 * (u * rng.next() + v * rng.next()) + 0.02 * normal * rng.next();
            (poly, normal, query)
        })
        .collect()
}

fn bench_volume<V: GatherVolume>(
    c: &mut Criterion,
    group_name: &str,
    make: impl Fn(Vec3, f32) -> V,
    sizes: &[(&str, f32)],
) {
    let mut group = c.benchmark_group(group_name);
    group.throughput(Throughput::Elements(BATCH as u64));
    let mut rng = Lcg(2);
    for (shape, sides) in [("triangle", 3), ("quad", 4)] {
        let polys = polygons(sides, &mut rng);
        for &(label, size) in sizes {
            let volumes: Vec<V> = polys.iter().map(|(_, _, q)| make(*q, size)).collect();
            let mut scratch = ClipScratch::new();
            group.bench_function(BenchmarkId::new(shape, label), |b| {
                b.iter(|| {
                    let mut total = 0.0;
                    for ((poly, normal, _), volume) in polys.iter().zip(&volumes) {
                        total += volume.polygon_area_inside(black_box(poly), *normal, &mut scratch);
                    }
                    black_box(total)
                })
            });
        }
    }
    group.finish();
}

fn clip_to_cube(c: &mut Criterion) {
    let sizes = [
        ("tiny_0.01", 0.01),
        ("partial_0.2", 0.2),
        ("large_0.45", 0.45),
        ("enclosing_2", 2.0),
    ];
    bench_volume(c, "area_in_cube", Aabb::cube, &sizes);
}

fn clip_to_ball(c: &mut Criterion) {
    let sizes = [
        ("tiny_0.01", 0.01),
        ("partial_0.2", 0.2),
        ("large_0.45", 0.45),
        ("enclosing_2", 2.0),
    ];
    bench_volume(c, "area_in_ball", Ball::new, &sizes);
}

/// Overlap queries on a `PolygonSet` of 16,384 triangles (a 128 × 128 floor grid, each
/// cell split in two) with cubes of a few cells: the candidate search of the estimator.
fn polygon_set_queries(c: &mut Criterion) {
    let mut set = PolygonSet::new();
    for i in 0..128 {
        for j in 0..64 {
            let (x, z) = (i as f32, j as f32 * 2.0);
            set.push(&[vec3(x, 0., z), vec3(x, 0., z + 1.), vec3(x + 1., 0., z + 1.)]);
            set.push(&[vec3(x, 0., z), vec3(x + 1., 0., z + 1.), vec3(x + 1., 0., z)]);
        }
    }
    set.build_index();
    let mut rng = Lcg(3);
    let queries: Vec<Aabb> = (0..BATCH)
        .map(|_| Aabb::cube(vec3(rng.next() * 128.0, 0.0, rng.next() * 128.0), 1.5))
        .collect();
    let mut group = c.benchmark_group("polygon_set_overlapping");
    group.throughput(Throughput::Elements(BATCH as u64));
    group.bench_function("16k_triangles_cube_1.5", |b| {
        b.iter(|| {
            let mut found = 0u32;
            for q in &queries {
                set.for_each_overlapping(black_box(q), |_| found += 1);
            }
            black_box(found)
        })
    });
    group.finish();
}

criterion_group!(benches, clip_to_cube, clip_to_ball, polygon_set_queries);
criterion_main!(benches);
