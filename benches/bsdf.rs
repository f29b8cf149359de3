//! What reading photons through a glossy BSDF costs. On the glossy Cornell box's crease maps
//! (100,000 photons), the cube estimate (k = 100) at the first hits of camera rays through a
//! 64×64 grid that land on a surface with a glossy lobe, read two ways: as irradiance (weight
//! one, the sum of powers without a direction decoded) and as reflected radiance through the
//! BSDF (`f(wo, wi_p)` per photon, the glTF metallic-roughness lobes). Their difference over
//! the photons gathered is the cost of one BSDF evaluation per photon. Then the photon-map
//! render of the glossy Cornell box against the diffuse one (64×64, 100,000 photons, cube,
//! crease maps, one thread), whole renders.
//!
//! Run: `cargo bench --bench bsdf -- --warm-up-time 1 --measurement-time 3`. Criterion prints
//! estimates/s as elem/s for the first group.

#[path = "support/camera_hits.rs"]
mod camera_hits;
#[path = "support/maps.rs"]
mod support_maps;
use camera_hits::camera_hits;
use criterion::{BenchmarkId, Criterion, Throughput, criterion_group, criterion_main};
use photon_maps::render::{
    BsdfWeight, Estimator, EstimatorKind, EstimatorOptions, EstimatorScratch, GeometryCube, Irradiance,
    MapView, Mode, PhotonWeight, RenderSettings, Renderer, SurfacePoint,
};
use photon_maps::trace::glam::Vec3;
use photon_maps::trace::{Bsdf, CreaseAngle, Hit, Partitioner, PhotonMaps, Scene, scenes};
use std::hint::black_box;
use std::time::Duration;
use support_maps::maps;

const GRID: u32 = 64;

/// A glossy query: the hit and the map of the surface it lies on.
struct Query {
    hit: Hit,
    wo: Vec3,
    map: u32,
}

/// First camera hits on surfaces with a glossy lobe.
fn glossy_queries(scene: &Scene, maps: &PhotonMaps) -> Vec<Query> {
    camera_hits(scene, GRID)
        .into_iter()
        .filter(|(hit, _)| scene.material(hit).lobes().has_glossy())
        .map(|(hit, ray)| Query {
            hit,
            wo: -ray.direction,
            map: maps.map_of(hit.part),
        })
        .collect()
}

fn run(
    scene: &Scene,
    maps: &PhotonMaps,
    queries: &[Query],
    through_bsdf: bool,
    scratch: &mut EstimatorScratch,
) -> f32 {
    let options = EstimatorOptions::for_scene(&scene.bounds());
    let mut sum = 0.0;
    for q in queries {
        let map = maps.map(q.map);
        let view = MapView {
            tree: map.tree(),
            polygons: map.geometry(),
        };
        let at = SurfacePoint {
            position: q.hit.position,
            normal: q.hit.normal,
            front_face: q.hit.front_face,
        };
        let bsdf = BsdfWeight::new(scene.material(&q.hit), scene.shading_point(&q.hit), q.wo);
        let weight: &dyn PhotonWeight = if through_bsdf { &bsdf } else { &Irradiance };
        sum += GeometryCube.estimate(at, view, &options, weight, scratch).x;
    }
    sum
}

fn photon_reads(c: &mut Criterion) {
    let scene = scenes::build("glossy-cornell-box").expect("built-in scene");
    let maps = maps(&scene, &CreaseAngle::default());
    let queries = glossy_queries(&scene, &maps);
    let mut group = c.benchmark_group("glossy_reads");
    group
        .sample_size(10)
        .warm_up_time(Duration::from_secs(1))
        .measurement_time(Duration::from_secs(3));
    group.throughput(Throughput::Elements(queries.len() as u64));
    let mut scratch = EstimatorScratch::new();
    for (label, through_bsdf) in [("irradiance", false), ("bsdf", true)] {
        group.bench_function(BenchmarkId::new("cube_k100", label), |b| {
            b.iter(|| black_box(run(&scene, &maps, &queries, through_bsdf, &mut scratch)))
        });
    }
    group.finish();
}

fn renders(c: &mut Criterion) {
    let mut group = c.benchmark_group("photon_map_render");
    group
        .sample_size(10)
        .warm_up_time(Duration::from_secs(1))
        .measurement_time(Duration::from_secs(5));
    let settings = RenderSettings {
        width: 64,
        height: 64,
        photons: 100_000,
        mode: Mode::PhotonMap,
        threads: 1,
        ..RenderSettings::default()
    };
    for name in ["cornell-box", "glossy-cornell-box"] {
        let scene = scenes::build(name).expect("built-in scene");
        let partitioned = CreaseAngle::default().partition(scene).unwrap();
        group.bench_function(BenchmarkId::new("crease_cube", name), |b| {
            b.iter(|| {
                black_box(
                    Renderer::new(EstimatorKind::GeometryCube, settings)
                        .render(&partitioned, &())
                        .unwrap()
                        .image,
                )
            })
        });
    }
    group.finish();
}

criterion_group!(benches, photon_reads, renders);
criterion_main!(benches);
