//! Faces that stand on others, against hand-made cases: walls on floors, boxes on tables,
//! doorways.

use super::*;
use crate::polygon_area;
use glam::vec3;

/// The arrangement with a 10 µm tolerance and no gap.
fn split<P: AsRef<[Vec3]> + Sync>(polygons: &[P]) -> Arrangement {
    split_polygons_at_intersections(polygons, &[], &ArrangementOptions::new(1e-5, 1e-5))
        .expect("within bounds")
}

fn quad(a: Vec3, b: Vec3, c: Vec3, d: Vec3) -> Vec<Vec3> {
    vec![a, b, c, d]
}

/// A 3 × 3 floor in y = 0 and the four sides of a unit box standing on its middle.
pub(super) fn floor_with_box() -> Vec<Vec<Vec3>> {
    let floor = quad(
        vec3(0.0, 0.0, 0.0),
        vec3(0.0, 0.0, 3.0),
        vec3(3.0, 0.0, 3.0),
        vec3(3.0, 0.0, 0.0),
    );
    let (lo, hi) = (1.0, 2.0);
    vec![
        floor,
        quad(
            vec3(lo, 0.0, lo),
            vec3(lo, 0.0, hi),
            vec3(lo, 1.0, hi),
            vec3(lo, 1.0, lo),
        ),
        quad(
            vec3(hi, 0.0, lo),
            vec3(hi, 1.0, lo),
            vec3(hi, 1.0, hi),
            vec3(hi, 0.0, hi),
        ),
        quad(
            vec3(lo, 0.0, lo),
            vec3(lo, 1.0, lo),
            vec3(hi, 1.0, lo),
            vec3(hi, 0.0, lo),
        ),
        quad(
            vec3(lo, 0.0, hi),
            vec3(hi, 0.0, hi),
            vec3(hi, 1.0, hi),
            vec3(lo, 1.0, hi),
        ),
    ]
}

/// A floor 2 × 1 in y = 0 facing up, and a wall in x = 1 standing on it over `z0..z1`.
fn floor_and_wall(z0: f32, z1: f32) -> Vec<Vec<Vec3>> {
    let floor = quad(
        vec3(0.0, 0.0, 0.0),
        vec3(0.0, 0.0, 1.0),
        vec3(2.0, 0.0, 1.0),
        vec3(2.0, 0.0, 0.0),
    );
    let wall = quad(
        vec3(1.0, 0.0, z0),
        vec3(1.0, 1.0, z0),
        vec3(1.0, 1.0, z1),
        vec3(1.0, 0.0, z1),
    );
    vec![floor, wall]
}

#[test]
fn full_width_wall_cuts_the_floor_in_two() {
    let split = split(&floor_and_wall(0.0, 1.0));
    assert_eq!(split.counts.meetings(), 1);
    assert_eq!(split.source, vec![0, 0, 1]);
    let areas: Vec<f32> = split.polygons.iter().map(|p| polygon_area(p)).collect();
    assert!(
        (areas[0] - 1.0).abs() < 1e-6 && (areas[1] - 1.0).abs() < 1e-6,
        "{areas:?}"
    );
}

#[test]
fn partial_wall_inserts_its_end_points_into_the_cut() {
    let split = split(&floor_and_wall(0.25, 0.75));
    assert_eq!(split.polygons.len(), 3);
    for half in &split.polygons[..2] {
        // 4 corners + the two contact points on the cut edge.
        assert_eq!(half.len(), 6, "{half:?}");
        assert!(half.iter().any(|p| p.distance(vec3(1.0, 0.0, 0.25)) < 1e-6));
        assert!(half.iter().any(|p| p.distance(vec3(1.0, 0.0, 0.75)) < 1e-6));
    }
    let total: f32 = split.polygons[..2].iter().map(|p| polygon_area(p)).sum();
    assert!((total - 2.0).abs() < 1e-6);
}

#[test]
fn wall_on_the_floor_border_is_not_a_contact() {
    let floor = quad(
        vec3(0.0, 0.0, 0.0),
        vec3(0.0, 0.0, 1.0),
        vec3(2.0, 0.0, 1.0),
        vec3(2.0, 0.0, 0.0),
    );
    let wall = quad(
        vec3(0.0, 0.0, 0.0),
        vec3(0.0, 1.0, 0.0),
        vec3(0.0, 1.0, 1.0),
        vec3(0.0, 0.0, 1.0),
    );
    let split = split(&[floor, wall]);
    assert_eq!(split.counts.meetings(), 0);
    assert_eq!(split.polygons.len(), 2);
}

