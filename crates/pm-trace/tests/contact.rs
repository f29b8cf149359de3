//! The contact-aware partition: faces touching without sharing an edge never join a map where
//! they touch, and the floor stays one map where light really passes (a doorway, around a box).

mod common;

use pm_trace::glam::Vec3;
use pm_trace::{
    Contact, CreaseAngle, MapAssignment, PartSource, Partitioned, Partitioner, PointLight, Ray, RayKind,
    Scene, SceneBuilder, Surface, TraceOptions, scenes, trace_photons,
};

/// The map of the surface straight below `(x, 0.5, z)`.
fn map_below(scene: &Scene, maps: &MapAssignment, x: f32, z: f32) -> u32 {
    let ray = Ray::new(Vec3::new(x, 0.5, z), Vec3::new(1e-4, -1.0, 1e-4).normalize());
    let hit = scene
        .intersect(&ray, 10.0, RayKind::Other)
        .expect("the floor is below");
    assert!(hit.position.y.abs() < 1e-4, "hit the floor, not {hit:?}");
    maps.map_of(hit.part)
}

/// Total area of the scene's mesh faces.
fn mesh_area(scene: &Scene) -> f64 {
    scene
        .meshes()
        .iter()
        .map(|m| {
            m.half_edge_mesh()
                .faces()
                .map(|f| m.half_edge_mesh().face_area(f) as f64)
                .sum::<f64>()
        })
        .sum()
}

#[test]
fn touching_rooms_floor_splits_into_one_map_per_room() {
    let scene = scenes::build("touching-rooms").unwrap();
    let crease = CreaseAngle::default().partition(scene.clone()).unwrap();
    let crease = crease.assignment();
    assert_eq!(
        map_below(&scene, crease, 0.5, 0.5),
        map_below(&scene, crease, 1.5, 0.5),
        "the scene must test the case"
    );

    let area_before = mesh_area(&scene);
    let contact = Contact::default().partition(scene).unwrap();
    let (split, maps) = (contact.scene(), contact.assignment());
    for mesh in split.meshes() {
        mesh.half_edge_mesh().validate().unwrap();
    }
    assert!(
        (mesh_area(split) - area_before).abs() < 1e-6 * area_before,
        "the split keeps the area"
    );
    assert_ne!(map_below(split, maps, 0.5, 0.5), map_below(split, maps, 1.5, 0.5));
    // No map reaches into both rooms.
    for parts in maps.parts_per_map() {
        let (mut lo, mut hi) = (f32::INFINITY, f32::NEG_INFINITY);
        for p in parts {
            split.for_each_part_polygon(p, |poly| {
                let c = poly.iter().copied().sum::<Vec3>() / poly.len() as f32;
                lo = lo.min(c.x);
                hi = hi.max(c.x);
            });
        }
        assert!(hi <= 1.0 + 1e-4 || lo >= 1.0 - 1e-4, "a map spans x {lo}..{hi}");
        assert!(hi <= 1.02 + 1e-4 || lo >= 1.02 - 1e-4, "a map spans x {lo}..{hi}");
    }
}

/// A 2 × 1 floor and a 0.02 m wall across it at x = 1 standing on it over each `z` span, as
/// separate meshes, with a light in the left half.
fn floor_with_wall(spans: &[(f32, f32)]) -> Scene {
    let p = Vec3::new;
    let floor = [
        p(0.0, 0.0, 0.0),
        p(0.0, 0.0, 1.0),
        p(2.0, 0.0, 1.0),
        p(2.0, 0.0, 0.0),
    ];
    let white = Surface::diffuse(Vec3::splat(0.5));
    let mut builder = Scene::builder().mesh(&floor, &[[0u32, 1, 2, 3]], white);
    for &(z0, z1) in spans {
        let (x0, x1) = (1.0, 1.02);
        let wall = [
            p(x0, 0.0, z0),
            p(x0, 1.0, z0),
            p(x0, 1.0, z1),
            p(x0, 0.0, z1),
            p(x1, 0.0, z0),
            p(x1, 1.0, z0),
            p(x1, 1.0, z1),
            p(x1, 0.0, z1),
        ];
        let faces = [
            [0u32, 1, 2, 3],
            [4, 7, 6, 5],
            [0, 4, 5, 1],
            [3, 2, 6, 7],
            [1, 5, 6, 2],
        ];
        builder = builder.mesh(&wall, &faces, white);
    }
    lit_by_the_left_room_s_lamp(builder)
}

