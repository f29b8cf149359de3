//! Mesh arrangement of convex faces: every pair of faces that pierce, touch, overlap in one plane
//! or nearly touch is found, and each face is cut along those segments into convex pieces, so
//! that every meeting line becomes an edge of the pieces on all its sides and can be kept out of
//! any photon map's flood fill.
//!
//! In the spirit of libigl's `remesh_self_intersections`, CGAL's autorefine and Zhou et al.,
//! *Mesh Arrangements for Solid Geometry* (SIGGRAPH 2016), with one scene-relative tolerance
//! instead of exact constructions: a point within the tolerance of a plane, a line or another
//! point lies on it. Every decision is a comparison of a distance with that tolerance, and the
//! tolerance is kept far above the rounding of the `f32` coordinates (at least 8 units in the
//! last place of the largest one), so no sign is decided by rounding noise.

mod barrier;
mod budget;
#[cfg(test)]
mod contact_tests;
mod copies;
mod cut;
mod inside;
mod junctions;
mod pair;
#[cfg(test)]
mod tests;

pub use barrier::BarrierSet;
pub use budget::ArrangementError;

use crate::aabb::Aabb;
use crate::bounds_bvh::BoundsBvh;
use crate::polygon::polygon_vector_area;
use budget::Budget;
use copies::{covered_by, exact_duplicates};
use cut::{Cut, add_cut, cut_face};
use glam::Vec3;
use junctions::resolve_t_junctions;
use pair::{Face, Meeting, PairOutcome, PairScratch, close_barrier_ends, meet};

/// Tolerances and bounds of [`split_polygons_at_intersections`].
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ArrangementOptions {
    /// Distance (metres) under which points coincide and a point lies on a plane or a line; a
    /// good choice is `1e-5` × the scene's diagonal, and a mesh welded from the output should
    /// use the same weld tolerance.
    pub tolerance: f32,
    /// Distance (metres, at least `tolerance`) under which two faces that do not meet count as
    /// touching: a wall that stops this close to a floor cuts the floor as if it stood on it.
    pub gap: f32,
    /// Most candidate face pairs (faces whose padded bounds overlap) examined.
    pub max_pairs: usize,
    /// Most output pieces, and most cut segments.
    pub max_pieces: usize,
    /// Most vertices over all output pieces.
    pub max_vertices: usize,
}

impl ArrangementOptions {
    /// Default [`Self::max_pairs`]: 16 million pairs, a few seconds of work.
    pub const DEFAULT_MAX_PAIRS: usize = 16_000_000;
    /// Default [`Self::max_pieces`]: 2 million pieces.
    pub const DEFAULT_MAX_PIECES: usize = 2_000_000;
    /// Default [`Self::max_vertices`]: 16 million vertices (192 MB of positions).
    pub const DEFAULT_MAX_VERTICES: usize = 16_000_000;

    /// `tolerance` and `gap` with the default bounds.
    pub fn new(tolerance: f32, gap: f32) -> Self {
        ArrangementOptions {
            tolerance,
            gap,
            max_pairs: Self::DEFAULT_MAX_PAIRS,
            max_pieces: Self::DEFAULT_MAX_PIECES,
            max_vertices: Self::DEFAULT_MAX_VERTICES,
        }
    }
}

/// How many meetings of each kind [`split_polygons_at_intersections`] found.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct IntersectionCounts {
    /// Face pairs passing through each other.
    pub piercing: usize,
    /// Face pairs where an edge of one lies in the other, across its inside.
    pub in_plane: usize,
    /// Face pairs lying in one plane and overlapping.
    pub coplanar_overlap: usize,
    /// Face pairs closer than the gap tolerance without meeting.
    pub near_contact: usize,
    /// Pieces dropped because another face covers them in the same plane, facing the same way
    /// (duplicated faces: only the first is kept).
    pub duplicate_pieces: usize,
    /// Pieces inside a closed solid, where no light reaches.
    pub sealed_pieces: usize,
}

impl IntersectionCounts {
    /// Meetings of every kind (not counting dropped or sealed pieces).
    pub fn meetings(&self) -> usize {
        self.piercing + self.in_plane + self.coplanar_overlap + self.near_contact
    }
}

/// The result of [`split_polygons_at_intersections`].
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Arrangement {
    /// The convex output pieces, each with extra collinear vertices where other pieces'
    /// vertices lie on its edges.
    pub polygons: Vec<Vec<Vec3>>,
    /// For each piece, the index of the input polygon it lies in.
    pub source: Vec<usize>,
    /// For each piece, whether it lies inside a closed solid (see the `solids` argument).
    pub sealed: Vec<bool>,
    /// Every segment along which faces meet and no photon map may join: piercing and in-plane
    /// contacts, near-contacts, and overlaps of faces facing opposite ways. Overlaps of faces
    /// facing the same way are not barriers (the hidden copy is dropped instead).
    pub barriers: Vec<[Vec3; 2]>,
    /// What was found.
    pub counts: IntersectionCounts,
}

