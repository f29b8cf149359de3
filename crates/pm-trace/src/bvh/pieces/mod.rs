//! Faces searched as the user gave them, their parts found among the pieces the contact
//! partition cut them into. A ray meets the original triangle (so the split never changes what
//! a ray hits, and no sliver piece loses precision); where the face was cut into pieces of
//! different parts, the point hit is located among its pieces to give the part — and so the
//! photon map — it lies in.
//!
//! A triangle whose face lies in one part keeps that part in its record as before. A triangle
//! of a cut face carries [`PIECES`] plus the index of its face's first row in the record's
//! part instead; [`PieceIndex::locate`] finds the piece (a convex face of the split scene, as
//! its outline's edge lines, without the T-junction corners the split put along its edges)
//! that contains the point, or else the nearest within the tolerance. A point farther than that
//! from every piece lies where the partition dropped the face (the hidden copy of a coincident
//! face): the ray passes there, and meets the copy that was kept at the same distance.

use crate::part::{PartId, PartSurface};
use glam::Vec3;
use pm_geom::polygon_vector_area;

/// Set in a triangle record's part when its face is cut into pieces: the rest of the bits
/// index the face's first row in the [`PieceIndex`].
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
fn outside(lines: &[Row], p: Vec3) -> f32 {
    lines
        .iter()
        .map(|l| l.outside(p))
        .fold(f32::NEG_INFINITY, f32::max)
}

/// Whether `p` lies inside every edge line (stops at the first it lies outside of).
#[inline]
fn contains(lines: &[Row], p: Vec3) -> bool {
    lines.iter().all(|l| l.outside(p) <= 0.0)
}

