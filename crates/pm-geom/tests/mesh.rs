//! Half-edge mesh tests: a closed cube (shared and split vertices), non-manifold and
//! inconsistently wound edges, degenerate faces, bad input, and a never-panic property.

use pm_geom::glam::{Vec3, vec3};
use pm_geom::{FaceId, HalfEdgeId, HalfEdgeMesh, MeshError, MeshOptions};
use proptest::prelude::*;
use std::f32::consts::FRAC_PI_2;

/// Unit cube corners; corner `i` has x = bit 0, y = bit 1, z = bit 2.
fn cube_corners() -> Vec<Vec3> {
    (0..8)
        .map(|i| vec3((i & 1) as f32, ((i >> 1) & 1) as f32, ((i >> 2) & 1) as f32))
        .collect()
}

/// The six faces of the unit cube, counter-clockwise seen from outside.
const CUBE_FACES: [[u32; 4]; 6] = [
    [0, 2, 3, 1], // z = 0, normal -z
    [4, 5, 7, 6], // z = 1, normal +z
    [0, 1, 5, 4], // y = 0, normal -y
    [2, 6, 7, 3], // y = 1, normal +y
    [0, 4, 6, 2], // x = 0, normal -x
    [1, 3, 7, 5], // x = 1, normal +x
];

fn build(positions: &[Vec3], faces: &[impl AsRef<[u32]>]) -> HalfEdgeMesh {
    let mesh = HalfEdgeMesh::build(positions, faces, &MeshOptions::default()).expect("valid input");
    mesh.validate().expect("invariants hold");
    mesh
}

/// Number of undirected edges: twinned pairs count once, the rest once each.
fn edge_count(mesh: &HalfEdgeMesh) -> usize {
    let hes = mesh.half_edge_count() as u32;
    (0..hes)
        .map(HalfEdgeId)
        .filter(|&he| mesh.twin(he).is_none_or(|t| t.0 > he.0))
        .count()
}

fn assert_closed_cube(mesh: &HalfEdgeMesh) {
    assert_eq!(mesh.vertex_count(), 8);
    assert_eq!(mesh.face_count(), 6);
    assert_eq!(mesh.half_edge_count(), 24);
    assert_eq!(edge_count(mesh), 12);
    assert_eq!(mesh.boundary_edge_count(), 0);
    assert_eq!(mesh.non_manifold_edge_count(), 0);
    for he in (0..24).map(HalfEdgeId) {
        let twin = mesh.twin(he).expect("every cube edge is twinned");
        assert_eq!(mesh.origin(twin), mesh.target(he));
        let angle = mesh.crease_angle(he).unwrap();
        assert!((angle - FRAC_PI_2).abs() < 1e-6, "crease {angle}");
    }
    for face in mesh.faces() {
        assert!((mesh.face_area(face) - 1.0).abs() < 1e-6);
        assert_eq!(mesh.neighbours(face).count(), 4);
        // Outward normals: the face centre minus the cube centre points along the normal.
        let centre = mesh.face_polygon(face).sum::<Vec3>() / 4.0;
        assert!(
            (centre - Vec3::splat(0.5))
                .normalize()
                .dot(mesh.face_normal(face))
                > 0.999
        );
    }
}

#[test]
fn cube_of_six_quads_has_twelve_twinned_edges_with_right_angle_creases() {
    assert_closed_cube(&build(&cube_corners(), &CUBE_FACES));
}

#[test]
fn split_vertex_cube_welds_to_eight_vertices_and_same_topology() {
    let corners = cube_corners();
    let mut positions = Vec::new();
    let mut faces = Vec::new();
    for face in CUBE_FACES {
        let start = positions.len() as u32;
        // Exporter-style copies, off by less than the tolerance.
        positions.extend(face.iter().map(|&i| corners[i as usize] + Vec3::splat(3e-7)));
        faces.push([start, start + 1, start + 2, start + 3]);
    }
    assert_eq!(positions.len(), 24);
    let mesh = build(&positions, &faces);
    assert_closed_cube(&mesh);
    assert_eq!(
        (0..6).map(|f| mesh.source_face(FaceId(f))).collect::<Vec<_>>(),
        [0, 1, 2, 3, 4, 5]
    );
}

#[test]
fn split_vertex_cube_farther_apart_than_tolerance_stays_split() {
    let corners = cube_corners();
    // Copies of face f are shifted by (f + 1) mm: 1 mm apart, ten times the tolerance.
    let positions: Vec<Vec3> = CUBE_FACES
        .iter()
        .enumerate()
        .flat_map(|(f, face)| face.iter().map(move |&i| (i, f)))
        .map(|(i, f)| corners[i as usize] + Vec3::splat(1e-3 * (f + 1) as f32))
        .collect();
    let faces: Vec<[u32; 4]> = (0..6).map(|f| [4 * f, 4 * f + 1, 4 * f + 2, 4 * f + 3]).collect();
    let mesh = HalfEdgeMesh::build(&positions, &faces, &MeshOptions { weld_tolerance: 1e-4 }).unwrap();
    mesh.validate().unwrap();
    assert_eq!(mesh.vertex_count(), 24);
    assert_eq!(mesh.boundary_edge_count(), 24);
}

