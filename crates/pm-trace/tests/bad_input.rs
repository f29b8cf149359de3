//! Bad input gives typed errors (or documented handling), never a panic.

use pm_trace::glam::Vec3;
use pm_trace::{
    CreaseAngle, Hit, MAX_SCENE_TRIANGLES, Partitioner, PhotonMaps, PointLight, Ray, RayKind, Scene,
    SceneError, SingleMap, Surface, TraceError, TraceOptions, scenes, trace_photons,
};

fn quad() -> [Vec3; 4] {
    [
        Vec3::new(0.0, 0.0, 0.0),
        Vec3::new(0.0, 0.0, 1.0),
        Vec3::new(1.0, 0.0, 1.0),
        Vec3::new(1.0, 0.0, 0.0),
    ]
}

fn grey() -> Surface {
    Surface::diffuse(Vec3::splat(0.5))
}

#[test]
fn tracing_without_photons_lights_or_power_is_an_error() {
    let dark = Scene::builder()
        .mesh(&quad(), &[[0u32, 1, 2, 3]], grey())
        .build()
        .unwrap();
    let maps = SingleMap.partition(dark.clone()).unwrap().assignment().clone();
    let opts = TraceOptions::default();
    assert_eq!(trace_photons(&dark, &maps, &opts), Err(TraceError::NoLights));

    let zero = Scene::builder()
        .mesh(&quad(), &[[0u32, 1, 2, 3]], grey())
        .light(PointLight::new(Vec3::Y, Vec3::ZERO))
        .build()
        .unwrap();
    assert!(matches!(
        trace_photons(&zero, &maps, &opts),
        Err(TraceError::InvalidPower { light: 1, .. })
    ));
    assert_eq!(
        trace_photons(&zero, &maps, &TraceOptions { photons: 0, ..opts }),
        Err(TraceError::ZeroPhotons)
    );

    // A light with NaN power is refused when the scene is built, naming the light.
    let nan = Scene::builder()
        .mesh(&quad(), &[[0u32, 1, 2, 3]], grey())
        .light(PointLight::new(Vec3::Y, Vec3::splat(1.0)))
        .light(PointLight::new(Vec3::Y, Vec3::new(f32::NAN, 1.0, 1.0)))
        .build()
        .unwrap_err();
    assert!(matches!(nan, SceneError::InvalidLight { light: 1, .. }), "{nan}");
    assert!(nan.to_string().contains("light 1"), "{nan}");
}

#[test]
fn an_assignment_for_another_scene_is_an_error() {
    let small = Scene::builder()
        .mesh(&quad(), &[[0u32, 1, 2, 3]], grey())
        .light(PointLight::new(Vec3::Y, Vec3::ONE))
        .build()
        .unwrap();
    let cornell = scenes::build("cornell-box").unwrap();
    let maps = CreaseAngle::default()
        .partition(cornell.clone())
        .unwrap()
        .assignment()
        .clone();
    assert!(matches!(
        trace_photons(&small, &maps, &TraceOptions::default()),
        Err(TraceError::AssignmentMismatch {
            assigned: 11,
            parts: 1
        })
    ));
    let own = SingleMap.partition(small.clone()).unwrap().assignment().clone();
    let traced = trace_photons(
        &small,
        &own,
        &TraceOptions {
            photons: 100,
            ..TraceOptions::default()
        },
    )
    .unwrap();
    assert!(PhotonMaps::build(&small, &maps, traced).is_err());
}

#[test]
fn invalid_geometry_is_a_typed_error_naming_the_culprit() {
    let bad_index = Scene::builder().mesh(&quad(), &[[0u32, 1, 7]], grey()).build();
    assert!(matches!(bad_index, Err(SceneError::Mesh { mesh: 0, .. })));
    let nan = [Vec3::ZERO, Vec3::X, Vec3::new(f32::NAN, 0.0, 1.0)];
    assert!(matches!(
        Scene::builder().mesh(&nan, &[[0u32, 1, 2]], grey()).build(),
        Err(SceneError::Mesh { .. })
    ));
    let zero_radius = Scene::builder().sphere(Vec3::ZERO, 0.0, grey()).build();
    assert!(matches!(
        zero_radius,
        Err(SceneError::InvalidShape { shape: 0, .. })
    ));
    let ring = Scene::builder()
        .ring(Vec3::ZERO, Vec3::Y, 2.0, 1.0, 0.1, grey())
        .build();
    assert!(matches!(ring, Err(SceneError::InvalidShape { shape: 0, .. })));
    let no_axis = Scene::builder()
        .ring(Vec3::ZERO, Vec3::ZERO, 0.5, 1.0, 0.1, grey())
        .build();
    assert!(matches!(no_axis, Err(SceneError::InvalidShape { .. })));
    assert!(matches!(Scene::builder().build(), Err(SceneError::NoGeometry)));
    let bright = Surface::diffuse(Vec3::splat(1.5));
    assert!(matches!(
        Scene::builder().sphere(Vec3::ZERO, 1.0, bright).build(),
        Err(SceneError::InvalidSurface { .. })
    ));
    let counts = Scene::builder()
        .mesh_per_face(&quad(), &[[0u32, 1, 2, 3]], &[grey(), grey()])
        .build();
    assert!(matches!(
        counts,
        Err(SceneError::SurfaceCount {
            surfaces: 2,
            faces: 1,
            ..
        })
    ));
}

