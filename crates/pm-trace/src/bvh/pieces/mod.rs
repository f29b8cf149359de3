//! Faces searched as the user gave them, their parts found among the pieces the contact
//! partition cut them into. A ray meets the original triangle (so the split never changes what
//! a ray hits, and no sliver piece loses precision); where the face was cut into pieces of
//! different parts, the point hit is located among its pieces to give the part — and so the
//! photon map — it lies in.
//!
//! A triangle whose face lies in one part keeps that part in its record as before. A triangle
//! of a cut face carries [`PIECES`] plus the index of its face's piece list in the record's
//! part instead; [`PieceIndex::locate`] finds the piece (a convex face of the split scene, as
//! its outline's edge lines, without the T-junction corners the split put along its edges)
//! that contains the point, or else the nearest within the tolerance. A point farther than that
//! from every piece lies where the partition dropped the face (the hidden copy of a coincident
//! face): the ray passes there, and meets the copy that was kept at the same distance.

use crate::part::{PartId, PartSurface};
use glam::Vec3;
use pm_geom::polygon_vector_area;

/// Set in a triangle record's part when its face is cut into pieces: the rest of the bits
/// index the face's piece list.
pub(crate) const PIECES: u32 = 1 << 31;

/// One edge of a piece's outline: where it starts, its inward unit normal (in the face's
/// plane) and its offset, so that `offset - inward·p` is how far `p` lies outside it. It ends
/// where the piece's next edge starts.
#[derive(Clone, Copy, Debug)]
struct PieceEdge {
    from: Vec3,
    inward: Vec3,
    offset: f32,
}

/// One piece: its edges' range in the index's edges, and its part.
#[derive(Clone, Copy, Debug)]
struct PiecePolygon {
    first: u32,
    end: u32,
    part: PartSurface,
}

/// A convex piece outline made ready to locate points in, about its face's unit normal `n`
/// (not its own: a sliver whose corners are nearly collinear has a normal that rounding points
/// anywhere, and edge planes about it would take in points far off): wound counter-clockwise
/// about `n`, repeated corners and the T-junction corners the split inserted along an edge
/// dropped ([`drop_corners_on_edges`]).
/// Fills `edges` and gives the outline's area; `None` when it has no area about `n`, fewer
/// than three corners, or an edge with no direction.
fn outline_edges(polygon: &[Vec3], n: Vec3, tolerance: f32, edges: &mut Vec<PieceEdge>) -> Option<f32> {
    edges.clear();
    let vector_area = polygon_vector_area(polygon);
    let winding = vector_area.dot(n);
    if !(winding != 0.0 && winding.is_finite()) {
        return None;
    }
    let mut corners: Vec<Vec3> = Vec::with_capacity(polygon.len());
    let push_corner = |corners: &mut Vec<Vec3>, v: Vec3| {
        if corners.last() != Some(&v) {
            corners.push(v);
        }
    };
    if winding > 0.0 {
        polygon.iter().for_each(|&v| push_corner(&mut corners, v));
    } else {
        polygon.iter().rev().for_each(|&v| push_corner(&mut corners, v));
    }
    while corners.len() > 1 && corners.first() == corners.last() {
        corners.pop();
    }
    if corners.len() < 3 {
        return None;
    }
    let corners = drop_corners_on_edges(&corners, n, tolerance);
    let k = corners.len();
    for i in 0..k {
        let (a, b) = (corners[i], corners[(i + 1) % k]);
        let Some(inward) = n.cross(b - a).try_normalize() else {
            edges.clear();
            return None;
        };
        edges.push(PieceEdge {
            from: a,
            inward,
            offset: inward.dot(a),
        });
    }
    Some(vector_area.length())
}

