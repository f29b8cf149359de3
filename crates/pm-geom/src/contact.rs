//! Contact splitting: faces that touch without sharing an edge (a wall standing on a floor
//! that runs under it, a box resting on a table) are cut so that they do share one.
//!
//! For every edge of a face *A* that lies in the plane of another face *B* and crosses *B*'s
//! interior, *B* is cut along the edge's line into convex pieces, and the contact points are
//! inserted as vertices on both sides, so that after welding the contact segment is one edge
//! used by *A* and by the pieces of *B* on either side of it: an edge of three or more faces,
//! which a half-edge mesh reports as non-manifold and a photon-map partition never crosses.
//! Where the cut line runs beyond the contact (a doorway, the floor around a box), the pieces of
//! *B* share ordinary two-face edges and stay connected.

use crate::bounds_bvh::BoundsBvh;
use crate::{Aabb, polygon_vector_area};
use glam::Vec3;

/// The result of [`split_polygons_at_contacts`].
#[derive(Clone, Debug, Default, PartialEq)]
pub struct ContactSplit {
    /// The output polygons: every input polygon, cut into convex pieces where it is touched,
    /// with extra collinear vertices where other pieces' vertices lie on its edges.
    pub polygons: Vec<Vec<Vec3>>,
    /// For each output polygon, the index of the input polygon it came from.
    pub source: Vec<usize>,
    /// Number of (edge, touched face) contacts found.
    pub contact_count: usize,
}

/// A cut of one face: a line in the face's plane and the contact points on it.
#[derive(Clone, Debug)]
struct Cut {
    point: Vec3,
    direction: Vec3,
    contacts: Vec<Vec3>,
}

/// The plane and bounds of one input polygon.
#[derive(Clone, Copy, Debug)]
struct FaceFrame {
    normal: Vec3,
    offset: f32,
    bounds: Aabb,
}

/// Finds every contact between the convex planar `polygons` and cuts the touched ones.
///
/// `tolerance` is the distance (metres) under which a point counts as lying on a plane, a line
/// or another point; a good choice is `1e-5` times the scene's bounding-box diagonal, and the
/// mesh that is built from the output should weld vertices with a tolerance no larger than it.
/// Degenerate polygons (zero area) are passed through unchanged and never touched. The total
/// area of each input polygon is preserved by its pieces (up to float rounding).
///
/// Candidate pairs are found through a bounding-volume hierarchy over the polygon bounds, so
/// the cost grows with the number of overlapping bounds, not with the square of the polygon
/// count.
pub fn split_polygons_at_contacts<P: AsRef<[Vec3]>>(polygons: &[P], tolerance: f32) -> ContactSplit {
    let tolerance = tolerance.max(0.0);
    let frames: Vec<Option<FaceFrame>> = polygons
        .iter()
        .map(|p| face_frame(p.as_ref(), tolerance))
        .collect();

    // Cuts per touched face, and the contact relation (for the T-junction pass).
    let mut cuts: Vec<Vec<Cut>> = vec![Vec::new(); polygons.len()];
    let mut touching: Vec<(usize, usize)> = Vec::new();
    let mut contact_count = 0;
    for (a, b) in overlapping_pairs(&frames) {
        for (edge_face, touched) in [(a, b), (b, a)] {
            let Some(touched_frame) = frames[touched] else {
                continue;
            };
            let edge_poly = polygons[edge_face].as_ref();
            let touched_poly = polygons[touched].as_ref();
            for i in 0..edge_poly.len() {
                let (p, q) = (edge_poly[i], edge_poly[(i + 1) % edge_poly.len()]);
                if let Some((c0, c1)) = contact_segment(p, q, touched_poly, &touched_frame, tolerance) {
                    add_cut(&mut cuts[touched], c0, c1, tolerance);
                    touching.push((edge_face, touched));
                    contact_count += 1;
                }
            }
        }
    }

    // Cut every touched face into pieces.
    let mut pieces: Vec<Vec<Vec3>> = Vec::with_capacity(polygons.len());
    let mut source = Vec::with_capacity(polygons.len());
    let mut first_piece = Vec::with_capacity(polygons.len() + 1);
    for (index, polygon) in polygons.iter().enumerate() {
        first_piece.push(pieces.len());
        let polygon = polygon.as_ref();
        match frames[index] {
            Some(frame) if !cuts[index].is_empty() => {
                let mut current = vec![polygon.to_vec()];
                for cut in &cuts[index] {
                    current = apply_cut(current, cut, frame.normal, tolerance);
                }
                source.extend(std::iter::repeat_n(index, current.len()));
                pieces.extend(current);
            }
            _ => {
                pieces.push(polygon.to_vec());
                source.push(index);
            }
        }
    }
    first_piece.push(pieces.len());

    // Resolve T-junctions between faces in contact: a vertex of one lying inside an edge of the
    // other becomes a vertex of both, so that the contact segment is one shared edge.
    touching.sort_unstable();
    touching.dedup();
    let mut insertions: Vec<Vec<Vec3>> = vec![Vec::new(); pieces.len()];
    for &(a, b) in &touching {
        for (from, to) in [(a, b), (b, a)] {
            let donors = &pieces[first_piece[from]..first_piece[from + 1]];
            for target in &mut insertions[first_piece[to]..first_piece[to + 1]] {
                donors.iter().for_each(|donor| target.extend_from_slice(donor));
            }
        }
    }
    for (piece, extra) in pieces.iter_mut().zip(&insertions) {
        if !extra.is_empty() {
            insert_points_on_edges(piece, extra, tolerance);
        }
    }

    ContactSplit {
        polygons: pieces,
        source,
        contact_count,
    }
}