#[test]
fn three_faces_on_one_edge_make_it_non_manifold() {
    // Three fins around the edge (0,0,0)–(1,0,0).
    let positions = [
        vec3(0., 0., 0.),
        vec3(1., 0., 0.),
        vec3(0., 1., 0.),
        vec3(0., -1., 1.),
        vec3(0., -1., -1.),
    ];
    let faces = [[0u32, 1, 2], [1, 0, 3], [0, 1, 4]];
    let mesh = build(&positions, &faces);
    assert_eq!(mesh.non_manifold_edge_count(), 1);
    for face in mesh.faces() {
        let he = mesh.face_half_edges(face).find(|&he| {
            let (a, b) = (mesh.origin(he).0, mesh.target(he).0);
            a.min(b) == 0 && a.max(b) == 1
        });
        let he = he.expect("each fin uses the shared edge");
        assert!(mesh.is_non_manifold(he));
        assert_eq!(mesh.twin(he), None);
        assert_eq!(mesh.crease_angle(he), None);
        assert_eq!(mesh.neighbours(face).count(), 0, "no fin may join another");
    }
    assert_eq!(mesh.boundary_edge_count(), 6);
}

#[test]
fn inconsistent_winding_edge_is_non_manifold() {
    // Two triangles sharing edge 0–1, both running 0→1.
    let positions = [
        vec3(0., 0., 0.),
        vec3(1., 0., 0.),
        vec3(0., 1., 0.),
        vec3(0., -1., 0.),
    ];
    let mesh = build(&positions, &[[0u32, 1, 2], [0, 1, 3]]);
    assert_eq!(mesh.non_manifold_edge_count(), 1);
    assert!(mesh.is_non_manifold(HalfEdgeId(0)));
    assert_eq!(mesh.twin(HalfEdgeId(0)), None);
}

#[test]
fn coplanar_neighbours_have_zero_crease() {
    let positions = [
        vec3(0., 0., 0.),
        vec3(1., 0., 0.),
        vec3(1., 0., -1.),
        vec3(0., 0., -1.),
    ];
    let mesh = build(&positions, &[[0u32, 1, 2], [0, 2, 3]]);
    let shared = mesh
        .face_half_edges(FaceId(0))
        .find(|&he| mesh.twin(he).is_some())
        .unwrap();
    assert!(mesh.crease_angle(shared).unwrap().abs() < 1e-6);
    assert!((mesh.face_normal(FaceId(0)) - Vec3::Y).length() < 1e-6);
}

/// A cut piece of a sliver triangle (as the contact split makes on a real model: a kick plate
/// 2.26 m long and 55 mm high, its sharp corner 1.4°) has vertices on both edges near the sharp
/// corner, a few micrometres apart: welding brings them together, pinching the polygon. The
/// face stays, as its loop with area: its area is the polygon's less the collapsed sliver
/// (within the weld distance times its perimeter), not nothing.
#[test]
fn a_face_pinched_by_welding_keeps_its_area() {
    let positions = [
        vec3(1.126255, 0.0025149973, 0.0),
        vec3(1.126255, 0.055414, 0.0),
        vec3(-1.1321828, 0.055414, 0.0),
        vec3(-1.132296, 0.055414, 0.0),
        vec3(-1.1321828, 0.055411223, 0.0),
        vec3(-0.76929307, 0.04650765, 0.0),
        vec3(0.6822641, 0.010893408, 0.0),
        vec3(1.0237494, 0.0025149975, 0.0),
        // A far triangle, so that the mesh is 7 m across (the weld distance is capped at 10⁻⁶
        // of that).
        vec3(0.0, 0.0, 7.0),
        vec3(1.0, 0.0, 7.0),
        vec3(0.0, 1.0, 7.0),
    ];
    let faces: Vec<Vec<u32>> = vec![(0..8).collect(), vec![8, 9, 10]];
    let area = pm_geom::polygon_area(&positions[..8]);
    let mesh = HalfEdgeMesh::build(&positions, &faces, &MeshOptions { weld_tolerance: 7e-6 }).unwrap();
    mesh.validate().unwrap();
    assert!(
        mesh.vertex_count() < positions.len(),
        "the weld must pinch the face"
    );
    assert_eq!(mesh.dropped_face_count(), 0);
    let pinched: Vec<FaceId> = mesh.faces().filter(|&f| mesh.source_face(f) == 0).collect();
    let kept: f32 = pinched.iter().map(|&f| mesh.face_area(f)).sum();
    // Moving vertices by at most the weld distance changes the area by at most that distance
    // times the perimeter (about 4.6 m): 3.2e-5 against the 0.0624 m² face.
    assert!((kept - area).abs() <= 7e-6 * 4.6, "kept {kept} of {area}");
}

