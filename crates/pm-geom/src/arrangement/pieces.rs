//! The second pass of an arrangement: every face cut into convex pieces along the cuts the
//! first pass gathered, on the caller's rayon pool, a wave of faces at a time, folded in input
//! order so that the pieces, and the error when a bound is passed, are the same for any number
//! of threads.

use std::sync::atomic::{AtomicUsize, Ordering};

use super::budget::{ArrangementError, Budget};
use super::counts::IntersectionCounts;
use super::cut::{Cut, cut_face};
use super::face::Face;
use super::junctions::resolve_t_junctions;
use super::options::ArrangementOptions;
use glam::Vec3;
use rayon::prelude::*;

/// Faces cut together on the worker threads between two folds.
const WAVE_FACES: usize = 256;

/// Every face cut into convex pieces along its cuts, in input order, with the index of the
/// input polygon each piece lies in; then T-junctions resolved.
pub(super) struct Pieces {
    pub(super) polygons: Vec<Vec<Vec3>>,
    pub(super) source: Vec<usize>,
    /// For each input polygon, whether it was cut into more than one piece.
    pub(super) was_cut: Vec<bool>,
}

/// A wave's cutting passed the bound on pieces somewhere: the fold cuts from the first face
/// that saw it on, one face at a time, as a single thread would.
struct WaveFull;

/// Cuts every face met by another into convex pieces (exact duplicates are dropped and
/// counted), within the options' bounds on pieces and vertices.
pub(super) fn cut_faces<P: AsRef<[Vec3]> + Sync>(
    polygons: &[P],
    faces: &[Option<Face>],
    duplicate: &[bool],
    cuts: &[Vec<Cut>],
    tolerance: f32,
    options: &ArrangementOptions,
    counts: &mut IntersectionCounts,
) -> Result<Pieces, ArrangementError> {
    let limit = options.piece_limit(polygons.len());
    let mut budget = Budget::new(limit, options.max_vertices);
    let mut pieces: Vec<Vec<Vec3>> = Vec::with_capacity(polygons.len());
    let mut source = Vec::with_capacity(polygons.len());
    let mut was_cut = vec![false; polygons.len()];
    let to_cut = |index: usize| match &faces[index] {
        Some(face) if !duplicate[index] && !cuts[index].is_empty() => Some(face),
        _ => None,
    };
    for start in (0..polygons.len()).step_by(WAVE_FACES) {
        let wave = start..(start + WAVE_FACES).min(polygons.len());
        // The pieces the wave's faces made so far, all together: a face stops when the pieces
        // before the wave and these pass the bound, so a wave never holds much more than it.
        let made_in_wave = AtomicUsize::new(0);
        let room = limit.saturating_sub(pieces.len());
        let cut: Vec<Option<Result<Vec<Vec<Vec3>>, WaveFull>>> = wave
            .clone()
            .into_par_iter()
            .map(|index| {
                let face = to_cut(index)?;
                let mut counted = 0;
                Some(cut_face(
                    polygons[index].as_ref(),
                    &cuts[index],
                    face.normal,
                    tolerance,
                    |made| {
                        let total =
                            made_in_wave.fetch_add(made - counted, Ordering::Relaxed) + made - counted;
                        counted = made;
                        if total > room { Err(WaveFull) } else { Ok(()) }
                    },
                ))
            })
            .collect();
        let mut sequential = false;
        for (index, cut) in wave.zip(cut) {
            let polygon = polygons[index].as_ref();
            if duplicate[index] {
                counts.duplicate_pieces += 1;
                counts.coplanar_overlap += 1;
                continue;
            }
            let Some(face) = to_cut(index) else {
                budget.add(polygon)?;
                pieces.push(polygon.to_vec());
                source.push(index);
                continue;
            };
            let done = pieces.len();
            let current = match cut {
                Some(Ok(current)) if !sequential => {
                    // One thread checks after every cut; the count only grows, so checking
                    // the final count gives the same answer.
                    budget.check(done + current.len(), 0)?;
                    current
                }
                _ => {
                    sequential = true;
                    cut_face(polygon, &cuts[index], face.normal, tolerance, |made| {
                        budget.check(done + made, 0)
                    })?
                }
            };
            was_cut[index] = current.len() > 1;
            for piece in current {
                budget.add(&piece)?;
                pieces.push(piece);
                source.push(index);
            }
        }
    }
    if was_cut.iter().any(|&c| c) {
        resolve_t_junctions(&mut pieces, &source, &was_cut, tolerance, &mut budget)?;
    }
    Ok(Pieces {
        polygons: pieces,
        source,
        was_cut,
    })
}