/// The plane and bounds of a polygon, `None` when it is degenerate or not finite.
fn face_frame(polygon: &[Vec3], tolerance: f32) -> Option<FaceFrame> {
    if polygon.len() < 3 || polygon.iter().any(|p| !p.is_finite()) {
        return None;
    }
    let normal = polygon_vector_area(polygon).try_normalize()?;
    let offset = normal.dot(polygon[0]);
    let bounds = Aabb::from_points(polygon);
    let pad = Vec3::splat(tolerance);
    Some(FaceFrame {
        normal,
        offset,
        bounds: Aabb::new(bounds.min - pad, bounds.max + pad),
    })
}

/// Pairs `(i, j)`, `i < j`, of non-degenerate faces whose padded bounds overlap, found through
/// a bounding-volume hierarchy over the bounds (a sweep along one axis degrades to all pairs
/// for a finely tessellated wall in a plane of that axis).
fn overlapping_pairs(frames: &[Option<FaceFrame>]) -> Vec<(usize, usize)> {
    let faces: Vec<(usize, Aabb)> = frames
        .iter()
        .enumerate()
        .filter_map(|(i, f)| f.map(|f| (i, f.bounds)))
        .collect();
    let boxes: Vec<Aabb> = faces.iter().map(|&(_, b)| b).collect();
    let bvh = BoundsBvh::build(&boxes);
    let mut pairs = Vec::new();
    for (n, &(i, bounds)) in faces.iter().enumerate() {
        bvh.for_each_candidate(&bounds, |m| {
            let (j, other) = faces[m as usize];
            if m as usize > n && bounds.overlaps(&other) {
                pairs.push((i.min(j), i.max(j)));
            }
        });
    }
    pairs.sort_unstable();
    pairs
}

/// The part of segment `pq` that lies in the touched polygon's plane and crosses its interior:
/// `None` when the segment is off the plane, misses the polygon, or only runs along its border.
fn contact_segment(
    p: Vec3,
    q: Vec3,
    polygon: &[Vec3],
    frame: &FaceFrame,
    tolerance: f32,
) -> Option<(Vec3, Vec3)> {
    let (dp, dq) = (
        frame.normal.dot(p) - frame.offset,
        frame.normal.dot(q) - frame.offset,
    );
    if dp.abs() > tolerance || dq.abs() > tolerance {
        return None;
    }
    let (p, q) = (p - frame.normal * dp, q - frame.normal * dq);
    if p.distance(q) <= tolerance {
        return None;
    }
    // Clip the segment's parameter range against every edge's inward half-plane, once exactly
    // (for the contact's end points) and once shrunk by the tolerance (to require interior).
    let (mut t0, mut t1) = (0.0f32, 1.0f32);
    let (mut s0, mut s1) = (0.0f32, 1.0f32);
    for i in 0..polygon.len() {
        let (a, b) = (polygon[i], polygon[(i + 1) % polygon.len()]);
        let Some(inward) = frame.normal.cross(b - a).try_normalize() else {
            continue;
        };
        let (fp, fq) = (inward.dot(p - a), inward.dot(q - a));
        clip_range(fp, fq, &mut t0, &mut t1);
        clip_range(fp - tolerance, fq - tolerance, &mut s0, &mut s1);
    }
    let length = p.distance(q);
    if t1 <= t0 || (s1 - s0) * length <= tolerance {
        return None;
    }
    Some((p.lerp(q, t0), p.lerp(q, t1)))
}

