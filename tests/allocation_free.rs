//! "Allocates nothing once warm", counted: a global allocator that counts the allocations of
//! the calling thread shows that clipping, k-nearest queries, ray casts and all three
//! estimators allocate nothing once their scratch buffers have grown (the same queries run a
//! second time allocate zero times).

use photon_maps::geom::{Aabb, Ball, ClipScratch, GatherVolume, clip_polygon_to_aabb};
use photon_maps::kdtree::{Chebyshev, Euclidean, KindMask, Neighbours};
use photon_maps::render::Disc;
use photon_maps::render::{
    Estimator, EstimatorOptions, EstimatorScratch, GeometryBall, GeometryCube, MapView, SurfacePoint,
};
use photon_maps::trace::glam::Vec3;
use photon_maps::trace::{
    CreaseAngle, Partitioner, PhotonMaps, RayKind, Rng, TraceOptions, scenes, trace_photons,
};
use std::alloc::{GlobalAlloc, Layout, System};
use std::cell::Cell;

/// The system allocator, counting allocations (and reallocations) per thread.
struct Counting;

thread_local! {
    static ALLOCATIONS: Cell<u64> = const { Cell::new(0) };
}

fn count_one() {
    // `try_with`: the counter may already be gone while a thread shuts down.
    let _ = ALLOCATIONS.try_with(|c| c.set(c.get() + 1));
}

// SAFETY: every call is forwarded unchanged to the system allocator; counting touches only a
// const-initialised thread-local cell, which never allocates.
unsafe impl GlobalAlloc for Counting {
    unsafe fn alloc(&self, layout: Layout) -> *mut u8 {
        count_one();
        // SAFETY: the caller's contract is passed on as is.
        unsafe { System.alloc(layout) }
    }

    unsafe fn alloc_zeroed(&self, layout: Layout) -> *mut u8 {
        count_one();
        // SAFETY: as above.
        unsafe { System.alloc_zeroed(layout) }
    }

    unsafe fn realloc(&self, ptr: *mut u8, layout: Layout, new_size: usize) -> *mut u8 {
        count_one();
        // SAFETY: as above.
        unsafe { System.realloc(ptr, layout, new_size) }
    }

    unsafe fn dealloc(&self, ptr: *mut u8, layout: Layout) {
        // SAFETY: as above.
        unsafe { System.dealloc(ptr, layout) }
    }
}

#[global_allocator]
static GLOBAL: Counting = Counting;

/// Allocations made by this thread while `f` runs.
fn allocations_in(f: impl FnOnce()) -> u64 {
    let before = ALLOCATIONS.with(Cell::get);
    f();
    ALLOCATIONS.with(Cell::get) - before
}

#[test]
fn the_counter_sees_allocations() {
    // Guards the tests below against a counter that never counts.
    assert!(allocations_in(|| drop(std::hint::black_box(vec![1u8; 100]))) >= 1);
}

#[test]
fn clipping_allocates_nothing_once_warm() {
    let mut rng = Rng::new(1, 0);
    let mut r = || rng.next_f32();
    let cases: Vec<(Vec<Vec3>, Aabb, Ball)> = (0..500)
        .map(|_| {
            let corners = 3 + (r() * 6.0) as usize;
            let centre = Vec3::new(r(), r(), r());
            let (u, v) = (Vec3::new(r(), r(), r()) - 0.5, Vec3::new(r(), r(), r()) - 0.5);
            // A convex polygon: points on an ellipse in the plane of u and v.
            let polygon = (0..corners)
                .map(|i| {
                    let a = i as f32 / corners as f32 * std::f32::consts::TAU;
                    centre + u * a.cos() + v * a.sin()
                })
                .collect();
            let at = Vec3::new(r(), r(), r());
            (polygon, Aabb::cube(at, 0.3 * r()), Ball::new(at, 0.3 * r()))
        })
        .collect();
    let mut scratch = ClipScratch::new();
    let run = |scratch: &mut ClipScratch| {
        let mut area = 0.0;
        for (polygon, cube, ball) in &cases {
            let normal = (polygon[1] - polygon[0])
                .cross(polygon[2] - polygon[0])
                .normalize();
            area += clip_polygon_to_aabb(polygon, cube, scratch).len() as f32;
            area += cube.polygon_area_inside(polygon, normal, scratch);
            area += ball.polygon_area_inside(polygon, normal, scratch);
        }
        area
    };
    let warm = run(&mut scratch);
    let mut again = 0.0;
    assert_eq!(allocations_in(|| again = run(&mut scratch)), 0);
    assert_eq!(warm, again);
    assert!(warm > 0.0, "no polygon met its volume: the test measured nothing");
}

#[test]
fn queries_ray_casts_and_estimators_allocate_nothing_once_warm() {
    let scene = scenes::build("cornell-box").unwrap();
    let assignment = CreaseAngle::default()
        .partition(scene.clone())
        .unwrap()
        .assignment()
        .clone();
    let options = TraceOptions {
        photons: 20_000,
        seed: 3,
        max_bounces: 64,
        pass: 0,
    };
    let maps = PhotonMaps::build(
        &scene,
        &assignment,
        trace_photons(&scene, &assignment, &options).unwrap(),
    )
    .unwrap();
    // Camera rays over the image: the points the renderer would estimate at.
    let mut rng = Rng::new(4, 0);
    let rays: Vec<_> = (0..400)
        .map(|_| scene.camera().ray(rng.next_f32(), rng.next_f32(), 1.0))
        .collect();
    let estimator_options = EstimatorOptions::for_scene(&scene.bounds());
    let estimators: [&dyn Estimator; 3] = [&Disc, &GeometryCube, &GeometryBall];
    let mut scratch = EstimatorScratch::new();
    let mut neighbours = Neighbours::with_capacity(estimator_options.k);
    let run = |scratch: &mut EstimatorScratch, neighbours: &mut Neighbours| {
        let mut sum = Vec3::ZERO;
        let mut found = 0;
        for ray in &rays {
            let Some(hit) = scene.intersect(ray, f32::INFINITY, RayKind::Camera) else {
                continue;
            };
            let map = maps.map(maps.map_of(hit.part));
            let view = MapView {
                tree: map.tree(),
                polygons: map.geometry(),
            };
            let at = SurfacePoint::front(hit.position, hit.normal);
            for estimator in estimators {
                sum += estimator.irradiance(at, view, &estimator_options, scratch);
            }
            let k = estimator_options.k;
            map.tree()
                .nearest_k::<Chebyshev>(hit.position, k, f32::INFINITY, KindMask::ALL, neighbours);
            found += neighbours.as_slice().len();
            map.tree().nearest_k::<Euclidean>(
                hit.position,
                k,
                f32::INFINITY,
                KindMask::NOT_DIRECT,
                neighbours,
            );
            found += neighbours.as_slice().len();
        }
        (sum, found)
    };
    let warm = run(&mut scratch, &mut neighbours);
    let mut again = (Vec3::ZERO, 0);
    assert_eq!(allocations_in(|| again = run(&mut scratch, &mut neighbours)), 0);
    assert_eq!(warm, again);
    assert!(
        warm.0.min_element() > 0.0 && warm.1 > 0,
        "nothing was estimated: {warm:?}"
    );
}
