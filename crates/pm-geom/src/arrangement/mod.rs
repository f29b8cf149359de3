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

#[cfg(test)]
mod apart_tests;
mod barrier;
#[cfg(test)]
mod bounds_tests;
mod budget;
mod candidates;
#[cfg(test)]
mod contact_tests;
mod continuation;
mod copies;
mod counts;
mod cut;
mod dedup;
mod face;
mod inside;
mod junctions;
mod linked;
mod meetings;
mod options;
#[cfg(test)]
mod outline_tests;
mod pair;
#[cfg(test)]
mod parallel_tests;
mod pieces;
mod seconds;
#[cfg(test)]
mod slit_tests;
mod slits;
#[cfg(test)]
mod test_stream;
#[cfg(test)]
mod tests;

pub use barrier::BarrierSet;
pub use budget::ArrangementError;
pub use counts::IntersectionCounts;
pub use options::ArrangementOptions;
pub use seconds::{ArrangementSeconds, StepTimer};

use crate::aabb::Aabb;
use crate::polygon::polygon_vector_area;
use continuation::EdgeNeighbours;
use copies::{covered_by, exact_duplicates};
use face::Face;
use glam::Vec3;
use meetings::{Meetings, find_meetings};
use pieces::{Pieces, cut_faces};

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
    /// facing the same way are not barriers (the hidden copy is dropped instead). Each segment
    /// once, though it is an edge of the pieces on both faces.
    pub barriers: Vec<[Vec3; 2]>,
    /// What was found.
    pub counts: IntersectionCounts,
    /// How long each step took.
    pub seconds: ArrangementSeconds,
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
/// way a little in front of another (a lamp mounted under a ceiling) is left alone. Such a
/// near-contact is outlined where the near surface stops coming close, not along its inner
/// edges: an edge whose neighbour across it (sharing both end points bit for bit) continues
/// the surface within the gap, or goes on past the edge as seen from the face (the cap of
/// raised lettering and its walls), cuts nothing. A barrier that stops short of the face's
/// border runs on to it when the slit left is narrower than the gap and than a tenth of its
/// chain of linked barriers (a wall stopping just short of the floor closes the strip under
/// it; a letter near a button's border does not cut the button across). Cuts run as full
/// lines across a face, so the pieces stay convex; the meeting segments themselves are
/// returned as [`Arrangement::barriers`]. Vertices a cut makes are then inserted into every
/// edge they lie on, so that welding the output links pieces on both sides of a cut.
///
/// `solids` gives, for each polygon, the closed solid it bounds (its faces oriented outwards),
/// or `None`; it may be empty. A piece that lies inside another closed solid is marked
/// [`Arrangement::sealed`]: a piece of a cut face, and also a face wholly inside a solid, which
/// meets none of its faces and so is never cut (the end of a bar pushed into a cube).
///
/// Degenerate polygons (fewer than 3 vertices, zero area, non-finite) pass through unchanged.
///
/// The face pairs, the cuts and the T-junctions are worked on in parallel on the caller's
/// rayon pool (call it inside `ThreadPool::install` to choose the threads), a wave at a time,
/// and folded in input order: the result, and the error when a bound is passed, are the same
/// bits on any number of threads.
/// The area of every input polygon is kept by its pieces, except duplicates dropped.
pub fn split_polygons_at_intersections<P: AsRef<[Vec3]> + Sync>(
    polygons: &[P],
    solids: &[Option<u32>],
    options: &ArrangementOptions,
) -> Result<Arrangement, ArrangementError> {
    let mut timer = StepTimer::start();
    let mut seconds = ArrangementSeconds::default();
    let (tolerance, gap) = tolerances(polygons, options);
    let duplicate = exact_duplicates(polygons);
    let neighbours = EdgeNeighbours::new(polygons);
    let faces: Vec<Option<Face>> = polygons
        .iter()
        .zip(&duplicate)
        .enumerate()
        .map(|(i, (p, &dup))| {
            if dup {
                None
            } else {
                face_of(p.as_ref(), neighbours.of(i), gap)
            }
        })
        .collect();
    seconds.faces = timer.lap();
    let Meetings {
        cuts,
        barriers,
        hidden_by,
        mut counts,
    } = find_meetings(&faces, tolerance, gap, options)?;
    seconds.meetings = timer.lap();
    let mut pieces = cut_faces(
        polygons,
        &faces,
        &duplicate,
        &cuts,
        tolerance,
        options,
        &mut counts,
    )?;
    seconds.cutting = timer.lap();
    let keep = drop_hidden_copies(
        &pieces,
        &faces,
        &hidden_by,
        polygons.len(),
        tolerance,
        gap,
        &mut counts,
    );
    let mut sealed = vec![false; pieces.polygons.len()];
    if solids.iter().any(Option::is_some) {
        let Pieces {
            polygons,
            source,
            was_cut,
        } = &pieces;
        inside::mark_sealed(polygons, source, was_cut, solids, &faces, tolerance, &mut sealed);
    }

    let mut out = Arrangement {
        barriers,
        ..Arrangement::default()
    };
    for (p, piece) in std::mem::take(&mut pieces.polygons).into_iter().enumerate() {
        if keep[p] {
            out.polygons.push(piece);
            out.source.push(pieces.source[p]);
            out.sealed.push(sealed[p]);
        }
    }
    counts.sealed_pieces = out.sealed.iter().filter(|&&s| s).count();
    out.counts = counts;
    seconds.copies_and_sealing = timer.lap();
    out.seconds = seconds;
    Ok(out)
}