#[test]
fn degenerate_faces_are_dropped_counted_and_mapped() {
    let positions = [
        vec3(0., 0., 0.),
        vec3(1., 0., 0.),
        vec3(2., 0., 0.),
        vec3(0., 1., 0.),
        vec3(1e-9, 0., 0.),
    ];
    // Face 0: collinear. Face 1: fine. Face 2: collapses to 2 vertices after welding.
    // Face 3: consecutive duplicate removed, still a triangle.
    let faces: Vec<Vec<u32>> = vec![vec![0, 1, 2], vec![0, 1, 3], vec![0, 4, 1], vec![0, 0, 1, 3]];
    let mesh = HalfEdgeMesh::build(&positions, &faces, &MeshOptions { weld_tolerance: 1e-6 }).unwrap();
    mesh.validate().unwrap();
    assert_eq!(mesh.dropped_face_count(), 2);
    assert_eq!(mesh.face_count(), 2);
    assert_eq!(mesh.source_face(FaceId(0)), 1);
    assert_eq!(mesh.source_face(FaceId(1)), 3);
    assert_eq!(mesh.face_vertices(FaceId(1)).count(), 3);
}

#[test]
fn bad_input_gives_typed_errors() {
    let positions = [vec3(0., 0., 0.), vec3(1., 0., 0.), vec3(0., 1., 0.)];
    let opts = MeshOptions::default();
    assert_eq!(
        HalfEdgeMesh::build(&positions, &[[0u32, 1, 2], [0, 1, 7]], &opts).unwrap_err(),
        MeshError::IndexOutOfRange {
            face: 1,
            index: 7,
            vertex_count: 3
        }
    );
    assert_eq!(
        HalfEdgeMesh::build(&positions, &[vec![0u32, 1]], &opts).unwrap_err(),
        MeshError::TooFewVertices { face: 0, count: 2 }
    );
    let nan = [vec3(0., 0., 0.), vec3(f32::NAN, 0., 0.), vec3(0., 1., 0.)];
    assert!(matches!(
        HalfEdgeMesh::build(&nan, &[[0u32, 1, 2]], &opts),
        Err(MeshError::NonFinitePosition { vertex: 1, .. })
    ));
    let inf = [vec3(0., 0., f32::INFINITY)];
    assert!(matches!(
        HalfEdgeMesh::build(&inf, &[] as &[[u32; 3]], &opts),
        Err(MeshError::NonFinitePosition { vertex: 0, .. })
    ));
    let message = HalfEdgeMesh::build(&positions, &[[0u32, 1, 9]], &opts)
        .unwrap_err()
        .to_string();
    assert!(message.contains("face 0") && message.contains('9'), "{message}");
}

#[test]
fn empty_mesh_is_valid() {
    let mesh = build(&[], &[] as &[[u32; 3]]);
    assert_eq!(mesh.face_count(), 0);
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(256))]

    /// Arbitrary index lists over a few (possibly coincident) positions either fail with a
    /// typed error or build a mesh whose invariants hold.
    #[test]
    fn arbitrary_index_lists_never_panic(
        coords in prop::collection::vec((-2i8..3, -2i8..3, -2i8..3), 0..12),
        faces in prop::collection::vec(prop::collection::vec(0u32..14, 0..7), 0..12),
        tolerance in prop_oneof![Just(0.0f32), Just(1e-6), Just(0.6), Just(-1.0), Just(f32::NAN)],
    ) {
        let positions: Vec<Vec3> = coords.iter().map(|&(x, y, z)| vec3(x as f32, y as f32, z as f32) * 0.5).collect();
        if let Ok(mesh) = HalfEdgeMesh::build(&positions, &faces, &MeshOptions { weld_tolerance: tolerance }) {
            prop_assert_eq!(mesh.validate(), Ok(()));
            let sources = (0..mesh.face_count() as u32)
                .map(|f| mesh.source_face(FaceId(f)))
                .collect::<std::collections::BTreeSet<_>>()
                .len();
            prop_assert_eq!(sources + mesh.dropped_face_count(), faces.len());
            for he in (0..mesh.half_edge_count() as u32).map(HalfEdgeId) {
                if let Some(angle) = mesh.crease_angle(he) {
                    prop_assert!((0.0..=std::f32::consts::PI + 1e-6).contains(&angle));
                }
            }
        }
    }

    /// Arbitrary float positions, including non-finite ones, never panic.
    #[test]
    fn arbitrary_positions_never_panic(
        positions in prop::collection::vec(prop::array::uniform3(prop::num::f32::ANY), 0..10),
        faces in prop::collection::vec(prop::collection::vec(0u32..10, 3..6), 0..6),
    ) {
        let positions: Vec<Vec3> = positions.into_iter().map(Vec3::from_array).collect();
        if let Ok(mesh) = HalfEdgeMesh::build(&positions, &faces, &MeshOptions::default()) {
            prop_assert_eq!(mesh.validate(), Ok(()));
        }
    }
}

