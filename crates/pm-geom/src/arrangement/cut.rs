//! Cutting one convex face along the lines where other faces meet it into convex pieces, with
//! the contact points inserted on the new edges so that the meeting face's edge is shared after
//! welding.

use glam::Vec3;

/// A cut of one face: a line in the face's plane and the contact points on it.
#[derive(Clone, Debug)]
pub(super) struct Cut {
    pub(super) point: Vec3,
    pub(super) direction: Vec3,
    pub(super) contacts: Vec<Vec3>,
}

/// Adds a cut through `c0`–`c1`, merging it with an existing cut along the same line.
pub(super) fn add_cut(cuts: &mut Vec<Cut>, c0: Vec3, c1: Vec3, tolerance: f32) {
    let Some(direction) = (c1 - c0).try_normalize() else {
        return;
    };
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
pub(super) fn apply_cut(
    pieces: Vec<Vec<Vec3>>,
    cut: &Cut,
    face_normal: Vec3,
    tolerance: f32,
) -> Vec<Vec<Vec3>> {
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
pub(super) fn insert_points_on_edges(polygon: &mut Vec<Vec3>, points: &[Vec3], tolerance: f32) {
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
