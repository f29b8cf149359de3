//! Pieces inside closed solids: a ray from each piece counts how often it leaves and enters
//! every other closed solid (signed by the solid's outward normals); a piece with a winding
//! number of at least one in some solid lies where no light reaches. Every piece of a cut face
//! is tested, and so is every uncut face within the bounds of another outward solid: a face
//! wholly inside a solid meets none of its faces, so it is never cut.

use super::face::Face;
use crate::aabb::Aabb;
use crate::bounds_bvh::BoundsBvh;
use crate::polygon::polygon_area;
use glam::Vec3;

/// A direction off every axis and diagonal, added to the piece's normal so that the ray does
/// not run along the edges of axis-aligned geometry.
const SKEW: Vec3 = Vec3::new(1.31e-3, 2.87e-3, 1.73e-3);

/// Sets `sealed[p]` for each piece that lies inside a closed solid other than its own.
pub(super) fn mark_sealed(
    pieces: &[Vec<Vec3>],
    source: &[usize],
    was_cut: &[bool],
    solids: &[Option<u32>],
    faces: &[Option<Face>],
    tolerance: f32,
    sealed: &mut [bool],
) {
    let boxes: Vec<Aabb> = faces
        .iter()
        .map(|f| f.as_ref().map_or(Aabb::EMPTY, |f| Aabb::from_points(f.vertices)))
        .collect();
    let everything = boxes
        .iter()
        .filter(|b| !b.is_empty())
        .fold(Aabb::EMPTY, |a, &b| a.union(b));
    let reach = everything.diagonal() * 2.0;
    let live: Vec<u32> = (0..boxes.len() as u32)
        .filter(|&i| faces[i as usize].is_some() && solids.get(i as usize).copied().flatten().is_some())
        .collect();
    let live_boxes: Vec<Aabb> = live.iter().map(|&i| boxes[i as usize]).collect();
    let bvh = BoundsBvh::build_sah(&live_boxes, crate::bounds_bvh::MAX_LEAF);
    let outward = OutwardSolids::new(solids, faces, &boxes);
    let mut winding: Vec<(u32, i32)> = Vec::new();
    for (p, piece) in pieces.iter().enumerate() {
        let s = source[p];
        let Some(own) = &faces[s] else { continue };
        let own_solid = solids.get(s).copied().flatten();
        if !was_cut[s] && !outward.may_hold(&boxes[s], own_solid) {
            continue;
        }
        let start = piece.iter().copied().sum::<Vec3>() / piece.len() as f32;
        let direction = (own.normal + SKEW).normalize();
        let end = start + direction * reach;
        let ray_box = Aabb::from_points(&[start, end]);
        winding.clear();
        bvh.for_each_candidate(&ray_box, |m| {
            let k = live[m as usize] as usize;
            let solid = solids[k].expect("live faces bound solids");
            if Some(solid) == own_solid || k == s || !live_boxes[m as usize].overlaps(&ray_box) {
                return;
            }
            let Some(face) = &faces[k] else { return };
            if let Some(sign) = crossing(face, start, direction, tolerance) {
                match winding.iter_mut().find(|(id, _)| *id == solid) {
                    Some((_, w)) => *w += sign,
                    None => winding.push((solid, sign)),
                }
            }
        });
        sealed[p] = winding.iter().any(|&(_, w)| w >= 1);
    }
}

/// The bounds of every closed solid wound outwards (positive volume), to find the uncut faces
/// worth a ray: a room, wound inwards, holds every face in it and seals none.
struct OutwardSolids {
    ids: Vec<u32>,
    boxes: Vec<Aabb>,
    bvh: BoundsBvh,
}

impl OutwardSolids {
    fn new(solids: &[Option<u32>], faces: &[Option<Face>], boxes: &[Aabb]) -> Self {
        // Per solid: its bounds and six times its signed volume (Σ offset · area · 2).
        let mut found: Vec<(u32, Aabb, f64)> = Vec::new();
        for ((solid, face), b) in solids.iter().zip(faces).zip(boxes) {
            let (Some(solid), Some(face)) = (solid, face) else {
                continue;
            };
            let volume = f64::from(face.offset) * f64::from(polygon_area(face.vertices));
            match found.iter_mut().find(|(id, _, _)| id == solid) {
                Some((_, bounds, v)) => {
                    *bounds = bounds.union(*b);
                    *v += volume;
                }
                None => found.push((*solid, *b, volume)),
            }
        }
        found.retain(|&(_, _, volume)| volume > 0.0);
        let boxes: Vec<Aabb> = found.iter().map(|&(_, b, _)| b).collect();
        OutwardSolids {
            ids: found.iter().map(|&(id, _, _)| id).collect(),
            bvh: BoundsBvh::build_sah(&boxes, crate::bounds_bvh::MAX_LEAF),
            boxes,
        }
    }

    /// Whether a face with bounds `face` could lie inside an outward solid other than `own`.
    fn may_hold(&self, face: &Aabb, own: Option<u32>) -> bool {
        let mut found = false;
        self.bvh.for_each_candidate(face, |m| {
            let m = m as usize;
            found |= Some(self.ids[m]) != own && self.boxes[m].overlaps(face);
        });
        found
    }
}

/// +1 when the ray leaves through `face` (along its normal), −1 when it enters, `None` when it
/// misses it or starts on it (within `tolerance`).
fn crossing(face: &Face, start: Vec3, direction: Vec3, tolerance: f32) -> Option<i32> {
    let along = face.normal.dot(direction);
    if along == 0.0 {
        return None;
    }
    let t = (face.offset - face.normal.dot(start)) / along;
    if t <= tolerance {
        return None;
    }
    let x = start + direction * t;
    let n = face.vertices.len();
    let inside = (0..n).all(|i| {
        let (a, b) = (face.vertices[i], face.vertices[(i + 1) % n]);
        face.normal.cross(b - a).dot(x - a) >= 0.0
    });
    inside.then_some(if along > 0.0 { 1 } else { -1 })
}
