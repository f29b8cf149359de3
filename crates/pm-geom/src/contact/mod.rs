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

mod cut;
#[cfg(test)]
mod tests;

use crate::bounds_bvh::BoundsBvh;
use crate::{Aabb, polygon_vector_area};
use cut::{apply_cut, insert_points_on_edges};
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