/// The scene of `builder` with a point lamp above the left room's floor.
fn lit_by_the_left_room_s_lamp(builder: SceneBuilder) -> Scene {
    builder
        .light(PointLight::new(Vec3::new(0.5, 0.5, 0.5), Vec3::splat(10.0)))
        .build()
        .unwrap()
}

#[test]
fn full_width_wall_splits_the_floor_into_two_maps() {
    let contact = Contact::default()
        .partition(floor_with_wall(&[(0.0, 1.0)]))
        .unwrap();
    let (scene, maps) = (contact.scene(), contact.assignment());
    assert_ne!(map_below(scene, maps, 0.5, 0.5), map_below(scene, maps, 1.5, 0.5));
}

#[test]
fn doorway_keeps_the_floor_one_map() {
    let contact = Contact::default()
        .partition(floor_with_wall(&[(0.0, 0.4), (0.6, 1.0)]))
        .unwrap();
    let (scene, maps) = (contact.scene(), contact.assignment());
    let left = map_below(scene, maps, 0.5, 0.1);
    assert_eq!(
        left,
        map_below(scene, maps, 1.5, 0.9),
        "light passes through the doorway"
    );
    assert_eq!(
        left,
        map_below(scene, maps, 1.01, 0.5),
        "the doorway's floor joins both rooms"
    );
}

#[test]
fn box_on_a_floor_is_cut_out_and_the_floor_around_it_stays_one_map() {
    let p = Vec3::new;
    let white = Surface::diffuse(Vec3::splat(0.5));
    let floor = [
        p(0.0, 0.0, 0.0),
        p(0.0, 0.0, 3.0),
        p(3.0, 0.0, 3.0),
        p(3.0, 0.0, 0.0),
    ];
    let (lo, hi) = (1.0, 2.0);
    let corners = [
        p(lo, 0.0, lo),
        p(hi, 0.0, lo),
        p(hi, 0.0, hi),
        p(lo, 0.0, hi),
        p(lo, 1.0, lo),
        p(hi, 1.0, lo),
        p(hi, 1.0, hi),
        p(lo, 1.0, hi),
    ];
    // Outward normals: bottom, top, x = lo, x = hi, z = lo, z = hi.
    let faces = [
        [0u32, 1, 2, 3],
        [4, 7, 6, 5],
        [0, 3, 7, 4],
        [1, 5, 6, 2],
        [0, 4, 5, 1],
        [3, 2, 6, 7],
    ];
    let scene = Scene::builder()
        .mesh(&floor, &[[0u32, 1, 2, 3]], white)
        .mesh(&corners, &faces, white)
        .light(PointLight::new(p(1.5, 2.0, 1.5), Vec3::splat(10.0)))
        .build()
        .unwrap();
    let contact = Contact::default().partition(scene).unwrap();
    let (split, maps) = (contact.scene(), contact.assignment());
    let around = [(0.5, 0.5), (1.5, 0.5), (2.5, 2.5), (0.5, 1.5), (2.5, 1.5)];
    let m = map_below(split, maps, 0.5, 0.5);
    for (x, z) in around {
        assert_eq!(map_below(split, maps, x, z), m, "floor at ({x}, {z})");
    }
    // Under the box: the floor piece there is in no map of the floor around it.
    let under: Vec<u32> = (0..split.part_count() as u32)
        .map(pm_trace::PartId)
        .filter(|&part| matches!(split.part_source(part), PartSource::MeshFace { mesh: 0, .. }))
        .filter(|&part| {
            let mut inside = false;
            split.for_each_part_polygon(part, |poly| {
                let c = poly.iter().copied().sum::<Vec3>() / poly.len() as f32;
                inside = (1.0..2.0).contains(&c.x) && (1.0..2.0).contains(&c.z);
            });
            inside
        })
        .map(|part| maps.map_of(part))
        .collect();
    assert_eq!(under.len(), 1);
    assert_ne!(under[0], m);
}