/// Narrows `[t0, t1]` to where the linear function from `fp` (t = 0) to `fq` (t = 1) is ≥ 0.
fn clip_range(fp: f32, fq: f32, t0: &mut f32, t1: &mut f32) {
    if fp < 0.0 && fq < 0.0 {
        *t1 = -1.0;
    } else if fp < 0.0 {
        *t0 = t0.max(fp / (fp - fq));
    } else if fq < 0.0 {
        *t1 = t1.min(fp / (fp - fq));
    }
}

/// Adds a cut through `c0`–`c1`, merging it with an existing cut along the same line.
fn add_cut(cuts: &mut Vec<Cut>, c0: Vec3, c1: Vec3, tolerance: f32) {
    let direction = (c1 - c0).normalize();
    let on_line =
        |cut: &Cut, p: Vec3| (p - cut.point).reject_from_normalized(cut.direction).length() <= tolerance;
    if let Some(cut) = cuts.iter_mut().find(|cut| on_line(cut, c0) && on_line(cut, c1)) {
        cut.contacts.extend([c0, c1]);
    } else {
        cuts.push(Cut {
            point: c0,
            direction,
            contacts: vec![c0, c1],
        });
    }
}

/// Cuts every piece crossed by the cut's line in two, adding the cut's contact points to the
/// new edge on both sides.
fn apply_cut(pieces: Vec<Vec<Vec3>>, cut: &Cut, face_normal: Vec3, tolerance: f32) -> Vec<Vec<Vec3>> {
    let Some(side) = face_normal.cross(cut.direction).try_normalize() else {
        return pieces;
    };
    let offset = side.dot(cut.point);
    let mut out = Vec::with_capacity(pieces.len() + 1);
    for piece in pieces {
        let distances: Vec<f32> = piece.iter().map(|&p| side.dot(p) - offset).collect();
        let has_front = distances.iter().any(|&d| d > tolerance);
        let has_back = distances.iter().any(|&d| d < -tolerance);
        if !(has_front && has_back) {
            out.push(piece);
            continue;
        }
        let (mut front, mut back) = (Vec::new(), Vec::new());
        split_by_line(&piece, &distances, tolerance, &mut front, &mut back);
        for mut half in [front, back] {
            if half.len() >= 3 {
                insert_points_on_edges(&mut half, &cut.contacts, tolerance);
                out.push(half);
            }
        }
    }
    out
}

/// Splits a convex polygon by the signed `distances` of its vertices to a plane; vertices
/// within the tolerance of the plane go to both sides.
fn split_by_line(
    polygon: &[Vec3],
    distances: &[f32],
    tolerance: f32,
    front: &mut Vec<Vec3>,
    back: &mut Vec<Vec3>,
) {
    let n = polygon.len();
    for i in 0..n {
        let j = (i + 1) % n;
        let (p, dp, dq) = (polygon[i], distances[i], distances[j]);
        if dp.abs() <= tolerance {
            front.push(p);
            back.push(p);
            continue;
        }
        if dp > 0.0 {
            front.push(p)
        } else {
            back.push(p)
        }
        let crosses = (dp > tolerance && dq < -tolerance) || (dp < -tolerance && dq > tolerance);
        if crosses {
            let x = p.lerp(polygon[j], dp / (dp - dq));
            front.push(x);
            back.push(x);
        }
    }
}

