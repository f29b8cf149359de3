//! The first pass of an arrangement: the candidate face pairs (from a hierarchy over their
//! padded bounds) and how each pair meets, gathered into the cuts each face must take.

use super::budget::ArrangementError;
use super::candidates::CandidatePairs;
use super::counts::IntersectionCounts;
use super::cut::{Cut, add_cut};
use super::dedup::dedup_segments;
use super::face::Face;
use super::options::ArrangementOptions;
use super::pair::{Constraint, Meeting, PairOutcome, PairScratch, meet};
use super::slits::{PendingBarrier, close_slits};
use glam::Vec3;
use rayon::prelude::*;

/// What the pairs of faces gave: each face's cuts, the barrier segments, the same-facing
/// copies (hidden face, covering face) and the meetings counted by kind.
pub(super) struct Meetings {
    pub(super) cuts: Vec<Vec<Cut>>,
    pub(super) barriers: Vec<[Vec3; 2]>,
    pub(super) hidden_by: Vec<(usize, usize)>,
    pub(super) counts: IntersectionCounts,
}

/// Faces whose candidate pairs are met together on the worker threads, between two sequential
/// folds of what they found.
const WAVE_FACES: usize = 256;

/// A face with more candidate partners than this is met on the folding thread instead (as a
/// single thread would), so that a wave holds at most `WAVE_FACES × PARTNER_CAP` pairs
/// however the faces crowd together.
const PARTNER_CAP: usize = 4096;

/// Examines every candidate pair of `faces` and gathers the cuts, within the options' bounds
/// on pairs and cut segments.
///
/// The pairs are met in parallel (on the caller's rayon pool) a wave of faces at a time and
/// folded in the order one thread would take them, so the result, and the error when a bound
/// is passed, are the same for any number of threads.
pub(super) fn find_meetings(
    faces: &[Option<Face>],
    tolerance: f32,
    gap: f32,
    options: &ArrangementOptions,
) -> Result<Meetings, ArrangementError> {
    let mut fold = Fold {
        found: Meetings {
            cuts: vec![Vec::new(); faces.len()],
            barriers: Vec::new(),
            hidden_by: Vec::new(),
            counts: IntersectionCounts::default(),
        },
        faces,
        tolerance,
        gap,
        options,
        cut_count: 0,
        pair_count: 0,
        pending: Vec::new(),
    };
    let candidates = CandidatePairs::new(faces, tolerance, gap);
    for wave in (0..candidates.live.len()).collect::<Vec<_>>().chunks(WAVE_FACES) {
        let met: Vec<FaceMeetings> = wave
            .par_iter()
            .map_init(FaceScratch::default, |scratch, &n| {
                candidates.meet_partners(n, faces, tolerance, gap, scratch)
            })
            .collect();
        for (&n, face) in wave.iter().zip(met) {
            fold.face(&candidates, n, face)?;
        }
    }
    let Fold {
        mut found,
        pending,
        pair_count,
        ..
    } = fold;
    found.counts.candidate_pairs = pair_count;
    close_slits(
        &mut found.cuts,
        &mut found.barriers,
        &pending,
        faces,
        tolerance,
        gap,
    );
    // A piercing or in-plane meeting reports its segment for both faces: keep it once.
    found.barriers = dedup_segments(std::mem::take(&mut found.barriers), tolerance);
    Ok(found)
}

impl CandidatePairs {
    /// Live face `n` met with each of its partners, or [`FaceMeetings::Crowded`] when it has
    /// more than [`PARTNER_CAP`].
    fn meet_partners(
        &self,
        n: usize,
        faces: &[Option<Face>],
        tolerance: f32,
        gap: f32,
        scratch: &mut FaceScratch,
    ) -> FaceMeetings {
        let FaceScratch {
            partners,
            pair,
            outcome,
        } = scratch;
        self.partners(n, PARTNER_CAP, partners);
        if partners.len() > PARTNER_CAP {
            return FaceMeetings::Crowded;
        }
        let mut met = Met {
            candidates: partners.len(),
            ..Met::default()
        };
        let a = faces[self.live[n]].as_ref().expect("live faces are faces");
        for (position, &m) in partners.iter().enumerate() {
            let b = faces[self.live[m as usize]]
                .as_ref()
                .expect("live faces are faces");
            meet(faces, a, b, tolerance, gap, pair, outcome);
            if let Some(meeting) = outcome.meeting {
                met.pairs.push(MetPair {
                    position,
                    partner: m,
                    meeting,
                    second_hidden: outcome.second_hidden,
                    on_first: outcome.on_first.len(),
                    on_second: outcome.on_second.len(),
                });
                met.constraints.extend_from_slice(&outcome.on_first);
                met.constraints.extend_from_slice(&outcome.on_second);
            }
        }
        FaceMeetings::Met(met)
    }
}

/// A worker's buffers, reused from face to face: the candidate partners, and the pair test's
/// own.
#[derive(Default)]
struct FaceScratch {
    partners: Vec<u32>,
    pair: PairScratch,
    outcome: PairOutcome,
}

/// What the worker threads found for one face.
enum FaceMeetings {
    /// Its pairs that meet, in partner order.
    Met(Met),
    /// More partners than [`PARTNER_CAP`]: left to the folding thread.
    Crowded,
}

