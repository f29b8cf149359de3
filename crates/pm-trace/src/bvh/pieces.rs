//! Faces searched as the user gave them, their parts found among the pieces the contact
//! partition cut them into. A ray meets the original triangle (so the split never changes what
//! a ray hits, and no sliver piece loses precision); where the face was cut into pieces of
//! different parts, the point hit is located among its pieces to give the part — and so the
//! photon map — it lies in.
//!
//! A triangle whose face lies in one part keeps that part in its record as before. A triangle
//! of a cut face carries [`PIECES`] plus the index of its face's piece list in the record's
//! part instead; [`PieceIndex::locate`] finds the piece (a triangle of the split scene) that
//! contains the point, or else the nearest within the tolerance. A point farther than that
//! from every piece lies where the partition dropped the face (the hidden copy of a coincident
//! face): the ray passes there, and meets the copy that was kept at the same distance.

use crate::part::{PartId, PartSurface};
use glam::Vec3;

/// Set in a triangle record's part when its face is cut into pieces: the rest of the bits
/// index the face's piece list.
pub(crate) const PIECES: u32 = 1 << 31;

/// One piece triangle: its corners, its three edges' inward unit normals (in its plane) and
/// their offsets, so that `offset[i] - inward[i]·p` is how far `p` lies outside edge i, and
/// its part.
#[derive(Clone, Copy, Debug)]
struct PieceTriangle {
    v: [Vec3; 3],
    inward: [Vec3; 3],
    offset: [f32; 3],
    part: PartSurface,
}

impl PieceTriangle {
    /// A triangle's edge planes about its face's unit normal `n` (not its own: a fan
    /// triangle of three nearly collinear corners has a normal that rounding points anywhere,
    /// and edge planes about it would take in points far off); `None` when an edge has no
    /// length or the triangle no area.
    fn new(v: &[Vec3; 3], n: Vec3, part: PartSurface) -> Option<Self> {
        let winding = (v[1] - v[0]).cross(v[2] - v[0]).dot(n);
        if !(winding != 0.0 && winding.is_finite()) {
            return None;
        }
        let n = if winding > 0.0 { n } else { -n };
        let mut inward = [Vec3::ZERO; 3];
        let mut offset = [0.0; 3];
        for i in 0..3 {
            let (a, b) = (v[i], v[(i + 1) % 3]);
            inward[i] = n.cross(b - a).try_normalize()?;
            offset[i] = inward[i].dot(a);
        }
        Some(PieceTriangle {
            v: *v,
            inward,
            offset,
            part,
        })
    }

    /// How far `p` lies outside the triangle's edge lines (≤ 0 inside: in its plane, `p` is
    /// then on the triangle; a positive value is only a lower bound of the distance, which
    /// past a sliver's sharp corner is far larger).
    #[inline]
    fn outside(&self, p: Vec3) -> f32 {
        (self.offset[0] - self.inward[0].dot(p))
            .max(self.offset[1] - self.inward[1].dot(p))
            .max(self.offset[2] - self.inward[2].dot(p))
    }

    /// The triangle's area.
    fn area(&self) -> f32 {
        (self.v[1] - self.v[0]).cross(self.v[2] - self.v[0]).length() * 0.5
    }

    /// The distance from `p` to the triangle (its nearest point on an edge when outside).
    fn distance(&self, p: Vec3) -> f32 {
        if self.outside(p) <= 0.0 {
            return 0.0;
        }
        (0..3)
            .map(|i| segment_distance(p, self.v[i], self.v[(i + 1) % 3]))
            .fold(f32::INFINITY, f32::min)
    }
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

/// One face's pieces: their range in the index's triangles, and whether they cover the face.
#[derive(Clone, Copy, Debug)]
struct PieceList {
    start: u32,
    end: u32,
    coverage: Coverage,
}

/// Every cut face's pieces, as lists of triangles.
#[derive(Clone, Debug, Default)]
pub(crate) struct PieceIndex {
    lists: Vec<PieceList>,
    triangles: Vec<PieceTriangle>,
    /// Points within this of a piece lie on it (the partition's tolerance).
    tolerance: f32,
}

impl PieceIndex {
    /// An empty index whose points lie on a piece within `tolerance` (metres).
    pub(crate) fn new(tolerance: f32) -> Self {
        PieceIndex {
            lists: Vec::new(),
            triangles: Vec::new(),
            tolerance,
        }
    }

    /// Adds the pieces of a face of unit normal `normal` (triangles with their parts;
    /// degenerate ones are skipped), which cover it as `coverage` says, and returns the part value its triangles' records carry:
    /// [`PIECES`] plus the list's index. `None` when no piece has area, or past 2³¹ lists or
    /// triangles.
    pub(crate) fn push(
        &mut self,
        normal: Vec3,
        coverage: Coverage,
        pieces: impl IntoIterator<Item = ([Vec3; 3], PartSurface)>,
    ) -> Option<PartId> {
        let index = u32::try_from(self.lists.len()).ok().filter(|&i| i < PIECES)?;
        let start = u32::try_from(self.triangles.len()).ok()?;
        self.triangles.extend(
            pieces
                .into_iter()
                .filter_map(|(v, part)| PieceTriangle::new(&v, normal, part)),
        );
        let end = u32::try_from(self.triangles.len()).ok()?;
        // Largest first: a hit lands in a piece in proportion to its area, so the search
        // mostly ends at the first few (a cut floor's fan triangles run to a hundred, most of
        // them slivers). Stable, so equal areas keep the pieces' order.
        self.triangles[start as usize..].sort_by(|a, b| b.area().total_cmp(&a.area()));
        if end == start {
            return None;
        }
        self.lists.push(PieceList { start, end, coverage });
        Some(PartId(PIECES | index))
    }