#[test]
fn splitting_keeps_the_traced_power() {
    let scene = scenes::build("touching-rooms").unwrap();
    let options = TraceOptions {
        photons: 20_000,
        seed: 7,
        ..TraceOptions::default()
    };
    let crease = CreaseAngle::default().partition(scene).unwrap();
    let before = trace_photons(crease.scene(), crease.assignment(), &options).unwrap();
    let contact = Contact::default()
        .partition(scenes::build("touching-rooms").unwrap())
        .unwrap();
    let after = trace_photons(contact.scene(), contact.assignment(), &options).unwrap();
    let (a, b) = (
        common::stored_power(&before, None),
        common::stored_power(&after, None),
    );
    // The same seed and the same surfaces: the same paths up to float rounding at the cuts.
    let relative = ((a - b).abs() / a).max_element();
    assert!(relative < 1e-3, "stored power {a} before, {b} after the split");
}

#[test]
fn contact_maps_come_only_with_the_split_scene() {
    let scene = scenes::build("touching-rooms").unwrap();
    let parts = scene.part_count();
    let contact = Contact::default().partition(scene.clone()).unwrap();
    let record = contact
        .record()
        .expect("the contact partition keeps what it found");
    assert!(record.counts().in_plane > 0, "{:?}", record.counts());
    // Every meeting came from a candidate pair, and the partition's time is its steps' sum.
    assert!(record.counts().candidate_pairs >= record.counts().meetings());
    let phases = record.phases();
    assert_eq!(record.seconds(), phases.total(), "{phases:?}");
    assert!(
        phases.arrangement.meetings > 0.0 && phases.fill > 0.0,
        "{phases:?}"
    );
    // The maps are the split scene's: they cover its parts, not the scene as built.
    assert!(contact.scene().part_count() > parts);
    assert_eq!(contact.assignment().part_count(), contact.scene().part_count());
    // The same scene split twice gives the same scene and maps.
    let again = Contact::default().partition(scene.clone()).unwrap();
    assert_eq!(again.assignment(), contact.assignment());
    assert_eq!(again.scene().part_count(), contact.scene().part_count());
    // The crease-angle partition leaves the scene as it is and has no record.
    let crease = CreaseAngle::default().partition(scene).unwrap();
    assert!(crease.record().is_none());
    assert_eq!(crease.scene().part_count(), parts);
}

/// The six outward quads of the box `[lo, hi]` as one closed mesh: the unit room, scaled,
/// turned inside out.
fn solid_box(lo: Vec3, hi: Vec3) -> (Vec<Vec3>, Vec<[u32; 4]>) {
    let (unit, inward) = common::unit_box();
    let corners = unit.iter().map(|&c| lo + c * (hi - lo)).collect();
    let faces = inward
        .into_iter()
        .map(|mut f| {
            f.reverse();
            f
        })
        .collect();
    (corners, faces)
}