/// The distance from `p` to a piece of edge `lines` whose edges start at `corners` (its
/// nearest point on an edge when outside).
fn distance(lines: &[Row], corners: &[Vec3], p: Vec3) -> f32 {
    if contains(lines, p) {
        return 0.0;
    }
    (0..corners.len())
        .map(|i| segment_distance(p, corners[i], corners[(i + 1) % corners.len()]))
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

/// One 16-byte row of the index, as four words. A cut face's rows follow one another: its
/// header (piece count, [`Coverage`]), then for each piece, largest first, the piece's header
/// (part, surface, edge count, where its corners start in [`PieceIndex::corners`]) and one row
/// per edge line (the inward unit normal's bits and
/// the offset's, so that `offset - inward·p` is how far `p` lies outside it). So locating a
/// point reads one run of memory from where its triangle's record points, rather than a list,
/// then its pieces, then their edges, each somewhere else: on the obvhs kitchen that took a
/// third off the lookup's time (4.5 % to 3.4 % of a photon-map run's samples, one thread).
#[derive(Clone, Copy, Debug, Default)]
#[repr(C, align(16))]
struct Row([u32; 4]);

impl Row {
    fn face(pieces: u32, coverage: Coverage) -> Row {
        Row([pieces, coverage as u32, 0, 0])
    }

    fn piece(part: PartSurface, edges: u32, first_corner: u32) -> Row {
        Row([part.part.0, part.surface, edges, first_corner])
    }

    fn line(inward: Vec3, offset: f32) -> Row {
        Row([inward.x, inward.y, inward.z, offset].map(f32::to_bits))
    }

    /// A face header's piece count and coverage.
    #[inline]
    fn face_header(self) -> (usize, Coverage) {
        let coverage = if self.0[1] == Coverage::Whole as u32 {
            Coverage::Whole
        } else {
            Coverage::Dropped
        };
        (self.0[0] as usize, coverage)
    }

    /// A piece header's part, edge count and first corner.
    #[inline]
    fn piece_header(self) -> (PartSurface, usize, usize) {
        let part = PartSurface {
            part: PartId(self.0[0]),
            surface: self.0[1],
        };
        (part, self.0[2] as usize, self.0[3] as usize)
    }

    /// How far `p` lies outside this edge line.
    #[inline]
    fn outside(self, p: Vec3) -> f32 {
        let [x, y, z, offset] = self.0.map(f32::from_bits);
        offset - Vec3::new(x, y, z).dot(p)
    }
}

/// Every cut face's pieces, as convex outlines: [`Row`]s, and the corners their edges start
/// from.
#[derive(Clone, Debug, Default)]
pub(crate) struct PieceIndex {
    rows: Vec<Row>,
    /// Each piece's corners in the order of its edge lines (read only for a point off every
    /// piece).
    corners: Vec<Vec3>,
    /// Points within this of a piece lie on it (the partition's tolerance).
    tolerance: f32,
}

impl PieceIndex {
    /// An empty index whose points lie on a piece within `tolerance` (metres).
    pub(crate) fn new(tolerance: f32) -> Self {
        PieceIndex {
            rows: Vec::new(),
            corners: Vec::new(),
            tolerance,
        }
    }

    /// Adds the pieces of a face of unit normal `normal` (convex outlines in the face's plane
    /// with their parts; outlines of no area are skipped), which cover it as `coverage` says,
    /// and returns the part value its triangles' records carry: [`PIECES`] plus the index of
    /// the face's first row. `None` when no piece has area, or past 2³¹ rows.
    pub(crate) fn push<'a>(
        &mut self,
        normal: Vec3,
        coverage: Coverage,
        pieces: impl IntoIterator<Item = (&'a [Vec3], PartSurface)>,
    ) -> Option<PartId> {
        let mut edges = Vec::new();
        let mut outlines: Vec<(f32, PartSurface, Vec<PieceEdge>)> = Vec::new();
        for (polygon, part) in pieces {
            if let Some(area) = outline_edges(polygon, normal, self.tolerance, &mut edges) {
                outlines.push((area, part, std::mem::take(&mut edges)));
            }
        }
        if outlines.is_empty() {
            return None;
        }
        let rows = 1 + outlines.iter().map(|o| 1 + o.2.len()).sum::<usize>();
        let first = u32::try_from(self.rows.len()).ok().filter(|&i| i < PIECES)?;
        u32::try_from(self.rows.len() + rows)
            .ok()
            .filter(|&end| end <= PIECES)?;
        u32::try_from(self.corners.len() + rows).ok()?;
        // Largest first: a hit lands in a piece in proportion to its area, so the search
        // mostly ends at the first one or two. Stable, so equal areas keep the pieces' order.
        outlines.sort_by(|a, b| b.0.total_cmp(&a.0));
        self.rows.push(Row::face(outlines.len() as u32, coverage));
        for (_, part, edges) in outlines {
            self.rows
                .push(Row::piece(part, edges.len() as u32, self.corners.len() as u32));
            for e in edges {
                self.rows.push(Row::line(e.inward, e.offset));
                self.corners.push(e.from);
            }
        }
        Some(PartId(PIECES | first))
    }

    /// Frees the room the rows grew into: the index lives as long as the scene.
    pub(crate) fn shrink_to_fit(&mut self) {
        self.rows.shrink_to_fit();
        self.corners.shrink_to_fit();
    }

    /// Calls `visit(part, lines, corners)` for each piece of the face whose first row is
    /// `face`, largest first, until it returns `Some`.
    #[inline]
    fn find_piece<T>(
        &self,
        face: u32,
        mut visit: impl FnMut(PartSurface, &[Row], &[Vec3]) -> Option<T>,
    ) -> Option<T> {
        let (pieces, _) = self.rows[face as usize].face_header();
        let mut at = face as usize + 1;
        for _ in 0..pieces {
            let (part, edges, corner) = self.rows[at].piece_header();
            let (lines, corners) = (at + 1..at + 1 + edges, corner..corner + edges);
            if let Some(found) = visit(part, &self.rows[lines], &self.corners[corners]) {
                return Some(found);
            }
            at += 1 + edges;
        }
        None
    }

    /// The part of the piece of the face whose first row is `face` (a record's part without
    /// [`PIECES`]) that contains `p` (the larger, on an edge two share; `p` lies in the face's
    /// plane), else the nearest; `None` when part of the face was dropped
    /// ([`Coverage::Dropped`]) and `p` lies farther than the tolerance from every piece.
    #[inline]
    pub(crate) fn locate(&self, face: u32, p: Vec3) -> Option<PartSurface> {
        let inside = self.find_piece(face, |part, lines, _| contains(lines, p).then_some(part));
        if inside.is_some() {
            return inside;
        }
        let reach = match self.rows[face as usize].face_header().1 {
            Coverage::Whole => f32::INFINITY,
            Coverage::Dropped => self.tolerance,
        };
        // Off every piece: the nearest by true distance (the edge lines' bound would take in
        // points well past a sliver's tip).
        let mut best = (reach, None);
        self.find_piece(face, |part, lines, corners| {
            if outside(lines, p) <= best.0 {
                let d = distance(lines, corners, p);
                if d <= best.0 {
                    best = (d, Some(part));
                }
            }
            None::<()>
        });
        best.1
    }

    /// Heap bytes held.
    pub(crate) fn heap_bytes(&self) -> usize {
        self.rows.capacity() * size_of::<Row>() + self.corners.capacity() * size_of::<Vec3>()
    }

    /// Edge lines held (rows that are neither a face's nor a piece's header).
    #[cfg(test)]
    fn edge_lines(&self) -> usize {
        let mut lines = 0;
        let mut at = 0;
        while at < self.rows.len() {
            let (pieces, _) = self.rows[at].face_header();
            at += 1;
            for _ in 0..pieces {
                let edges = self.rows[at].piece_header().1;
                lines += edges;
                at += 1 + edges;
            }
        }
        lines
    }
}

#[cfg(test)]
mod tests;