    /// Frees the room the lists grew into: the index lives as long as the scene.
    pub(crate) fn shrink_to_fit(&mut self) {
        self.lists.shrink_to_fit();
        self.triangles.shrink_to_fit();
    }

    /// The part of the piece of list `list` (a record's part without [`PIECES`]) that
    /// contains `p` (the larger, on an edge two share; `p` lies in the face's plane), else the
    /// nearest; `None` when part of the face was dropped ([`Coverage::Dropped`]) and `p` lies
    /// farther than the tolerance from every piece.
    #[inline]
    pub(crate) fn locate(&self, list: u32, p: Vec3) -> Option<PartSurface> {
        let PieceList { start, end, coverage } = self.lists[list as usize];
        let reach = match coverage {
            Coverage::Whole => f32::INFINITY,
            Coverage::Dropped => self.tolerance,
        };
        let mut best = (reach, None);
        let pieces = &self.triangles[start as usize..end as usize];
        if let Some(piece) = pieces.iter().find(|piece| piece.outside(p) <= 0.0) {
            return Some(piece.part);
        }
        // Off every piece: the nearest by true distance (the edge lines' bound would take in
        // points well past a sliver's tip).
        for piece in pieces {
            if piece.outside(p) <= best.0 {
                let d = piece.distance(p);
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
            + self.triangles.capacity() * size_of::<PieceTriangle>()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn part(p: u32) -> PartSurface {
        PartSurface {
            part: PartId(p),
            surface: 0,
        }
    }

    /// A unit square in z = 0 cut into a left and a right half (two triangles each): points
    /// are located in their half, edge points in the larger (the first listed of equals), points
    /// just off within the tolerance in the nearest, and points beyond it nowhere.
    #[test]
    fn locates_points_among_pieces() {
        let (a, b, c, d, e, f) = (
            Vec3::new(0.0, 0.0, 0.0),
            Vec3::new(0.5, 0.0, 0.0),
            Vec3::new(0.5, 1.0, 0.0),
            Vec3::new(0.0, 1.0, 0.0),
            Vec3::new(1.0, 0.0, 0.0),
            Vec3::new(1.0, 1.0, 0.0),
        );
        let mut index = PieceIndex::new(1e-3);
        let id = index
            .push(
                Vec3::Z,
                Coverage::Dropped,
                [
                    ([a, b, c], part(1)),
                    ([a, c, d], part(1)),
                    ([b, e, f], part(2)),
                    ([b, f, c], part(2)),
                ],
            )
            .unwrap();
        assert_eq!(id.0, PIECES);
        let list = id.0 & !PIECES;
        assert_eq!(index.locate(list, Vec3::new(0.2, 0.7, 0.0)), Some(part(1)));
        assert_eq!(index.locate(list, Vec3::new(0.8, 0.1, 0.0)), Some(part(2)));
        assert_eq!(index.locate(list, Vec3::new(0.5, 0.5, 0.0)), Some(part(1)));
        assert_eq!(index.locate(list, Vec3::new(1.0005, 0.5, 0.0)), Some(part(2)));
        assert_eq!(index.locate(list, Vec3::new(1.01, 0.5, 0.0)), None);
        // Pieces that cover their face: a point rounded off them is on the nearest.
        let whole = index
            .push(
                Vec3::Z,
                Coverage::Whole,
                [([a, b, c], part(1)), ([b, e, f], part(2))],
            )
            .unwrap()
            .0
            & !PIECES;
        assert_eq!(index.locate(whole, Vec3::new(1.01, 0.5, 0.0)), Some(part(2)));
        assert_eq!(index.locate(whole, Vec3::new(-3.0, 0.9, 0.0)), Some(part(1)));
    }

    /// A fan triangle of three corners on one line (a piece outline with a T-junction vertex)
    /// contains no point off that line, however rounding tilts its own normal.
    #[test]
    fn collinear_fan_triangles_contain_nothing() {
        let mut index = PieceIndex::new(1e-6);
        let line = [
            Vec3::new(3.42, 2.44, -1.83),
            Vec3::new(3.42, 2.44, -1.79),
            Vec3::new(3.42, 2.44, -1.74),
        ];
        let square = [
            Vec3::new(3.0, 2.44, -1.0),
            Vec3::new(3.0, 2.44, -0.9),
            Vec3::new(2.9, 2.44, -0.9),
        ];
        let list = index
            .push(Vec3::Y, Coverage::Dropped, [(line, part(1)), (square, part(2))])
            .unwrap()
            .0
            & !PIECES;
        assert_eq!(index.locate(list, Vec3::new(3.0, 2.44, 0.5)), None);
        assert_eq!(index.locate(list, Vec3::new(2.97, 2.44, -0.92)), Some(part(2)));
    }
}