/// One face's meeting pairs and their cuts.
#[derive(Default)]
struct Met {
    /// How many candidate partners the face had (met or not).
    candidates: usize,
    pairs: Vec<MetPair>,
    /// Each pair's cuts on the first face, then on the second, in pair order.
    constraints: Vec<Constraint>,
}

/// A pair that meets: where its partner stood among the candidates, and the outcome.
struct MetPair {
    position: usize,
    partner: u32,
    meeting: Meeting,
    second_hidden: bool,
    on_first: usize,
    on_second: usize,
}

/// The sequential fold of the pairs' outcomes into the cuts, counting pairs and cuts against
/// the options' bounds in the order one thread meets the pairs.
struct Fold<'a, 'f> {
    found: Meetings,
    faces: &'a [Option<Face<'f>>],
    tolerance: f32,
    gap: f32,
    options: &'a ArrangementOptions,
    cut_count: usize,
    pair_count: usize,
    /// The barriers whose ends are settled once all are known (see `slits`).
    pending: Vec<PendingBarrier>,
}

impl Fold<'_, '_> {
    /// Folds live face `n`'s pairs (met on the workers, or here when it is crowded).
    fn face(
        &mut self,
        candidates: &CandidatePairs,
        n: usize,
        met: FaceMeetings,
    ) -> Result<(), ArrangementError> {
        let i = candidates.live[n];
        let met = match met {
            FaceMeetings::Met(met) => met,
            FaceMeetings::Crowded => return self.crowded_face(candidates, n),
        };
        // The pair that would pass the bound on pairs, if this face has it: the pairs before
        // it are folded (a bound on cuts may fail first, as it would on one thread).
        let allowed = self.options.max_pairs.saturating_sub(self.pair_count);
        let mut constraints = met.constraints.as_slice();
        for pair in &met.pairs {
            if pair.position >= allowed {
                break;
            }
            let (first, rest) = constraints.split_at(pair.on_first);
            let (second, rest) = rest.split_at(pair.on_second);
            constraints = rest;
            let j = candidates.live[pair.partner as usize];
            self.pair(i, j, pair.meeting, pair.second_hidden, first, second)?;
        }
        if met.candidates > allowed {
            return Err(ArrangementError::TooManyPairs {
                limit: self.options.max_pairs,
            });
        }
        self.pair_count += met.candidates;
        Ok(())
    }

    /// A face with more partners than a wave may hold, met pair by pair here.
    fn crowded_face(&mut self, candidates: &CandidatePairs, n: usize) -> Result<(), ArrangementError> {
        let i = candidates.live[n];
        let mut partners = Vec::new();
        candidates.partners(n, usize::MAX, &mut partners);
        let mut scratch = PairScratch::default();
        let mut outcome = PairOutcome::default();
        let a = self.faces[i].as_ref().expect("live faces are faces");
        for &m in &partners {
            self.pair_count += 1;
            if self.pair_count > self.options.max_pairs {
                return Err(ArrangementError::TooManyPairs {
                    limit: self.options.max_pairs,
                });
            }
            let j = candidates.live[m as usize];
            let b = self.faces[j].as_ref().expect("live faces are faces");
            meet(
                self.faces,
                a,
                b,
                self.tolerance,
                self.gap,
                &mut scratch,
                &mut outcome,
            );
            if let Some(meeting) = outcome.meeting {
                self.pair(
                    i,
                    j,
                    meeting,
                    outcome.second_hidden,
                    &outcome.on_first,
                    &outcome.on_second,
                )?;
            }
        }
        Ok(())
    }

    /// Counts one meeting pair `(i, j)` and adds its cuts.
    fn pair(
        &mut self,
        i: usize,
        j: usize,
        meeting: Meeting,
        second_hidden: bool,
        on_first: &[Constraint],
        on_second: &[Constraint],
    ) -> Result<(), ArrangementError> {
        let counts = &mut self.found.counts;
        match meeting {
            Meeting::Piercing => counts.piercing += 1,
            Meeting::InPlane => counts.in_plane += 1,
            Meeting::CoplanarOverlap => counts.coplanar_overlap += 1,
            Meeting::NearContact => counts.near_contact += 1,
        }
        if second_hidden {
            self.cut_count += 1;
            self.found.hidden_by.push((j, i));
        }
        for (face, list) in [(i, on_first), (j, on_second)] {
            if self.faces[face].is_none() {
                continue;
            }
            for &c in list {
                self.cut_count += 1;
                if self.cut_count > self.options.max_pieces {
                    return Err(ArrangementError::TooManyPieces {
                        limit: self.options.max_pieces,
                    });
                }
                let cuts = &mut self.found.cuts[face];
                let placed = add_cut(cuts, c.a, c.b, self.tolerance);
                if cuts.len() > self.options.max_cut_lines_per_polygon {
                    return Err(ArrangementError::TooManyCutLines {
                        polygon: face,
                        limit: self.options.max_cut_lines_per_polygon,
                    });
                }
                if c.barrier {
                    // Its ends may still run on to the border, once every barrier is known.
                    if let Some((cut, contact)) = placed {
                        self.pending.push(PendingBarrier {
                            face,
                            cut,
                            contact,
                            barrier: self.found.barriers.len(),
                        });
                    }
                    self.found.barriers.push([c.a, c.b]);
                }
            }
        }
        Ok(())
    }
}
