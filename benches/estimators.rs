//! Irradiance queries per second of the disc, cube and ball estimators on the Cornell box's
//! photon maps (100,000 photons emitted), with one map for the whole scene and with crease-angle
//! maps, for k = 50, 100 and 200. The query points are the first diffuse hits of camera rays
//! through a 64×64 grid of pixel centres, computed once; one thread.
//!
//! Run: `cargo bench --bench estimators -- --warm-up-time 1 --measurement-time 2` (add a
//! filter such as `estimators/crease` to run a part). Criterion prints queries/s as elem/s.

#[path = "support/camera_hits.rs"]
mod camera_hits;
#[path = "support/maps.rs"]
mod support_maps;
use camera_hits::camera_hits;
use criterion::{BenchmarkId, Criterion, Throughput, criterion_group, criterion_main};
use photon_maps::render::{
    Disc, Estimator, EstimatorOptions, EstimatorScratch, GeometryBall, GeometryCube, MapView, SurfacePoint,
};
use photon_maps::trace::{CreaseAngle, Material, Partitioner, PhotonMaps, Scene, SingleMap, scenes};
use std::hint::black_box;
use std::time::Duration;
use support_maps::maps;

const GRID: u32 = 64;

/// A query: the point and the map of the surface it lies on.
struct Query {
    at: SurfacePoint,
    map: usize,
}

/// First hits on diffuse surfaces of camera rays through a grid of pixel centres.
fn queries(scene: &Scene, maps: &PhotonMaps) -> Vec<Query> {
    camera_hits(scene, GRID)
        .into_iter()
        .filter(|(hit, _)| matches!(scene.material(hit), Material::Lambertian { .. }))
        .map(|(hit, _)| Query {
            at: SurfacePoint {
                position: hit.position,
                normal: hit.normal,
                front_face: hit.front_face,
            },
            map: maps.map_of(hit.part) as usize,
        })
        .collect()
}

fn run<E: Estimator>(
    estimator: &E,
    maps: &PhotonMaps,
    queries: &[Query],
    options: &EstimatorOptions,
    scratch: &mut EstimatorScratch,
) -> f32 {
    let mut sum = 0.0;
    for q in queries {
        let map = maps.map(q.map as u32);
        let view = MapView {
            tree: map.tree(),
            polygons: map.geometry(),
        };
        sum += estimator.irradiance(q.at, view, options, scratch).x;
    }
    sum
}

fn estimators(c: &mut Criterion) {
    let scene = scenes::build("cornell-box").expect("built-in scene");
    let partitions: [(&str, &dyn Partitioner); 2] =
        [("single", &SingleMap), ("crease", &CreaseAngle::default())];
    let mut group = c.benchmark_group("estimators");
    group
        .sample_size(10)
        .warm_up_time(Duration::from_secs(1))
        .measurement_time(Duration::from_secs(2));
    for (name, partitioner) in partitions {
        let maps = maps(&scene, partitioner);
        let queries = queries(&scene, &maps);
        group.throughput(Throughput::Elements(queries.len() as u64));
        for k in [50, 100, 200] {
            let mut options = EstimatorOptions::for_scene(&scene.bounds());
            options.k = k;
            let mut scratch = EstimatorScratch::new();
            let mut bench = |label: &str, f: &mut dyn FnMut(&mut EstimatorScratch) -> f32| {
                group.bench_function(BenchmarkId::new(format!("{name}/{label}"), k), |b| {
                    b.iter(|| black_box(f(&mut scratch)))
                });
            };
            bench("disc", &mut |s| run(&Disc, &maps, &queries, &options, s));
            bench("cube", &mut |s| run(&GeometryCube, &maps, &queries, &options, s));
            bench("ball", &mut |s| run(&GeometryBall, &maps, &queries, &options, s));
        }
    }
    group.finish();
}

criterion_group!(benches, estimators);
criterion_main!(benches);