/// Corners within `tolerance` of the straight edge through their kept neighbours, and no
/// farther from it than 10⁻⁴ of its length (so that only corners the split put on an edge go,
/// not a shallow real corner far from the origin, where `tolerance` is coarse), are dropped:
/// every dropped corner lies that close to the kept outline's edge, so drops do not add up.
/// Starts at the sharpest corner (a real one); keeps at least three corners.
fn drop_corners_on_edges(corners: &[Vec3], n: Vec3, tolerance: f32) -> Vec<Vec3> {
    let k = corners.len();
    let turn = |i: usize| {
        let (a, b, c) = (corners[(i + k - 1) % k], corners[i], corners[(i + 1) % k]);
        let (u, v) = (b - a, c - b);
        u.cross(v).dot(n).abs() / (u.length() * v.length()).max(f32::MIN_POSITIVE)
    };
    let sharpest = (0..k).max_by(|&i, &j| turn(i).total_cmp(&turn(j))).unwrap_or(0);
    let mut kept = vec![corners[sharpest]];
    let mut dropped: Vec<Vec3> = Vec::new();
    for step in 1..k {
        let b = corners[(sharpest + step) % k];
        let next = corners[(sharpest + step + 1) % k];
        let from = *kept.last().unwrap_or(&b);
        let chord = next - from;
        let length = chord.length();
        let reach = tolerance.min(1e-4 * length);
        let on_chord = |p: &Vec3| length > 0.0 && chord.cross(*p - from).dot(n).abs() <= reach * length;
        // Room for three: a sliver narrower than the tolerance stays a sliver.
        let room = kept.len() + (k - step) > 3;
        if room && on_chord(&b) && dropped.iter().all(on_chord) {
            dropped.push(b);
        } else {
            kept.push(b);
            dropped.clear();
        }
    }
    kept
}

/// How far `p` lies outside a piece's edge lines (≤ 0 inside: in its plane, `p` is then on
/// the piece; a positive value is only a lower bound of the distance, which past a sliver's
/// sharp corner is far larger).
#[inline]
fn outside(edges: &[PieceEdge], p: Vec3) -> f32 {
    edges
        .iter()
        .map(|e| e.offset - e.inward.dot(p))
        .fold(f32::NEG_INFINITY, f32::max)
}

/// Whether `p` lies inside every edge line (stops at the first it lies outside of).
#[inline]
fn contains(edges: &[PieceEdge], p: Vec3) -> bool {
    edges.iter().all(|e| e.offset - e.inward.dot(p) <= 0.0)
}

/// The distance from `p` to a piece of `edges` (its nearest point on an edge when outside).
fn distance(edges: &[PieceEdge], p: Vec3) -> f32 {
    if contains(edges, p) {
        return 0.0;
    }
    (0..edges.len())
        .map(|i| segment_distance(p, edges[i].from, edges[(i + 1) % edges.len()].from))
        .fold(f32::INFINITY, f32::min)
}

/// The distance from `p` to the segment `ab`.
fn segment_distance(p: Vec3, a: Vec3, b: Vec3) -> f32 {
    let ab = b - a;
    let length2 = ab.length_squared();
    let t = if length2 > 0.0 {
        ((p - a).dot(ab) / length2).clamp(0.0, 1.0)
    } else {
        0.0
    };
    p.distance(a + ab * t)
}

/// Whether a cut face's pieces cover it all, or the split dropped part of it (the hidden copy
/// of a coincident face).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum Coverage {
    /// The pieces tile the whole face: every point of it is on the nearest piece, however far
    /// rounding puts it off (far from the origin an f32 step can be coarser than the tolerance).
    Whole,
    /// Part of the face was dropped: a point farther than the tolerance from every piece lies
    /// there, and a ray passes.
    Dropped,
}

/// One face's pieces: their range in the index's pieces, and whether they cover the face.
#[derive(Clone, Copy, Debug)]
struct PieceList {
    start: u32,
    end: u32,
    coverage: Coverage,
}

/// Every cut face's pieces, as convex outlines.
#[derive(Clone, Debug, Default)]
pub(crate) struct PieceIndex {
    lists: Vec<PieceList>,
    pieces: Vec<PiecePolygon>,
    edges: Vec<PieceEdge>,
    /// Points within this of a piece lie on it (the partition's tolerance).
    tolerance: f32,
}

impl PieceIndex {
    /// An empty index whose points lie on a piece within `tolerance` (metres).
    pub(crate) fn new(tolerance: f32) -> Self {
        PieceIndex {
            lists: Vec::new(),
            pieces: Vec::new(),
            edges: Vec::new(),
            tolerance,
        }
    }