#[test]
fn wall_above_the_floor_is_not_a_contact() {
    let mut input = floor_and_wall(0.0, 1.0);
    for p in &mut input[1] {
        p.y += 0.01;
    }
    assert_eq!(split(&input).counts.meetings(), 0);
}

/// The first side cuts the whole floor; each later side cuts only the pieces its own segment
/// runs through (not the 3 × 3 grid full lines would make).
#[test]
fn box_on_a_floor_cuts_five_pieces_and_keeps_the_area() {
    let input = floor_with_box();
    let split = split(&input);
    let floor_pieces: Vec<&Vec<Vec3>> = split
        .polygons
        .iter()
        .zip(&split.source)
        .filter(|(_, s)| **s == 0)
        .map(|(p, _)| p)
        .collect();
    assert_eq!(floor_pieces.len(), 5);
    let total: f32 = floor_pieces.iter().map(|p| polygon_area(p)).sum();
    assert!((total - 9.0).abs() < 1e-5, "{total}");
}

/// Welds the pieces into one half-edge mesh, as a partition would.
pub(super) fn mesh_of(polygons: &[Vec<Vec3>]) -> crate::HalfEdgeMesh {
    let positions: Vec<Vec3> = polygons.iter().flatten().copied().collect();
    let mut faces = Vec::new();
    let mut start = 0u32;
    for p in polygons {
        faces.push((start..start + p.len() as u32).collect::<Vec<u32>>());
        start += p.len() as u32;
    }
    let mesh = crate::HalfEdgeMesh::build(&positions, &faces, &crate::MeshOptions { weld_tolerance: 1e-5 })
        .expect("valid input");
    mesh.validate().expect("valid mesh");
    mesh
}

/// For each point on the floor (y = 0, input polygon 0), the group of floor pieces it lies
/// in, where groups are pieces connected across twinned, flat edges.
fn floor_groups_at(split: &Arrangement, points: &[Vec3]) -> Vec<usize> {
    let mesh = mesh_of(&split.polygons);
    assert_eq!(mesh.face_count(), split.polygons.len());
    groups_at(
        &mesh,
        points,
        |face| split.source[mesh.source_face(face)] == 0,
        |he| mesh.crease_angle(he).is_some_and(|a| a < 0.5),
    )
}

/// For each point (in y = 0, seen from above), the group of the face of `mesh` it lies in among
/// the faces `holds` accepts, where groups are faces connected across the twinned edges that
/// `joins` accepts.
pub(super) fn groups_at(
    mesh: &crate::HalfEdgeMesh,
    points: &[Vec3],
    holds: impl Fn(crate::FaceId) -> bool,
    joins: impl Fn(crate::HalfEdgeId) -> bool,
) -> Vec<usize> {
    let mut group: Vec<usize> = (0..mesh.face_count()).collect();
    fn find(group: &mut [usize], mut i: usize) -> usize {
        while group[i] != i {
            group[i] = group[group[i]];
            i = group[i];
        }
        i
    }
    for face in mesh.faces() {
        for (he, other) in mesh.neighbours(face) {
            if joins(he) {
                let (a, b) = (
                    find(&mut group, face.0 as usize),
                    find(&mut group, other.0 as usize),
                );
                group[a] = b;
            }
        }
    }
    let inside = |poly: &[Vec3], p: Vec3| {
        (0..poly.len()).all(|i| {
            let (a, b) = (poly[i], poly[(i + 1) % poly.len()]);
            (b - a).cross(p - a).y >= 0.0
        })
    };
    points
        .iter()
        .map(|&p| {
            let face = mesh
                .faces()
                .find(|&f| holds(f) && inside(&mesh.face_polygon(f).collect::<Vec<_>>(), p))
                .expect("point on the floor");
            find(&mut group, face.0 as usize)
        })
        .collect()
}

/// A 0.02 m thick wall across the floor at x = 1, standing on it over each `z` span.
fn thick_wall(spans: &[(f32, f32)]) -> Vec<Vec<Vec3>> {
    let mut out = vec![quad(
        vec3(0.0, 0.0, 0.0),
        vec3(0.0, 0.0, 1.0),
        vec3(2.0, 0.0, 1.0),
        vec3(2.0, 0.0, 0.0),
    )];
    for &(z0, z1) in spans {
        let (x0, x1) = (1.0, 1.02);
        out.push(quad(
            vec3(x0, 0.0, z0),
            vec3(x0, 1.0, z0),
            vec3(x0, 1.0, z1),
            vec3(x0, 0.0, z1),
        ));
        out.push(quad(
            vec3(x1, 0.0, z0),
            vec3(x1, 0.0, z1),
            vec3(x1, 1.0, z1),
            vec3(x1, 1.0, z0),
        ));
        out.push(quad(
            vec3(x0, 0.0, z0),
            vec3(x1, 0.0, z0),
            vec3(x1, 1.0, z0),
            vec3(x0, 1.0, z0),
        ));
        out.push(quad(
            vec3(x0, 0.0, z1),
            vec3(x0, 1.0, z1),
            vec3(x1, 1.0, z1),
            vec3(x1, 0.0, z1),
        ));
    }
    out
}

