//! Ray casting against triangle count: closest-hit rays per second through the scene's BVH on
//! the rooms with every face split n × n (24 → 240k triangles), beside an anchor measured in
//! the same run: obvhs's own `CwBvh` (its PLOC builder, `medium_build`) and its Möller–Trumbore
//! triangle test on the same triangles and rays. Also scene build times, including a
//! 60k-triangle fan (thin triangles sharing one vertex: a degenerate input for BVH builders).
//! `ours_in_pairs` casts the same rays two at a time through `Scene::intersect_pair`.
//!
//! Run: `cargo bench --bench raycast -- --warm-up-time 1 --measurement-time 2`

use criterion::{BenchmarkId, Criterion, Throughput, criterion_group, criterion_main};
use glam::{Vec2, Vec3, Vec3A};
use obvhs::BvhBuildParams;
use obvhs::cwbvh::builder::build_cwbvh_from_tris;
use obvhs::ray::RayHit;
use obvhs::triangle::Triangle;
use photon_maps::trace::scene::RayKind;
use photon_maps::trace::scenes::scale::split_rooms;
use photon_maps::trace::{PointLight, Ray, Rng, Scene, Surface, sampling};
use std::hint::black_box;
use std::time::Duration;

const SPLITS: [u32; 4] = [1, 10, 30, 100];

/// Rays from random points inside either room in uniformly random directions.
fn random_rays(count: usize) -> Vec<Ray> {
    let mut rng = Rng::new(3, 1);
    (0..count)
        .map(|_| {
            let room = if rng.next_f32() < 0.5 { 0.0 } else { 1.02 };
            let origin = Vec3::new(room + rng.next_f32(), rng.next_f32(), rng.next_f32());
            let direction = sampling::uniform_sphere(Vec2::new(rng.next_f32(), rng.next_f32()));
            Ray { origin, direction }
        })
        .collect()
}

fn scene_triangles(scene: &Scene) -> Vec<Triangle> {
    let mut out = Vec::new();
    for mesh in scene.meshes() {
        let mesh = mesh.half_edge_mesh();
        for face in mesh.faces() {
            let p: Vec<Vec3> = mesh.face_polygon(face).collect();
            for i in 1..p.len() - 1 {
                out.push(Triangle {
                    v0: p[0].into(),
                    v1: p[i].into(),
                    v2: p[i + 1].into(),
                });
            }
        }
    }
    out
}

fn bench_raycast(c: &mut Criterion) {
    let rays = random_rays(20_000);
    let mut g = c.benchmark_group("closest_hit");
    g.sample_size(10).measurement_time(Duration::from_secs(2));
    g.throughput(Throughput::Elements(rays.len() as u64));
    for n in SPLITS {
        let scene = split_rooms(n).expect("scene");
        let triangles = scene_triangles(&scene);
        let label = format!("{}_triangles", triangles.len());
        g.bench_with_input(BenchmarkId::new("ours", &label), &n, |b, _| {
            b.iter(|| {
                rays.iter()
                    .filter(|r| scene.intersect(r, f32::INFINITY, RayKind::Other).is_some())
                    .count()
            })
        });
        g.bench_with_input(BenchmarkId::new("ours_in_pairs", &label), &n, |b, _| {
            b.iter(|| {
                rays.chunks_exact(2)
                    .map(|r| {
                        let [a, b] = scene.intersect_pair([&r[0], &r[1]], f32::INFINITY);
                        a.is_some() as usize + b.is_some() as usize
                    })
                    .sum::<usize>()
            })
        });
        let bvh = build_cwbvh_from_tris(
            &triangles,
            BvhBuildParams::medium_build(),
            &mut Duration::default(),
        );
        let ordered: Vec<Triangle> = bvh
            .primitive_indices
            .iter()
            .map(|&i| triangles[i as usize])
            .collect();
        g.bench_with_input(BenchmarkId::new("obvhs_anchor", &label), &n, |b, _| {
            b.iter(|| {
                rays.iter()
                    .filter(|r| {
                        let ray = obvhs::ray::Ray::new_inf(Vec3A::from(r.origin), Vec3A::from(r.direction));
                        let mut hit = RayHit::none();
                        bvh.ray_traverse(ray, &mut hit, |ray, i| ordered[i].intersect(ray))
                    })
                    .count()
            })
        });
    }
    g.finish();

    let mut g = c.benchmark_group("scene_build");
    g.sample_size(10).measurement_time(Duration::from_secs(3));
    for n in [10u32, 100] {
        g.bench_with_input(BenchmarkId::new("split_rooms", 24 * n * n), &n, |b, &n| {
            b.iter(|| black_box(split_rooms(n).expect("scene")))
        });
    }
    let fan = 60_000u32;
    let mut positions = vec![Vec3::ZERO];
    positions.extend((0..fan).map(|i| {
        let a = i as f32 / fan as f32 * 0.999 * std::f32::consts::TAU;
        Vec3::new(a.cos(), 0.0, a.sin())
    }));
    let faces: Vec<[u32; 3]> = (1..fan).map(|i| [0, i + 1, i]).collect();
    g.bench_function(BenchmarkId::new("triangle_fan", fan - 1), |b| {
        b.iter(|| {
            Scene::builder()
                .mesh(&positions, &faces, Surface::diffuse(Vec3::splat(0.5)))
                .light(PointLight::new(Vec3::Y, Vec3::ONE))
                .build()
                .expect("fan scene")
        })
    });
    g.finish();
}

criterion_group!(benches, bench_raycast);
criterion_main!(benches);
