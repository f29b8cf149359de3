//! T-junctions after cutting: every vertex a cut makes is inserted into each edge of any piece it
//! lies on, so that welding links the pieces on both sides of a cut and the faces beside a cut
//! face.

use super::budget::{ArrangementError, Budget};
use super::cut::insert_points_on_edges;
use crate::aabb::Aabb;
use crate::bounds_bvh::BoundsBvh;
use glam::Vec3;

/// Inserts every vertex of a cut face's pieces into each edge of any piece it lies inside, so
/// that the pieces on both sides of a cut, and the faces next to a cut face, share vertices.
pub(super) fn resolve_t_junctions(
    pieces: &mut [Vec<Vec3>],
    source: &[usize],
    was_cut: &[bool],
    tolerance: f32,
    budget: &mut Budget,
) -> Result<(), ArrangementError> {
    let points: Vec<Vec3> = pieces
        .iter()
        .zip(source)
        .filter(|(_, s)| was_cut[**s])
        .flat_map(|(p, _)| p.iter().copied())
        .collect();
    let pad = Vec3::splat(tolerance);
    let boxes: Vec<Aabb> = points.iter().map(|&p| Aabb::new(p - pad, p + pad)).collect();
    let all = boxes.iter().fold(Aabb::EMPTY, |b, &x| b.union(x));
    let bvh = BoundsBvh::build(&boxes);
    let mut found: Vec<Vec3> = Vec::new();
    for piece in pieces.iter_mut() {
        let bounds = Aabb::from_points(piece);
        let bounds = Aabb::new(bounds.min - pad, bounds.max + pad);
        if !bounds.overlaps(&all) {
            continue;
        }
        found.clear();
        let n = piece.len();
        for i in 0..n {
            let edge = Aabb::from_points(&[piece[i], piece[(i + 1) % n]]);
            let edge = Aabb::new(edge.min - pad, edge.max + pad);
            bvh.for_each_candidate(&edge, |k| {
                if boxes[k as usize].overlaps(&edge) {
                    found.push(points[k as usize]);
                }
            });
        }
        if found.is_empty() {
            continue;
        }
        let before = piece.len();
        insert_points_on_edges(piece, &found, tolerance);
        budget.check(budget.pieces, budget.vertices + piece.len() - before)?;
        budget.vertices += piece.len() - before;
    }
    Ok(())
}