#[test]
fn bar_pushed_into_a_cube_seals_its_end_and_reports_four_barriers() {
    // A bar [0.5, 1.5]² × [−1, 1] enters the cube [0, 2]³ through its face z = 0 and ends
    // inside it: the four sides of the entry square are the meeting lines, and the bar's end
    // face at z = 1 (never cut) lies inside the cube with the bar's sides from z = 0 to 1.
    let white = Surface::diffuse(Vec3::splat(0.5));
    let (cube, cube_faces) = solid_box(Vec3::ZERO, Vec3::splat(2.0));
    let (bar, bar_faces) = solid_box(Vec3::new(0.5, 0.5, -1.0), Vec3::new(1.5, 1.5, 1.0));
    let scene = Scene::builder()
        .mesh(&cube, &cube_faces, white)
        .mesh(&bar, &bar_faces, white)
        .light(PointLight::new(Vec3::new(1.0, 1.0, -3.0), Vec3::splat(10.0)))
        .build()
        .unwrap();
    let contact = Contact::default().partition(scene).unwrap();
    let record = contact.record().unwrap();
    assert_eq!(record.barriers().len(), 4, "{:?}", record.barriers().segments());
    let split = contact.scene();
    let mut sealed_area = [0.0f64; 2];
    let mut end_sealed = false;
    for (m, mesh) in split.meshes().iter().enumerate() {
        let half_edges = mesh.half_edge_mesh();
        for face in half_edges.faces() {
            let part = mesh.part_of_face(face);
            if !record.is_sealed(part) {
                continue;
            }
            sealed_area[m] += half_edges.face_area(face) as f64;
            end_sealed |= half_edges.face_polygon(face).all(|p| (p.z - 1.0).abs() < 1e-6);
        }
    }
    assert!(end_sealed, "the bar's end face lies inside the cube");
    // Cube: its face z = 0 inside the bar's square (1 m²); bar: four sides (4 m²) and the end.
    assert!((sealed_area[0] - 1.0).abs() < 1e-4, "{sealed_area:?}");
    assert!((sealed_area[1] - 5.0).abs() < 1e-4, "{sealed_area:?}");
}

/// Every piece of the split scene names the face it came from; per source face, the pieces'
/// areas sum to the face's area and every piece keeps its surface.
fn pieces_tile_their_source_faces(name: &str) {
    let scene = scenes::build(name).unwrap();
    let contact = Contact::default().partition(scene.clone()).unwrap();
    let record = contact.record().unwrap();
    assert!(
        record.counts().meetings() > 0,
        "{name}: the scene must test the case"
    );
    assert_eq!(record.counts().duplicate_pieces, 0, "{name}: no copies dropped");
    let split = contact.scene();
    let mut area: std::collections::BTreeMap<pm_trace::SourceFace, f64> = Default::default();
    for p in 0..split.part_count() as u32 {
        let part = pm_trace::PartId(p);
        let Some(source) = contact.source_face(part) else {
            assert!(!matches!(split.part_source(part), PartSource::MeshFace { .. }));
            continue;
        };
        let original = scene.meshes()[source.mesh as usize].half_edge_mesh();
        let face = original
            .faces()
            .find(|&f| original.source_face(f) == source.face as usize)
            .expect("the source face is in the scene as built");
        let original_part = scene.meshes()[source.mesh as usize].part_of_face(face);
        assert_eq!(
            split.part_surface(part),
            scene.part_surface(original_part),
            "{name}: {source:?}"
        );
        let PartSource::MeshFace { mesh, face: piece } = split.part_source(part) else {
            panic!("a mesh part")
        };
        *area.entry(source).or_default() +=
            split.meshes()[mesh as usize].half_edge_mesh().face_area(piece) as f64;
    }
    // Every face of the scene as built is tiled by its pieces.
    let mut faces = 0;
    for (m, mesh) in scene.meshes().iter().enumerate() {
        let half_edges = mesh.half_edge_mesh();
        for face in half_edges.faces() {
            let source = pm_trace::SourceFace {
                mesh: m as u32,
                face: half_edges.source_face(face) as u32,
            };
            assert_eq!(scene.source_face(mesh.part_of_face(face)), Some(source));
            let whole = half_edges.face_area(face) as f64;
            let pieces = area.get(&source).copied().unwrap_or(0.0);
            assert!(
                (pieces - whole).abs() <= 1e-5 * whole.max(1.0),
                "{name}: {source:?} {pieces} of {whole}"
            );
            faces += 1;
        }
    }
    assert_eq!(area.len(), faces, "{name}: no piece names a face the scene lacks");
}