    /// Adds the pieces of a face of unit normal `normal` (convex outlines in the face's plane
    /// with their parts; outlines of no area are skipped), which cover it as `coverage` says,
    /// and returns the part value its triangles' records carry: [`PIECES`] plus the list's
    /// index. `None` when no piece has area, or past 2³¹ lists, pieces or edges.
    pub(crate) fn push<'a>(
        &mut self,
        normal: Vec3,
        coverage: Coverage,
        pieces: impl IntoIterator<Item = (&'a [Vec3], PartSurface)>,
    ) -> Option<PartId> {
        let index = u32::try_from(self.lists.len()).ok().filter(|&i| i < PIECES)?;
        let start = u32::try_from(self.pieces.len()).ok()?;
        let mut edges = Vec::new();
        let mut areas = Vec::new();
        for (polygon, part) in pieces {
            let Some(area) = outline_edges(polygon, normal, self.tolerance, &mut edges) else {
                continue;
            };
            let first = u32::try_from(self.edges.len()).ok()?;
            let end = u32::try_from(self.edges.len() + edges.len()).ok()?;
            self.edges.extend_from_slice(&edges);
            self.pieces.push(PiecePolygon { first, end, part });
            areas.push(area);
        }
        let end = u32::try_from(self.pieces.len()).ok()?;
        if end == start {
            return None;
        }
        // Largest first: a hit lands in a piece in proportion to its area, so the search
        // mostly ends at the first one or two. Stable, so equal areas keep the pieces' order.
        let mut order: Vec<usize> = (0..areas.len()).collect();
        order.sort_by(|&a, &b| areas[b].total_cmp(&areas[a]));
        let listed = &mut self.pieces[start as usize..];
        let sorted: Vec<PiecePolygon> = order.iter().map(|&i| listed[i]).collect();
        listed.copy_from_slice(&sorted);
        self.lists.push(PieceList { start, end, coverage });
        Some(PartId(PIECES | index))
    }

    /// Frees the room the lists grew into: the index lives as long as the scene.
    pub(crate) fn shrink_to_fit(&mut self) {
        self.lists.shrink_to_fit();
        self.pieces.shrink_to_fit();
        self.edges.shrink_to_fit();
    }

    /// The edges of `piece`.
    #[inline]
    fn edges_of(&self, piece: &PiecePolygon) -> &[PieceEdge] {
        &self.edges[piece.first as usize..piece.end as usize]
    }

    /// The part of the piece of list `list` (a record's part without [`PIECES`]) that
    /// contains `p` (the larger, on an edge two share; `p` lies in the face's plane), else the
    /// nearest; `None` when part of the face was dropped ([`Coverage::Dropped`]) and `p` lies
    /// farther than the tolerance from every piece.
    #[inline]
    pub(crate) fn locate(&self, list: u32, p: Vec3) -> Option<PartSurface> {
        let PieceList { start, end, coverage } = self.lists[list as usize];
        let pieces = &self.pieces[start as usize..end as usize];
        if let Some(piece) = pieces.iter().find(|piece| contains(self.edges_of(piece), p)) {
            return Some(piece.part);
        }
        let reach = match coverage {
            Coverage::Whole => f32::INFINITY,
            Coverage::Dropped => self.tolerance,
        };
        // Off every piece: the nearest by true distance (the edge lines' bound would take in
        // points well past a sliver's tip).
        let mut best = (reach, None);
        for piece in pieces {
            let edges = self.edges_of(piece);
            if outside(edges, p) <= best.0 {
                let d = distance(edges, p);
                if d <= best.0 {
                    best = (d, Some(piece.part));
                }
            }
        }
        best.1
    }

    /// Heap bytes held.
    pub(crate) fn heap_bytes(&self) -> usize {
        self.lists.capacity() * size_of::<PieceList>()
            + self.pieces.capacity() * size_of::<PiecePolygon>()
            + self.edges.capacity() * size_of::<PieceEdge>()
    }
}

#[cfg(test)]
mod tests;
