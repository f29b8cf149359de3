//! Photon maps store their coplanar faces merged: on the split rooms (every wall split into
//! 10 × 10 quads) each map's polygons hold the same area inside random cubes and balls as the
//! faces one by one, and the cube and ball estimators render the same image both ways.

use photon_maps::geom::glam::{Vec3, vec3};
use photon_maps::geom::{Aabb, Ball, ClipScratch, GatherVolume, PolygonSet};
use photon_maps::render::{EstimatorKind, RenderSettings, Renderer};
use photon_maps::trace::{
    CreaseAngle, MapAssignment, MapGeometry, Partitioner, PhotonMaps, Scene, TraceOptions, scenes,
    trace_photons,
};

fn maps(scene: &Scene, assignment: &MapAssignment, geometry: MapGeometry, photons: u32) -> PhotonMaps {
    let options = TraceOptions {
        photons,
        seed: 5,
        ..TraceOptions::default()
    };
    let traced = trace_photons(scene, assignment, &options).unwrap();
    let maps = PhotonMaps::build_with(scene, assignment, traced, geometry).unwrap();
    maps.validate().unwrap();
    maps
}

fn area_inside(volume: &impl GatherVolume, set: &PolygonSet, scratch: &mut ClipScratch) -> f64 {
    let mut sum = 0.0;
    set.for_each_overlapping(&volume.bounds(), |i| {
        sum += f64::from(volume.polygon_area_inside(set.polygon(i), set.normal(i), scratch));
    });
    sum
}

#[test]
fn split_rooms_maps_merge_to_one_polygon_per_wall_with_the_same_area_in_any_volume() {
    let scene = scenes::build("split-rooms-10").unwrap();
    let assignment = CreaseAngle::default()
        .partition(scene.clone())
        .unwrap()
        .assignment()
        .clone();
    let (merged, per_face) = (
        maps(&scene, &assignment, MapGeometry::Merged, 2_000),
        maps(&scene, &assignment, MapGeometry::PerFace, 2_000),
    );
    let mut scratch = ClipScratch::new();
    let mut state = 0x2545_f491_u64;
    let mut uniform = move || {
        state = state
            .wrapping_mul(6_364_136_223_846_793_005)
            .wrapping_add(1_442_695_040_888_963_407);
        (state >> 40) as f32 / (1u64 << 24) as f32
    };
    for (m, (a, b)) in merged.iter().zip(per_face.iter()).enumerate() {
        let (a_set, b_set) = (a.geometry(), b.geometry());
        assert_eq!(b_set.len(), 100, "map {m}: one wall of 10 × 10 quads");
        assert_eq!(a_set.len(), 1, "map {m}: the wall merges to one polygon");
        assert_eq!(a.bounds(), b.bounds(), "map {m}");
        let (ta, tb) = (f64::from(a_set.total_area()), f64::from(b_set.total_area()));
        assert!((ta - tb).abs() <= 1e-5 * tb, "map {m}: total area {ta} vs {tb}");
        let bounds = b.bounds();
        let corners: Vec<Vec3> = (0..8)
            .map(|c| {
                let pick = |bit: u32, lo: f32, hi: f32| if c & bit == 0 { lo } else { hi };
                vec3(
                    pick(1, bounds.min.x, bounds.max.x),
                    pick(2, bounds.min.y, bounds.max.y),
                    pick(4, bounds.min.z, bounds.max.z),
                )
            })
            .collect();
        for k in 0..300 {
            // A third centred on a corner of the wall (straddling two edges), the rest anywhere
            // around it; sizes from a fraction of a quad to most of the wall.
            let center = if k % 3 == 0 {
                corners[k % 8]
            } else {
                let t = vec3(uniform(), uniform(), uniform()) * 1.4 - Vec3::splat(0.2);
                bounds.min + t * bounds.size()
            };
            let size = bounds.diagonal() * (0.005 + 0.5 * uniform());
            let tolerance = |x: f64| 1e-5 * x + 1e-7;
            let cube = Aabb::cube(center, size);
            let (x, y) = (
                area_inside(&cube, a_set, &mut scratch),
                area_inside(&cube, b_set, &mut scratch),
            );
            assert!(
                (x - y).abs() <= tolerance(y),
                "map {m}, {cube:?}: merged {x}, per face {y}"
            );
            let ball = Ball::new(center, size);
            let (x, y) = (
                area_inside(&ball, a_set, &mut scratch),
                area_inside(&ball, b_set, &mut scratch),
            );
            assert!(
                (x - y).abs() <= tolerance(y),
                "map {m}, {ball:?}: merged {x}, per face {y}"
            );
        }
    }
}

#[test]
fn cube_and_ball_estimators_render_the_same_image_from_merged_and_per_face_maps() {
    let scene = scenes::build("split-rooms-10").unwrap();
    let assignment = CreaseAngle::default()
        .partition(scene.clone())
        .unwrap()
        .assignment()
        .clone();
    let photons = 20_000;
    let (merged, per_face) = (
        maps(&scene, &assignment, MapGeometry::Merged, photons),
        maps(&scene, &assignment, MapGeometry::PerFace, photons),
    );
    for kind in [EstimatorKind::GeometryCube, EstimatorKind::GeometryBall] {
        let settings = RenderSettings {
            width: 48,
            height: 48,
            photons,
            threads: 2,
            ..RenderSettings::default()
        };
        let renderer = Renderer::new(kind, settings);
        let a = renderer.render_image(&scene, Some(&merged), &()).unwrap();
        let b = renderer.render_image(&scene, Some(&per_face), &()).unwrap();
        assert!(b.mean().x > 0.0, "{kind}: a lit image");
        let mut worst = 0.0f32;
        for (pa, pb) in a.pixels().iter().zip(b.pixels()) {
            let diff = (*pa - *pb).abs().max_element();
            let relative = diff / (pb.abs().max_element() + 1e-3 * b.mean().x);
            worst = worst.max(relative);
        }
        eprintln!("{kind}: worst relative pixel difference {worst:e}");
        assert!(worst <= 1e-4, "{kind}: pixels differ by up to {worst:e} relative");
    }
}