#[test]
fn zero_area_faces_are_dropped_and_a_fully_degenerate_mesh_means_no_geometry() {
    let p = [
        Vec3::ZERO,
        Vec3::X,
        Vec3::new(2.0, 0.0, 0.0),
        Vec3::new(0.0, 0.0, 1.0),
    ];
    // Face 0 is collinear (zero area), face 1 is fine.
    let scene = Scene::builder()
        .mesh(&p, &[[0u32, 1, 2], [0, 3, 1]], grey())
        .build()
        .unwrap();
    assert_eq!(scene.part_count(), 1);
    assert_eq!(scene.meshes()[0].half_edge_mesh().dropped_face_count(), 1);
    let none = Scene::builder().mesh(&p, &[[0u32, 1, 2]], grey()).build();
    assert!(matches!(none, Err(SceneError::NoGeometry)));
}

#[test]
fn unknown_scene_names_list_the_valid_ones() {
    let err = scenes::build("cornel-box").unwrap_err();
    let msg = err.to_string();
    for name in scenes::NAMES {
        assert!(msg.contains(name), "{msg}");
    }
}

#[test]
fn rays_with_non_finite_input_miss_instead_of_panicking() {
    let scene = scenes::build("cornell-box").unwrap();
    let weird = [
        Ray {
            origin: Vec3::splat(f32::NAN),
            direction: Vec3::Z,
        },
        Ray {
            origin: Vec3::ZERO,
            direction: Vec3::ZERO,
        },
        Ray {
            origin: Vec3::splat(f32::INFINITY),
            direction: Vec3::X,
        },
    ];
    for r in weird {
        let _: Option<Hit> = scene.intersect(&r, f32::INFINITY, RayKind::Other);
    }
    assert!(!scene.occluded(Vec3::splat(f32::NAN), Vec3::ONE));
}

#[test]
fn map_assignments_accept_any_ids_and_renumber_them() {
    use pm_trace::{MapAssignment, PartId};
    let dense = MapAssignment::new(vec![0, 1, 1]);
    assert_eq!(dense.map_count(), 2);
    let sparse = MapAssignment::new(vec![7, u32::MAX, 7, 3]);
    assert_eq!(sparse.map_count(), 3, "three distinct ids, three maps");
    let maps: Vec<u32> = (0..4).map(|p| sparse.map_of(PartId(p))).collect();
    assert_eq!(maps, [0, 1, 0, 2], "renumbered in order of first appearance");
    assert!(sparse.parts_per_map().iter().all(|parts| !parts.is_empty()));
    let empty = MapAssignment::new(Vec::new());
    assert_eq!(
        (empty.part_count(), empty.map_count()),
        (0, 1),
        "no parts, one empty map"
    );
}

#[test]
fn a_scene_past_its_triangle_limit_is_refused_before_building() {
    // Two quads = 4 triangles (fan-triangulated), against limits of 3 and 4.
    let positions = [quad(), quad().map(|p| p + Vec3::Y)].concat();
    let faces = [[0u32, 1, 2, 3], [4, 5, 6, 7]];
    let build = |limit| {
        Scene::builder()
            .mesh(&positions, &faces, grey())
            .light(PointLight::new(Vec3::new(0.0, 3.0, 0.0), Vec3::ONE))
            .max_triangles(limit)
            .build()
    };
    match build(3) {
        Err(
            e @ SceneError::TooManyTriangles {
                triangles: 4,
                limit: 3,
            },
        ) => {
            assert!(e.to_string().contains("4 triangles"), "{e}");
        }
        other => panic!("{other:?}"),
    }
    assert!(build(4).is_ok());
    // Past the library's own limit, the limit asked for is capped.
    assert!(build(usize::MAX).is_ok());
}

#[test]
fn a_mesh_declaring_a_billion_empty_faces_is_refused_without_allocating_for_them() {
    // Zero-sized faces cost the caller nothing; the builder must not reserve per face.
    let faces = vec![[0u32; 0]; 1_000_000_000];
    let quad = quad();
    match Scene::builder()
        .mesh(&quad, &faces, grey())
        .light(PointLight::new(Vec3::new(0.0, 3.0, 0.0), Vec3::ONE))
        .build()
    {
        Err(SceneError::Mesh {
            mesh: 0,
            source: pm_geom::MeshError::TooFewVertices { face: 0, count: 0 },
        }) => {}
        other => panic!("{other:?}"),
    }
    // A face past the triangle limit is refused before the faces are copied.
    let big = vec![0u32; MAX_SCENE_TRIANGLES + 3];
    match Scene::builder()
        .mesh(&quad, &[big.as_slice()], grey())
        .light(PointLight::new(Vec3::new(0.0, 3.0, 0.0), Vec3::ONE))
        .build()
    {
        Err(SceneError::TooManyTriangles { triangles, limit }) => {
            assert_eq!((triangles, limit), (MAX_SCENE_TRIANGLES + 1, MAX_SCENE_TRIANGLES));
        }
        other => panic!("{other:?}"),
    }
}
