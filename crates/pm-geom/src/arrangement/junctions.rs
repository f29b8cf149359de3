//! T-junctions after cutting: every vertex a cut makes is inserted into each edge of any piece it
//! lies on, so that welding links the pieces on both sides of a cut and the faces beside a cut
//! face. Pieces are worked on in parallel (the caller's rayon pool), a wave at a time, and
//! folded in order: the same result, and the same error, for any number of threads.

use super::budget::{ArrangementError, Budget};
use super::cut::insert_points_by_edge;
use crate::aabb::Aabb;
use crate::bounds_bvh::BoundsBvh;
use glam::Vec3;
use rayon::prelude::*;

/// Points per leaf of the cut vertices' hierarchy: each piece queries it once with its bounds
/// and tests what it finds against each edge, so wide leaves cost little there and quarter the
/// nodes held at the split's peak (which points are found does not depend on the leaves).
const POINT_LEAF: usize = 16;

/// Pieces worked on together between two folds.
const WAVE_PIECES: usize = 1024;

/// A piece that finds more cut vertices than this near its edges is left to the folding thread,
/// so that a wave holds at most `WAVE_PIECES × POINT_CAP` found points.
const POINT_CAP: usize = 4096;

/// Inserts every vertex of a cut face's pieces into each edge of any piece it lies inside, so
/// that the pieces on both sides of a cut, and the faces next to a cut face, share vertices.
pub(super) fn resolve_t_junctions(
    pieces: &mut [Vec<Vec3>],
    source: &[usize],
    was_cut: &[bool],
    tolerance: f32,
    budget: &mut Budget,
) -> Result<(), ArrangementError> {
    let cut = || {
        pieces
            .iter()
            .zip(source)
            .filter(|(_, s)| was_cut[**s])
            .map(|(p, _)| p)
    };
    // Counted first, so that the table is not grown by doubling at the split's peak.
    let mut points: Vec<Vec3> = Vec::with_capacity(cut().map(Vec::len).sum());
    cut().for_each(|p| points.extend_from_slice(p));
    // A corner shared by several pieces is one point: kept once, each edge finds it once (what
    // an edge gains does not change: its points are sorted and merged along it).
    points.par_sort_unstable_by_key(|p| [p.x.to_bits(), p.y.to_bits(), p.z.to_bits()]);
    points.dedup();
    points.shrink_to_fit();
    let pad = Vec3::splat(tolerance);
    // The hierarchy is built over the points' padded boxes made when needed, never held as
    // a table; queries remake them from the points (the same bits).
    let padded = |k: u32| {
        let p = points[k as usize];
        Aabb::new(p - pad, p + pad)
    };
    let all = (0..points.len() as u32).fold(Aabb::EMPTY, |b, k| b.union(padded(k)));
    let bvh = BoundsBvh::build_by(points.len(), padded, POINT_LEAF);
    let near = NearPoints {
        points,
        all,
        bvh,
        pad,
    };
    for wave in pieces.chunks_mut(WAVE_PIECES) {
        // Each piece grows in place; the fold then counts the growth in order (an error
        // discards every piece, so pieces grown past the one that failed do not matter).
        let grown: Vec<Grown> = wave
            .par_iter_mut()
            .map_init(Found::default, |found, piece| {
                near.along_edges(piece, POINT_CAP, found);
                if found.points.len() > POINT_CAP {
                    return Grown::Crowded;
                }
                let before = piece.len();
                if !found.points.is_empty() {
                    found.insert_into(piece, tolerance);
                }
                Grown::By(piece.len() - before)
            })
            .collect();
        for (piece, grown) in wave.iter_mut().zip(grown) {
            let added = match grown {
                Grown::By(0) => continue,
                Grown::By(added) => added,
                Grown::Crowded => {
                    let before = piece.len();
                    let mut found = Found::default();
                    near.along_edges(piece, usize::MAX, &mut found);
                    found.insert_into(piece, tolerance);
                    piece.len() - before
                }
            };
            budget.check(budget.pieces, budget.vertices + added)?;
            budget.vertices += added;
        }
    }
    Ok(())
}

/// What the workers did to one piece.
enum Grown {
    /// The cut vertices near its edges inserted: this many vertices more (0 when none was
    /// near, or none lay on an edge).
    By(usize),
    /// More than [`POINT_CAP`] cut vertices near its edges: left to the folding thread.
    Crowded,
}

/// The vertices of the cut faces' pieces, padded by the tolerance, in a hierarchy.
struct NearPoints {
    points: Vec<Vec3>,
    all: Aabb,
    bvh: BoundsBvh,
    pad: Vec3,
}

impl NearPoints {
    /// Point `k`'s box, padded by the tolerance.
    #[inline]
    fn padded(&self, k: u32) -> Aabb {
        let p = self.points[k as usize];
        Aabb::new(p - self.pad, p + self.pad)
    }

    /// The points whose padded boxes meet the padded bounds of each of `piece`'s edges (a
    /// point once per edge it is near), by edge, into `found`; stops adding past `cap` of them.
    /// One query of the hierarchy with the piece's bounds, then each edge's box against what
    /// it found: most pieces lie far from every cut and cost one query, not one per edge.
    fn along_edges(&self, piece: &[Vec3], cap: usize, found: &mut Found) {
        found.points.clear();
        found.starts.clear();
        found.starts.push(0);
        found.near.clear();
        let bounds = Aabb::from_points(piece);
        let bounds = Aabb::new(bounds.min - self.pad, bounds.max + self.pad);
        if bounds.overlaps(&self.all) {
            self.bvh.for_each_candidate(&bounds, |k| {
                if self.padded(k).overlaps(&bounds) {
                    found.near.push(k);
                }
            });
        }
        let n = piece.len();
        for i in 0..n {
            if !found.near.is_empty() {
                let edge = Aabb::from_points(&[piece[i], piece[(i + 1) % n]]);
                let edge = Aabb::new(edge.min - self.pad, edge.max + self.pad);
                for &k in &found.near {
                    if self.padded(k).overlaps(&edge) && found.points.len() <= cap {
                        found.points.push(self.points[k as usize]);
                    }
                }
            }
            found.starts.push(found.points.len());
        }
    }
}

/// The cut vertices near a piece's edges, by edge, and the hierarchy's answer they came from;
/// reused from piece to piece.
#[derive(Default)]
struct Found {
    /// The points near edge `i` are `points[starts[i]..starts[i + 1]]`.
    points: Vec<Vec3>,
    starts: Vec<usize>,
    /// The points (by index) whose padded boxes meet the piece's padded bounds.
    near: Vec<u32>,
}

impl Found {
    /// Inserts the points into the edges of `piece` they lie on.
    fn insert_into(&self, piece: &mut Vec<Vec3>, tolerance: f32) {
        insert_points_by_edge(
            piece,
            |i| &self.points[self.starts[i]..self.starts[i + 1]],
            tolerance,
        );
    }
}