/// An `n × n` grid of unit quads written as a split-vertex soup (4 corners per quad).
fn split_grid(n: u32) -> (Vec<Vec3>, Vec<[u32; 4]>) {
    let mut positions = Vec::new();
    let mut faces = Vec::new();
    for i in 0..n {
        for j in 0..n {
            let (x, z) = (i as f32, j as f32);
            let s = positions.len() as u32;
            positions.extend([
                vec3(x, 0., z),
                vec3(x, 0., z + 1.),
                vec3(x + 1., 0., z + 1.),
                vec3(x + 1., 0., z),
            ]);
            faces.push([s, s + 1, s + 2, s + 3]);
        }
    }
    (positions, faces)
}

#[test]
fn split_grid_welds_to_the_grid_topology() {
    let n = 60;
    let (positions, faces) = split_grid(n);
    let mesh = build(&positions, &faces);
    let n = n as usize;
    assert_eq!(mesh.vertex_count(), (n + 1) * (n + 1));
    assert_eq!(mesh.boundary_edge_count(), 4 * n);
    let twinned = (0..mesh.half_edge_count() as u32)
        .filter(|&h| mesh.twin(HalfEdgeId(h)).is_some())
        .count();
    assert_eq!(twinned, 2 * 2 * n * (n - 1), "two half-edges per interior edge");
    assert!((mesh.faces().map(|f| mesh.face_area(f)).sum::<f32>() - (n * n) as f32).abs() < 1e-2);
    for face in mesh.faces() {
        assert!((mesh.face_normal(face) - Vec3::Y).length() < 1e-6);
    }
}

proptest! {
    /// Two unit squares hinged on the x axis, the second turned by `fold` about it: the
    /// crease angle is `fold` (0 = flat continuation).
    #[test]
    fn hinge_crease_angle_equals_fold_angle(fold in 0.0f32..3.0) {
        let (s, c) = fold.sin_cos();
        // Square A in z <= 0 of the plane y = 0; square B turned from z >= 0 by `fold`.
        let positions = [vec3(0., 0., 0.), vec3(1., 0., 0.), vec3(1., 0., -1.), vec3(0., 0., -1.),
            vec3(1., s, c), vec3(0., s, c)];
        let mesh = build(&positions, &[[0u32, 1, 2, 3], [1, 0, 5, 4]]);
        let hinge = mesh.face_half_edges(FaceId(0)).find(|&he| mesh.twin(he).is_some()).unwrap();
        let angle = mesh.crease_angle(hinge).unwrap();
        prop_assert!((angle - fold).abs() < 1e-5, "angle {angle}, fold {fold}");
        prop_assert_eq!(mesh.crease_angle(mesh.twin(hinge).unwrap()), Some(angle));
    }
}

#[test]
fn vertices_beyond_the_weld_grid_weld_only_when_identical() {
    // At 1e13 m the weld grid's cells no longer fit an i64; such vertices weld exactly when
    // they are equal. A strip of 20,000 triangles shares each vertex among three triangles.
    let n = 20_000u32;
    let positions: Vec<Vec3> = (0..n + 2)
        .map(|i| Vec3::new(1e13 + (i / 2) as f32 * 1e7, 1e13 + (i % 2) as f32 * 1e7, 0.0))
        .collect();
    // Each triangle repeats its vertices as a separate copy, as a soup would.
    let mut soup = Vec::new();
    let mut faces = Vec::new();
    for t in 0..n {
        let tri = if t % 2 == 0 {
            [t, t + 1, t + 2]
        } else {
            [t + 1, t, t + 2]
        };
        let start = soup.len() as u32;
        soup.extend(tri.iter().map(|&i| positions[i as usize]));
        faces.push([start, start + 1, start + 2]);
    }
    let mesh = HalfEdgeMesh::build(&soup, &faces, &MeshOptions::default()).unwrap();
    mesh.validate().unwrap();
    assert_eq!(mesh.vertex_count(), (n + 2) as usize);
    assert_eq!(mesh.face_count(), n as usize);
}