#[test]
fn pieces_of_each_face_tile_it_and_keep_its_surface() {
    for name in [
        "touching-rooms",
        "solid-rooms-pierce",
        "solid-rooms-stand",
        "solid-rooms-sunk-box",
    ] {
        pieces_tile_their_source_faces(name);
    }
}

#[test]
fn source_faces_without_a_split_are_the_scene_s_own() {
    let scene = scenes::build("cornell-box").unwrap();
    let crease = CreaseAngle::default().partition(scene.clone()).unwrap();
    for p in 0..scene.part_count() as u32 {
        let part = pm_trace::PartId(p);
        assert_eq!(crease.source_face(part), scene.source_face(part));
        assert_eq!(
            scene.source_face(part).is_some(),
            matches!(scene.part_source(part), PartSource::MeshFace { .. })
        );
    }
}

/// A floor of two meshes (two materials) meeting along `x = 1` without sharing vertices, and
/// walls standing across it at `x = 1` over `spans` of z.
fn two_mesh_floor_with_wall(spans: &[(f32, f32)]) -> Scene {
    let p = Vec3::new;
    let half = |x0: f32, x1: f32| [p(x0, 0.0, 0.0), p(x0, 0.0, 1.0), p(x1, 0.0, 1.0), p(x1, 0.0, 0.0)];
    let (white, grey) = (
        Surface::diffuse(Vec3::splat(0.5)),
        Surface::diffuse(Vec3::splat(0.3)),
    );
    let mut builder = Scene::builder()
        .mesh(&half(0.0, 1.0), &[[0u32, 1, 2, 3]], white)
        .mesh(&half(1.0, 2.0), &[[0u32, 1, 2, 3]], grey);
    for &(z0, z1) in spans {
        // A thin closed box whose face at x = 1 stands on the meshes' common edge (closed,
        // so that its own open edges do not make the common edge non-manifold).
        let (wall, faces) = solid_box(p(1.0, 0.0, z0), p(1.02, 1.0, z1));
        builder = builder.mesh(&wall, &faces, white);
    }
    lit_by_the_left_room_s_lamp(builder)
}

/// Faces of different meshes that share a flat edge (welded across the meshes) share a map,
/// which the crease maps never do; a wall standing on that edge keeps them apart, and a
/// doorway in it lets them join again.
#[test]
fn meshes_sharing_a_flat_edge_share_a_map_unless_a_wall_stands_on_it() {
    // Whether the floor below (x, z) = `left` and below `right` share a map.
    let shared = |partitioned: Partitioned, left: (f32, f32), right: (f32, f32)| {
        let (scene, maps) = (partitioned.scene(), partitioned.assignment());
        map_below(scene, maps, left.0, left.1) == map_below(scene, maps, right.0, right.1)
    };
    let (left, right) = ((0.5, 0.5), (1.5, 0.5));
    let floor = two_mesh_floor_with_wall(&[]);
    let crease = CreaseAngle::default().partition(floor.clone()).unwrap();
    assert!(!shared(crease, left, right), "crease maps stay within a mesh");
    let contact = Contact::default().partition(floor).unwrap();
    assert!(
        shared(contact, left, right),
        "the two meshes join across their common flat edge"
    );
    let walled = Contact::default()
        .partition(two_mesh_floor_with_wall(&[(0.0, 1.0)]))
        .unwrap();
    assert!(
        !shared(walled, left, right),
        "a wall on the common edge keeps the meshes apart"
    );
    let doorway = Contact::default()
        .partition(two_mesh_floor_with_wall(&[(0.0, 0.4), (0.6, 1.0)]))
        .unwrap();
    assert!(
        shared(doorway, (0.5, 0.1), (1.5, 0.9)),
        "light passes through the doorway between the meshes"
    );
}
