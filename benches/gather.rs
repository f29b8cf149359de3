//! A final gather's lookup against the estimate it replaces: the precomputed irradiance read
//! by one nearest-point query versus a k-nearest estimate (k = 100, disc and cube) at the same
//! points, on the Cornell box's crease maps (100,000 photons emitted). The points are the
//! diffuse hits of gather rays from the first diffuse hits of a 32×32 grid of camera rays,
//! computed once; one thread. Also the cost of building the cache (one photon in 4).
//!
//! Run: `cargo bench --bench gather -- --warm-up-time 1 --measurement-time 2`. Criterion
//! prints lookups/s as elem/s.

#[path = "support/maps.rs"]
mod support_maps;
use criterion::{Criterion, Throughput, criterion_group, criterion_main};
use photon_maps::render::glam::Vec2;
use photon_maps::render::source::map_irradiance;
use photon_maps::render::{Disc, Estimator, EstimatorOptions, EstimatorScratch, GeometryCube, RadianceCache};
use photon_maps::trace::sampling::cosine_hemisphere;
use photon_maps::trace::{CreaseAngle, Hit, Material, PhotonMaps, RayKind, Rng, Scene, scenes};
use std::hint::black_box;
use std::time::Duration;
use support_maps::maps;

const GRID: u32 = 32;

fn diffuse(scene: &Scene, hit: &Hit) -> bool {
    matches!(scene.material(hit), Material::Lambertian { .. })
}

/// Diffuse hits of one cosine-weighted gather ray from each camera ray's first diffuse hit.
fn gather_hits(scene: &Scene) -> Vec<Hit> {
    let mut rng = Rng::new(1, 0);
    let mut out = Vec::new();
    for y in 0..GRID {
        for x in 0..GRID {
            let (u, v) = ((x as f32 + 0.5) / GRID as f32, (y as f32 + 0.5) / GRID as f32);
            let ray = scene.camera().ray(u, v, 1.0);
            let Some(hit) = scene.intersect(&ray, f32::INFINITY, RayKind::Camera) else {
                continue;
            };
            if !diffuse(scene, &hit) {
                continue;
            }
            let d = cosine_hemisphere(hit.normal, Vec2::new(rng.next_f32(), rng.next_f32()));
            if let Some(y) = scene.intersect(&scene.spawn_ray(&hit, d), f32::INFINITY, RayKind::Other)
                && diffuse(scene, &y)
            {
                out.push(y);
            }
        }
    }
    out
}

fn estimate<E: Estimator>(
    estimator: &E,
    scene: &Scene,
    maps: &PhotonMaps,
    hits: &[Hit],
    options: &EstimatorOptions,
    scratch: &mut EstimatorScratch,
) -> f32 {
    let mut sum = 0.0;
    for hit in hits {
        sum += map_irradiance(scene, maps, estimator, options, hit, scratch).x;
    }
    sum
}

fn gather(c: &mut Criterion) {
    let scene = scenes::build("cornell-box").expect("built-in scene");
    let maps = maps(&scene, &CreaseAngle::default());
    let options = EstimatorOptions::for_scene(&scene.bounds());
    let hits = gather_hits(&scene);
    let mut scratch = EstimatorScratch::new();
    let mut group = c.benchmark_group("gather");
    group.throughput(Throughput::Elements(hits.len() as u64));
    let cache = RadianceCache::build(&scene, &maps, &GeometryCube, &options, 4).expect("cache");
    group.bench_function("cache lookup", |b| {
        b.iter(|| {
            let mut sum = 0.0;
            for hit in &hits {
                sum += cache.radiance(&scene, black_box(hit), &mut scratch).x;
            }
            sum
        })
    });
    group.bench_function("k-nearest cube k=100", |b| {
        b.iter(|| {
            estimate(
                &GeometryCube,
                &scene,
                &maps,
                black_box(&hits),
                &options,
                &mut scratch,
            )
        })
    });
    group.bench_function("k-nearest disc k=100", |b| {
        b.iter(|| estimate(&Disc, &scene, &maps, black_box(&hits), &options, &mut scratch))
    });
    group.finish();
    let mut build = c.benchmark_group("gather cache build");
    build.sample_size(10);
    build.bench_function("one photon in 4, cube", |b| {
        b.iter(|| RadianceCache::build(&scene, &maps, &GeometryCube, &options, 4).expect("cache"))
    });
    build.finish();
}

criterion_group! {
    name = benches;
    config = Criterion::default().warm_up_time(Duration::from_millis(500)).measurement_time(Duration::from_secs(2));
    targets = gather
}
criterion_main!(benches);