/// Cuts the convex planar `polygons` wherever they meet each other.
///
/// Every pair of faces whose bounds (padded by the gap) overlap is examined (candidates come
/// from a bounding-volume hierarchy, so the cost grows with `n log n` plus the pairs found, not
/// with `n²`): faces that pierce each other are both cut along their common segment; a face
/// another face's edge lies in (a wall standing on a floor) is cut along that edge; faces in
/// one plane that overlap are cut along each other's outline, and where they face the same way
/// only the first keeps the overlapped part (the later copies' pieces are dropped); a face that
/// another face's edge comes within `gap` of is cut along that edge's projection, and so is a
/// face that a parallel face facing it comes within `gap` of. A parallel face facing the same
/// way a little in front of another (a lamp mounted under a ceiling) is left alone. Cuts run as
/// full lines across a face, so the pieces stay convex; the meeting segments themselves are
/// returned as [`Arrangement::barriers`]. Vertices a cut makes are then inserted into every
/// edge they lie on, so that welding the output links pieces on both sides of a cut.
///
/// `solids` gives, for each polygon, the closed solid it bounds (its faces oriented outwards),
/// or `None`; it may be empty. A piece of a cut face that lies inside another closed solid is
/// marked [`Arrangement::sealed`].
///
/// Degenerate polygons (fewer than 3 vertices, zero area, non-finite) pass through unchanged.
/// The area of every input polygon is kept by its pieces, except duplicates dropped.
pub fn split_polygons_at_intersections<P: AsRef<[Vec3]>>(
    polygons: &[P],
    solids: &[Option<u32>],
    options: &ArrangementOptions,
) -> Result<Arrangement, ArrangementError> {
    let largest = polygons
        .iter()
        .flat_map(|p| p.as_ref().iter())
        .filter(|p| p.is_finite())
        .fold(0.0f32, |m, p| m.max(p.abs().max_element()));
    let tolerance = options
        .tolerance
        .max(largest * 8.0 * f32::EPSILON)
        .max(f32::MIN_POSITIVE);
    let gap = options.gap.max(tolerance);
    let duplicate = exact_duplicates(polygons);
    let faces: Vec<Option<Face>> = polygons
        .iter()
        .zip(&duplicate)
        .map(|(p, &dup)| if dup { None } else { face_of(p.as_ref(), gap) })
        .collect();

    // Candidate pairs and how each meets.
    let mut cuts: Vec<Vec<Cut>> = vec![Vec::new(); polygons.len()];
    let mut barriers: Vec<[Vec3; 2]> = Vec::new();
    let mut hidden_by: Vec<(usize, usize)> = Vec::new();
    let mut counts = IntersectionCounts::default();
    let mut cut_count = 0usize;
    let mut scratch = PairScratch::default();
    let mut outcome = PairOutcome::default();
    let mut pair_count = 0usize;
    let mut failure = None;
    for_each_candidate_pair(&faces, gap, |i, j| {
        if failure.is_some() {
            return;
        }
        pair_count += 1;
        if pair_count > options.max_pairs {
            failure = Some(ArrangementError::TooManyPairs {
                limit: options.max_pairs,
            });
            return;
        }
        let (Some(a), Some(b)) = (&faces[i], &faces[j]) else {
            return;
        };
        meet(a, b, tolerance, gap, &mut scratch, &mut outcome);
        let Some(meeting) = outcome.meeting else {
            return;
        };
        match meeting {
            Meeting::Piercing => counts.piercing += 1,
            Meeting::InPlane => counts.in_plane += 1,
            Meeting::CoplanarOverlap => counts.coplanar_overlap += 1,
            Meeting::NearContact => counts.near_contact += 1,
        }
        if let Some(first_hidden) = outcome.first_hidden {
            cut_count += 1;
            hidden_by.push(if first_hidden { (i, j) } else { (j, i) });
        }
        for (face, list) in [(i, &outcome.on_first), (j, &outcome.on_second)] {
            let Some(target) = &faces[face] else { continue };
            for &c in list {
                let c = if c.barrier {
                    close_barrier_ends(c, target, tolerance, gap)
                } else {
                    c
                };
                cut_count += 1;
                if cut_count > options.max_pieces {
                    failure = Some(ArrangementError::TooManyPieces {
                        limit: options.max_pieces,
                    });
                    return;
                }
                add_cut(&mut cuts[face], c.a, c.b, tolerance);
                if c.barrier {
                    barriers.push([c.a, c.b]);
                }
            }
        }
    });
    if let Some(error) = failure {
        return Err(error);
    }

    // Cut every face met by another into convex pieces.
    let mut budget = Budget::new(options.max_pieces, options.max_vertices);
    let mut pieces: Vec<Vec<Vec3>> = Vec::with_capacity(polygons.len());
    let mut source = Vec::with_capacity(polygons.len());
    let mut was_cut = vec![false; polygons.len()];
    for (index, polygon) in polygons.iter().enumerate() {
        let polygon = polygon.as_ref();
        if duplicate[index] {
            counts.duplicate_pieces += 1;
            counts.coplanar_overlap += 1;
            continue;
        }
        match &faces[index] {
            Some(face) if !cuts[index].is_empty() => {
                let done = pieces.len();
                let current = cut_face(polygon, &cuts[index], face.normal, tolerance, |made| {
                    budget.check(done + made, 0)
                })?;
                was_cut[index] = current.len() > 1;
                for piece in current {
                    budget.add(&piece)?;
                    pieces.push(piece);
                    source.push(index);
                }
            }
            _ => {
                budget.add(polygon)?;
                pieces.push(polygon.to_vec());
                source.push(index);
            }
        }
    }
    if was_cut.iter().any(|&c| c) {
        resolve_t_junctions(&mut pieces, &source, &was_cut, tolerance, &mut budget)?;
    }

    // Drop the hidden copies of overlapping same-facing faces.
    let mut keep = vec![true; pieces.len()];
    if !hidden_by.is_empty() {
        let mut first_piece = vec![usize::MAX; polygons.len()];
        for (p, &s) in source.iter().enumerate().rev() {
            first_piece[s] = p;
        }
        for &(hidden, cover) in &hidden_by {
            let Some(cover_face) = &faces[cover] else { continue };
            let start = first_piece[hidden];
            if start == usize::MAX {
                continue;
            }
            for p in (start..pieces.len()).take_while(|&p| source[p] == hidden) {
                if keep[p] && covered_by(&pieces[p], cover_face, tolerance, gap) {
                    keep[p] = false;
                    counts.duplicate_pieces += 1;
                }
            }
        }
    }
    let mut sealed = vec![false; pieces.len()];
    if !solids.is_empty() && was_cut.iter().any(|&c| c) {
        inside::mark_sealed(&pieces, &source, &was_cut, solids, &faces, tolerance, &mut sealed);
    }

    let mut out = Arrangement {
        barriers,
        ..Arrangement::default()
    };
    for (p, piece) in pieces.into_iter().enumerate() {
        if keep[p] {
            out.polygons.push(piece);
            out.source.push(source[p]);
            out.sealed.push(sealed[p]);
        }
    }
    counts.sealed_pieces = out.sealed.iter().filter(|&&s| s).count();
    out.counts = counts;
    Ok(out)
}

