//! Map partitions: crease-angle maps of the built-in scenes, a tessellated sphere, a ring,
//! and the single map.

mod common;

use pm_trace::glam::Vec3;
use pm_trace::{CreaseAngle, MapAssignment, PartId, Partitioner, Scene, SingleMap, Surface, scenes};

/// The x range of all polygons of each map.
fn x_ranges(scene: &Scene, maps: &MapAssignment) -> Vec<(f32, f32)> {
    maps.parts_per_map()
        .iter()
        .map(|parts| {
            let mut r = (f32::INFINITY, f32::NEG_INFINITY);
            for &p in parts {
                scene.for_each_part_polygon(p, |poly| {
                    for v in poly {
                        r = (r.0.min(v.x), r.1.max(v.x));
                    }
                });
            }
            r
        })
        .collect()
}

#[test]
fn lit_unlit_rooms_have_twelve_maps_none_spanning_both_rooms() {
    let scene = scenes::build("lit-unlit-rooms").unwrap();
    let maps = CreaseAngle::default()
        .partition(scene.clone())
        .unwrap()
        .assignment()
        .clone();
    assert_eq!(maps.map_count(), 12);
    for (lo, hi) in x_ranges(&scene, &maps) {
        assert!(hi <= 1.0 + 1e-6 || lo >= 1.02 - 1e-6, "a map spans x {lo}..{hi}");
    }
    assert_eq!(
        SingleMap
            .partition(scene.clone())
            .unwrap()
            .assignment()
            .clone()
            .map_count(),
        1
    );
}

#[test]
fn touching_rooms_share_the_floor_map_under_crease_maps() {
    let scene = scenes::build("touching-rooms").unwrap();
    let maps = CreaseAngle::default()
        .partition(scene.clone())
        .unwrap()
        .assignment()
        .clone();
    // Ten faces, all meeting at right angles or not at all: ten maps, the floor spans both rooms.
    assert_eq!(maps.map_count(), 10);
    assert!(
        x_ranges(&scene, &maps)
            .iter()
            .any(|&(lo, hi)| lo < 0.5 && hi > 1.5)
    );
}

#[test]
fn accordion_has_one_map_per_facet() {
    let scene = scenes::build("accordion").unwrap();
    assert_eq!(scene.part_count(), 8);
    assert_eq!(
        CreaseAngle::default()
            .partition(scene.clone())
            .unwrap()
            .assignment()
            .clone()
            .map_count(),
        8
    );
    // Folds are 90°: a threshold above that joins them all.
    assert_eq!(
        CreaseAngle {
            max_angle: 100f32.to_radians()
        }
        .partition(scene)
        .unwrap()
        .assignment()
        .map_count(),
        1
    );
}

#[test]
fn tessellated_sphere_is_one_map_and_ring_is_four() {
    let (positions, faces) = common::icosphere(Vec3::ZERO, 1.0, 2);
    let scene = Scene::builder()
        .mesh(&positions, &faces, Surface::diffuse(Vec3::ONE * 0.5))
        .ring(
            Vec3::new(3.0, 0.0, 0.0),
            Vec3::Y,
            0.5,
            1.0,
            0.2,
            Surface::diffuse(Vec3::ONE * 0.5),
        )
        .sphere(Vec3::new(-3.0, 0.0, 0.0), 1.0, Surface::diffuse(Vec3::ONE * 0.5))
        .build()
        .unwrap();
    let maps = CreaseAngle::default()
        .partition(scene.clone())
        .unwrap()
        .assignment()
        .clone();
    assert_eq!(maps.map_count(), 1 + 4 + 1);
    let sphere_mesh_map = maps.map_of(PartId(0));
    assert!((0..320).all(|f| maps.map_of(PartId(f)) == sphere_mesh_map));
    let ring_maps: std::collections::BTreeSet<u32> = (320..324).map(|p| maps.map_of(PartId(p))).collect();
    assert_eq!(ring_maps.len(), 4);
    assert!(!ring_maps.contains(&sphere_mesh_map));
}

#[test]
fn cornell_box_walls_light_sphere_and_ring_get_their_own_maps() {
    let scene = scenes::build("cornell-box").unwrap();
    // 5 walls + light quad + sphere + 4 ring sides.
    assert_eq!(scene.part_count(), 11);
    assert_eq!(
        CreaseAngle::default()
            .partition(scene.clone())
            .unwrap()
            .assignment()
            .clone()
            .map_count(),
        11
    );
}

#[test]
fn photons_land_in_the_map_of_the_surface_they_hit_in_every_built_in_scene() {
    use pm_trace::{PhotonMaps, TraceOptions, trace_photons};
    for name in scenes::NAMES {
        let scene = scenes::build(name).unwrap();
        for maps in [
            CreaseAngle::default()
                .partition(scene.clone())
                .unwrap()
                .assignment()
                .clone(),
            SingleMap.partition(scene.clone()).unwrap().assignment().clone(),
        ] {
            let traced = trace_photons(
                &scene,
                &maps,
                &TraceOptions {
                    photons: 20_000,
                    seed: 3,
                    max_bounces: 32,
                    pass: 0,
                },
            )
            .unwrap();
            let stored = traced.stats().total_stored();
            let built = PhotonMaps::build(&scene, &maps, traced).unwrap();
            built.validate().unwrap_or_else(|e| panic!("{name}: {e}"));
            assert_eq!(built.len(), maps.map_count() as usize);
            assert_eq!(built.iter().map(|m| m.tree().len() as u64).sum::<u64>(), stored);
            // Every map holds its parts' polygons: the geometry estimator needs them.
            for (m, parts) in maps.parts_per_map().iter().enumerate() {
                let mut area = 0.0;
                for &p in parts {
                    scene.for_each_part_polygon(p, |poly| area += pm_geom::polygon_area(poly));
                }
                let got = built.map(m as u32).geometry().total_area();
                assert!(
                    (got - area).abs() <= 1e-4 * area.max(1.0),
                    "{name} map {m}: {got} vs {area}"
                );
            }
        }
    }
}