#[test]
fn full_width_wall_separates_the_floor_halves() {
    let split = split(&thick_wall(&[(0.0, 1.0)]));
    let [left, under, right] = floor_groups_at(
        &split,
        &[vec3(0.5, 0.0, 0.5), vec3(1.01, 0.0, 0.5), vec3(1.5, 0.0, 0.5)],
    )[..] else {
        unreachable!()
    };
    assert!(left != right && left != under && under != right);
}

#[test]
fn doorway_keeps_the_floor_one_group() {
    let split = split(&thick_wall(&[(0.0, 0.4), (0.6, 1.0)]));
    let groups = floor_groups_at(
        &split,
        &[
            vec3(0.5, 0.0, 0.1),
            vec3(1.01, 0.0, 0.5),
            vec3(1.5, 0.0, 0.9),
            vec3(1.01, 0.0, 0.2),
        ],
    );
    // Both rooms and the doorway are one group; the floor under the wall is cut out.
    assert_eq!(groups[0], groups[1]);
    assert_eq!(groups[1], groups[2]);
    assert_ne!(groups[3], groups[0]);
    let total: f32 = split
        .polygons
        .iter()
        .zip(&split.source)
        .filter(|(_, s)| **s == 0)
        .map(|(p, _)| polygon_area(p))
        .sum();
    assert!((total - 2.0).abs() < 1e-5, "{total}");
}

#[test]
fn box_on_a_floor_cuts_out_its_footprint_only() {
    let input = floor_with_box();
    let split = split(&input);
    // The pieces around the box are one group; the footprint is cut out.
    let around = [
        vec3(0.5, 0.0, 0.5),
        vec3(1.5, 0.0, 0.5),
        vec3(2.5, 0.0, 2.5),
        vec3(0.5, 0.0, 1.5),
    ];
    let mut groups = floor_groups_at(&split, &around);
    groups.dedup();
    assert_eq!(groups.len(), 1);
    assert_ne!(floor_groups_at(&split, &[vec3(1.5, 0.0, 1.5)])[0], groups[0]);
}

/// A 10 m floor under 300 small squares hovering 1 mm over it, facing it, at random places and
/// angles: each square's outline gives the floor four cut lines of its own. Past
/// `max_cut_lines_per_polygon` lines the split is refused, naming the floor, before the
/// merging of cuts along lines (a search through the floor's lines per new cut) grows with
/// their square; within the default bound it splits.
#[test]
fn a_floor_under_a_field_of_hovering_squares_is_bounded_in_its_cut_lines() {
    let floor = vec![
        vec3(0.0, 0.0, 0.0),
        vec3(0.0, 0.0, 10.0),
        vec3(10.0, 0.0, 10.0),
        vec3(10.0, 0.0, 0.0),
    ];
    let mut next = test_stream::stream();
    let mut input = vec![floor];
    for _ in 0..300 {
        let (x, z, turn) = (
            0.5 + 9.0 * next(),
            0.5 + 9.0 * next(),
            next() * std::f32::consts::FRAC_PI_2,
        );
        let (c, s) = (turn.cos() * 0.05, turn.sin() * 0.05);
        // Wound to face down, towards the floor.
        input.push(
            [(-1.0, -1.0), (1.0, -1.0), (1.0, 1.0), (-1.0, 1.0)]
                .iter()
                .map(|&(u, v): &(f32, f32)| vec3(x + u * c - v * s, 0.001, z + u * s + v * c))
                .collect(),
        );
    }
    let options = ArrangementOptions::new(1e-5, 0.01);
    let split = split_polygons_at_intersections(&input, &[], &options).expect("within the default bound");
    assert!(split.counts.meetings() >= 300, "{:?}", split.counts);
    let bounded = ArrangementOptions {
        max_cut_lines_per_polygon: 500,
        ..options
    };
    assert_eq!(
        split_polygons_at_intersections(&input, &[], &bounded).err(),
        Some(ArrangementError::TooManyCutLines {
            polygon: 0,
            limit: 500
        })
    );
}