/// The face of a polygon, `None` when it is degenerate or not finite; bounds padded by `pad`.
fn face_of(polygon: &[Vec3], pad: f32) -> Option<Face<'_>> {
    if polygon.len() < 3 || polygon.iter().any(|p| !p.is_finite()) {
        return None;
    }
    let normal = polygon_vector_area(polygon).try_normalize()?;
    let bounds = Aabb::from_points(polygon);
    let pad = Vec3::splat(pad);
    Some(Face {
        vertices: polygon,
        normal,
        offset: normal.dot(polygon[0]),
        bounds: Aabb::new(bounds.min - pad, bounds.max + pad),
    })
}

/// Calls `f(i, j)`, `i < j`, for every pair of faces whose bounds come within `gap` of each
/// other (one face's own bounds against the other's, padded by the gap), through a
/// bounding-volume hierarchy over the padded bounds; the order is fixed by the faces and the
/// tree, whatever the machine.
fn for_each_candidate_pair(faces: &[Option<Face>], gap: f32, mut f: impl FnMut(usize, usize)) {
    let live: Vec<(usize, Aabb)> = faces
        .iter()
        .enumerate()
        .filter_map(|(i, face)| face.as_ref().map(|face| (i, face.bounds)))
        .collect();
    let boxes: Vec<Aabb> = live.iter().map(|&(_, b)| b).collect();
    // Every face queries the tree once: leaves of 12 halve the levels each query walks
    // (82 against 97 ms on split-rooms-100's 120,000 quads with leaves of 4).
    let bvh = BoundsBvh::build_with_leaves(&boxes, 12);
    let mut partners: Vec<u32> = Vec::new();
    let pad = Vec3::splat(gap);
    for (n, &(i, padded)) in live.iter().enumerate() {
        let own = Aabb::new(padded.min + pad, padded.max - pad);
        partners.clear();
        bvh.for_each_candidate(&own, |m| {
            if m as usize > n && own.overlaps(&boxes[m as usize]) {
                partners.push(m);
            }
        });
        for &m in &partners {
            f(i, live[m as usize].0);
        }
    }
}