/// Inserts each point of `points` that lies strictly inside an edge of `polygon` (within the
/// tolerance) into that edge, in order along it; points at existing vertices are skipped.
fn insert_points_on_edges(polygon: &mut Vec<Vec3>, points: &[Vec3], tolerance: f32) {
    let mut result = Vec::with_capacity(polygon.len() + points.len());
    let mut on_edge: Vec<(f32, Vec3)> = Vec::new();
    let n = polygon.len();
    for i in 0..n {
        let (a, b) = (polygon[i], polygon[(i + 1) % n]);
        result.push(a);
        let length = a.distance(b);
        if length <= tolerance {
            continue;
        }
        let direction = (b - a) / length;
        on_edge.clear();
        for &p in points {
            let t = (p - a).dot(direction);
            if t > tolerance
                && t < length - tolerance
                && (p - a).reject_from_normalized(direction).length() <= tolerance
            {
                on_edge.push((t, a + direction * t));
            }
        }
        on_edge.sort_by(|x, y| x.0.total_cmp(&y.0));
        on_edge.dedup_by(|x, y| x.0 - y.0 <= tolerance);
        result.extend(on_edge.iter().map(|&(_, p)| p));
    }
    *polygon = result;
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::polygon_area;
    use glam::vec3;

    fn quad(a: Vec3, b: Vec3, c: Vec3, d: Vec3) -> Vec<Vec3> {
        vec![a, b, c, d]
    }

    /// A 3 × 3 floor in y = 0 and the four sides of a unit box standing on its middle.
    fn floor_with_box() -> Vec<Vec<Vec3>> {
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
        let split = split_polygons_at_contacts(&floor_and_wall(0.0, 1.0), 1e-5);
        assert_eq!(split.contact_count, 1);
        assert_eq!(split.source, vec![0, 0, 1]);
        let areas: Vec<f32> = split.polygons.iter().map(|p| polygon_area(p)).collect();
        assert!(
            (areas[0] - 1.0).abs() < 1e-6 && (areas[1] - 1.0).abs() < 1e-6,
            "{areas:?}"
        );
    }

    #[test]
    fn partial_wall_inserts_its_end_points_into_the_cut() {
        let split = split_polygons_at_contacts(&floor_and_wall(0.25, 0.75), 1e-5);
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
        let split = split_polygons_at_contacts(&[floor, wall], 1e-5);
        assert_eq!(split.contact_count, 0);
        assert_eq!(split.polygons.len(), 2);
    }

    #[test]
    fn wall_above_the_floor_is_not_a_contact() {
        let mut input = floor_and_wall(0.0, 1.0);
        for p in &mut input[1] {
            p.y += 0.01;
        }
        assert_eq!(split_polygons_at_contacts(&input, 1e-5).contact_count, 0);
    }

    #[test]
    fn box_on_a_floor_cuts_nine_pieces_and_keeps_the_area() {
        let input = floor_with_box();
        let split = split_polygons_at_contacts(&input, 1e-5);
        let floor_pieces: Vec<&Vec<Vec3>> = split
            .polygons
            .iter()
            .zip(&split.source)
            .filter(|(_, s)| **s == 0)
            .map(|(p, _)| p)
            .collect();
        assert_eq!(floor_pieces.len(), 9);
        let total: f32 = floor_pieces.iter().map(|p| polygon_area(p)).sum();
        assert!((total - 9.0).abs() < 1e-5, "{total}");
    }

    /// Welds the pieces into one half-edge mesh, as a partition would.
    fn mesh_of(polygons: &[Vec<Vec3>]) -> crate::HalfEdgeMesh {
        let positions: Vec<Vec3> = polygons.iter().flatten().copied().collect();
        let mut faces = Vec::new();
        let mut start = 0u32;
        for p in polygons {
            faces.push((start..start + p.len() as u32).collect::<Vec<u32>>());
            start += p.len() as u32;
        }
        let mesh =
            crate::HalfEdgeMesh::build(&positions, &faces, &crate::MeshOptions { weld_tolerance: 1e-5 })
                .expect("valid input");
        mesh.validate().expect("valid mesh");
        mesh
    }

    /// For each point on the floor (y = 0, input polygon 0), the group of floor pieces it lies
    /// in, where groups are pieces connected across twinned, flat edges.
    fn floor_groups_at(split: &ContactSplit, points: &[Vec3]) -> Vec<usize> {
        let mesh = mesh_of(&split.polygons);
        assert_eq!(mesh.face_count(), split.polygons.len());
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
                if mesh.crease_angle(he).is_some_and(|a| a < 0.5) {
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
                    .find(|&f| {
                        split.source[mesh.source_face(f)] == 0
                            && inside(&mesh.face_polygon(f).collect::<Vec<_>>(), p)
                    })
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
        let split = split_polygons_at_contacts(&thick_wall(&[(0.0, 1.0)]), 1e-5);
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
        let split = split_polygons_at_contacts(&thick_wall(&[(0.0, 0.4), (0.6, 1.0)]), 1e-5);
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
        let split = split_polygons_at_contacts(&input, 1e-5);
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
}