/// The tolerance and gap actually used: the options' values, the tolerance raised to at least
/// 8 units in the last place of the largest coordinate and the gap to at least the tolerance.
fn tolerances<P: AsRef<[Vec3]>>(polygons: &[P], options: &ArrangementOptions) -> (f32, f32) {
    let largest = polygons
        .iter()
        .flat_map(|p| p.as_ref().iter())
        .filter(|p| p.is_finite())
        .fold(0.0f32, |m, p| m.max(p.abs().max_element()));
    let tolerance = options
        .tolerance
        .max(largest * 8.0 * f32::EPSILON)
        .max(f32::MIN_POSITIVE);
    (tolerance, options.gap.max(tolerance))
}

/// Which pieces to keep: not the hidden copies of overlapping same-facing faces (each pair in
/// `hidden_by` is a hidden face and the face that covers it), which are counted as duplicates.
fn drop_hidden_copies(
    pieces: &Pieces,
    faces: &[Option<Face>],
    hidden_by: &[(usize, usize)],
    polygon_count: usize,
    tolerance: f32,
    gap: f32,
    counts: &mut IntersectionCounts,
) -> Vec<bool> {
    let mut keep = vec![true; pieces.polygons.len()];
    if hidden_by.is_empty() {
        return keep;
    }
    let mut first_piece = vec![usize::MAX; polygon_count];
    for (p, &s) in pieces.source.iter().enumerate().rev() {
        first_piece[s] = p;
    }
    for &(hidden, cover) in hidden_by {
        let Some(cover_face) = &faces[cover] else { continue };
        let start = first_piece[hidden];
        if start == usize::MAX {
            continue;
        }
        for p in (start..pieces.polygons.len()).take_while(|&p| pieces.source[p] == hidden) {
            if keep[p] && covered_by(&pieces.polygons[p], cover_face, tolerance, gap) {
                keep[p] = false;
                counts.duplicate_pieces += 1;
            }
        }
    }
    keep
}

/// The face of a polygon with the polygons across its edges, `None` when it is degenerate or
/// not finite; bounds padded by `pad`.
fn face_of<'a>(polygon: &'a [Vec3], across: &'a [u32], pad: f32) -> Option<Face<'a>> {
    if polygon.len() < 3 || polygon.iter().any(|p| !p.is_finite()) {
        return None;
    }
    let normal = polygon_vector_area(polygon).try_normalize()?;
    let bounds = Aabb::from_points(polygon);
    let pad = Vec3::splat(pad);
    Some(Face {
        vertices: polygon,
        across,
        normal,
        offset: normal.dot(polygon[0]),
        bounds: Aabb::new(bounds.min - pad, bounds.max + pad),
    })
}
