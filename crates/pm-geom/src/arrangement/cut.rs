//! Cutting one convex face along the lines where other faces meet it into convex pieces, with
//! the contact points inserted on the new edges so that the meeting face's edge is shared after
//! welding.

use crate::clip::split_convex_polygon_by_distance;
use glam::Vec3;

/// A cut of one face: a line in the face's plane and the contact points on it.
#[derive(Clone, Debug)]
pub(super) struct Cut {
    pub(super) point: Vec3,
    pub(super) direction: Vec3,
    pub(super) contacts: Vec<Vec3>,
}

/// Adds a cut through `c0`–`c1`, merging it with an existing cut along the same line; returns
/// where the two contact points went (the cut's index, the first point's index in its
/// contacts), or `None` for a segment too short to have a direction.
pub(super) fn add_cut(cuts: &mut Vec<Cut>, c0: Vec3, c1: Vec3, tolerance: f32) -> Option<(usize, usize)> {
    let direction = (c1 - c0).try_normalize()?;
    let on_line =
        |cut: &Cut, p: Vec3| (p - cut.point).reject_from_normalized(cut.direction).length() <= tolerance;
    if let Some(index) = cuts.iter().position(|cut| on_line(cut, c0) && on_line(cut, c1)) {
        let contacts = &mut cuts[index].contacts;
        contacts.extend([c0, c1]);
        Some((index, contacts.len() - 2))
    } else {
        cuts.push(Cut {
            point: c0,
            direction,
            contacts: vec![c0, c1],
        });
        Some((cuts.len() - 1, 0))
    }
}

/// Cuts a convex face along all its `cuts` into convex pieces: each cut splits, along its line,
/// every piece that one of its contact segments runs through, adding the contact points to the
/// new edge on both sides. Pieces the line crosses away from the segments are left whole (the
/// line ends at their border, a T-junction that the junction pass resolves), so a face met
/// along many short segments is not cut into a grid. A grid over the face finds the pieces near
/// a segment, so the work grows with the pieces a cut touches, not with all of the face's.
/// `check(pieces)` is asked after each cut and stops the work with its error.
pub(super) fn cut_face<E>(
    polygon: &[Vec3],
    cuts: &[Cut],
    normal: Vec3,
    tolerance: f32,
    mut check: impl FnMut(usize) -> Result<(), E>,
) -> Result<Vec<Vec<Vec3>>, E> {
    let mut pieces = vec![polygon.to_vec()];
    let grid = PieceGrid::new(polygon, normal, cuts.len());
    let mut cells: Vec<Vec<u32>> = vec![Vec::new(); grid.cells()];
    grid.register(&pieces[0], 0, &mut cells);
    let mut seen: Vec<usize> = vec![usize::MAX];
    let mut candidates: Vec<u32> = Vec::new();
    let mut distances: Vec<f32> = Vec::new();
    for (k, cut) in cuts.iter().enumerate() {
        let Some(side) = normal.cross(cut.direction).try_normalize() else {
            continue;
        };
        let offset = side.dot(cut.point);
        candidates.clear();
        for segment in cut.contacts.chunks_exact(2) {
            for cell in grid.cells_over(segment) {
                for &i in &cells[cell] {
                    if seen[i as usize] != k {
                        seen[i as usize] = k;
                        candidates.push(i);
                    }
                }
            }
        }
        candidates.sort_unstable();
        for &index in &candidates {
            let piece = &pieces[index as usize];
            if !crossed_by_contacts(piece, normal, &cut.contacts, tolerance) {
                continue;
            }
            distances.clear();
            distances.extend(piece.iter().map(|&p| side.dot(p) - offset));
            let has_front = distances.iter().any(|&d| d > tolerance);
            let has_back = distances.iter().any(|&d| d < -tolerance);
            if !(has_front && has_back) {
                continue;
            }
            let (mut front, mut back) = (Vec::new(), Vec::new());
            split_convex_polygon_by_distance(
                piece,
                |p| side.dot(p) - offset,
                tolerance,
                &mut front,
                &mut back,
            );
            if front.is_empty() || back.is_empty() {
                continue;
            }
            insert_points_on_edges(&mut front, &cut.contacts, tolerance);
            insert_points_on_edges(&mut back, &cut.contacts, tolerance);
            // The front lies within the old piece's cells; the back is registered anew.
            pieces[index as usize] = front;
            grid.register(&back, pieces.len() as u32, &mut cells);
            pieces.push(back);
            seen.push(k);
        }
        check(pieces.len())?;
    }
    Ok(pieces)
}

/// A uniform grid over a face's plane, about √cuts cells a side, for [`cut_face`].
struct PieceGrid {
    u: Vec3,
    v: Vec3,
    min: (f32, f32),
    cell: (f32, f32),
    side: usize,
}

impl PieceGrid {
    fn new(polygon: &[Vec3], normal: Vec3, cuts: usize) -> Self {
        let (u, v) = normal.any_orthonormal_pair();
        let (mut lo, mut hi) = (
            (f32::INFINITY, f32::INFINITY),
            (f32::NEG_INFINITY, f32::NEG_INFINITY),
        );
        for &p in polygon {
            let (a, b) = (u.dot(p), v.dot(p));
            lo = (lo.0.min(a), lo.1.min(b));
            hi = (hi.0.max(a), hi.1.max(b));
        }
        let side = ((cuts as f32).sqrt().ceil() as usize).clamp(1, 512);
        let cell = (
            ((hi.0 - lo.0) / side as f32).max(f32::MIN_POSITIVE),
            ((hi.1 - lo.1) / side as f32).max(f32::MIN_POSITIVE),
        );
        PieceGrid {
            u,
            v,
            min: lo,
            cell,
            side,
        }
    }

    fn cells(&self) -> usize {
        self.side * self.side
    }

    /// The cell range (inclusive) over the points' bounds, clamped to the grid.
    fn range(&self, points: &[Vec3]) -> (usize, usize, usize, usize) {
        let index =
            |x: f32, lo: f32, cell: f32| (((x - lo) / cell).floor().max(0.0) as usize).min(self.side - 1);
        let (mut i0, mut i1, mut j0, mut j1) = (usize::MAX, 0, usize::MAX, 0);
        for &p in points {
            let (i, j) = (
                index(self.u.dot(p), self.min.0, self.cell.0),
                index(self.v.dot(p), self.min.1, self.cell.1),
            );
            (i0, i1, j0, j1) = (i0.min(i), i1.max(i), j0.min(j), j1.max(j));
        }
        // One cell of margin: points within the tolerance of a cell border.
        (
            i0.saturating_sub(1),
            (i1 + 1).min(self.side - 1),
            j0.saturating_sub(1),
            (j1 + 1).min(self.side - 1),
        )
    }

    fn cells_over(&self, points: &[Vec3]) -> impl Iterator<Item = usize> + '_ {
        let (i0, i1, j0, j1) = self.range(points);
        (j0..=j1).flat_map(move |j| (i0..=i1).map(move |i| j * self.side + i))
    }

    fn register(&self, piece: &[Vec3], index: u32, cells: &mut [Vec<u32>]) {
        for cell in self.cells_over(piece) {
            cells[cell].push(index);
        }
    }
}

/// Whether one of the segments `contacts[2k]`–`contacts[2k + 1]` runs through the inside of the
/// convex `piece` for more than the tolerance.
fn crossed_by_contacts(piece: &[Vec3], normal: Vec3, contacts: &[Vec3], tolerance: f32) -> bool {
    let pad = Vec3::splat(tolerance);
    let (lo, hi) = piece
        .iter()
        .fold((Vec3::INFINITY, Vec3::NEG_INFINITY), |(lo, hi), &p| {
            (lo.min(p), hi.max(p))
        });
    contacts.chunks_exact(2).any(|segment| {
        let (a, b) = (segment[0], segment[1]);
        if a.min(b).cmpgt(hi + pad).any() || a.max(b).cmplt(lo - pad).any() {
            return false;
        }
        let length = a.distance(b);
        let (mut t0, mut t1) = (0.0f32, 1.0f32);
        for i in 0..piece.len() {
            let (p, q) = (piece[i], piece[(i + 1) % piece.len()]);
            let Some(inward) = normal.cross(q - p).try_normalize() else {
                continue;
            };
            let (fa, fb) = (inward.dot(a - p) - tolerance, inward.dot(b - p) - tolerance);
            if fa < 0.0 && fb < 0.0 {
                return false;
            } else if fa < 0.0 {
                t0 = t0.max(fa / (fa - fb));
            } else if fb < 0.0 {
                t1 = t1.min(fa / (fa - fb));
            }
        }
        (t1 - t0) * length > tolerance
    })
}

/// Inserts each point of `points` that lies strictly inside an edge of `polygon` (within the
/// tolerance) into that edge, in order along it; points at existing vertices are skipped.
pub(super) fn insert_points_on_edges(polygon: &mut Vec<Vec3>, points: &[Vec3], tolerance: f32) {
    insert_points_by_edge(polygon, |_| points, tolerance);
}

/// [`insert_points_on_edges`] with each edge's own candidates: `points_near(i)` are the
/// points that may lie on edge `i` (from vertex `i` to the next); the others are not tested.
pub(super) fn insert_points_by_edge<'p>(
    polygon: &mut Vec<Vec3>,
    points_near: impl Fn(usize) -> &'p [Vec3],
    tolerance: f32,
) {
    let n = polygon.len();
    // The points inserted, by edge in order, found before the polygon is rebuilt: most pieces
    // gain none and keep their vector, and the others get one of exactly the size they need
    // (sized by the candidates instead, the pieces held a third of the split's peak memory).
    let mut inserted: Vec<(usize, Vec3)> = Vec::new();
    let mut on_edge: Vec<(f32, Vec3)> = Vec::new();
    for i in 0..n {
        let (a, b) = (polygon[i], polygon[(i + 1) % n]);
        let length = a.distance(b);
        if length <= tolerance {
            continue;
        }
        let direction = (b - a) / length;
        on_edge.clear();
        for &p in points_near(i) {
            let t = (p - a).dot(direction);
            if t > tolerance
                && t < length - tolerance
                && (p - a).reject_from_normalized(direction).length() <= tolerance
            {
                on_edge.push((t, a + direction * t));
            }
        }
        on_edge.sort_by(|x, y| x.0.total_cmp(&y.0));
        on_edge.dedup_by(|x, y| x.0 - y.0 <= tolerance);
        inserted.extend(on_edge.iter().map(|&(_, p)| (i, p)));
    }
    if inserted.is_empty() {
        return;
    }
    let mut result = Vec::with_capacity(n + inserted.len());
    let mut next = inserted.iter().peekable();
    for (i, &a) in polygon.iter().enumerate() {
        result.push(a);
        while let Some(&(_, p)) = next.next_if(|&&(edge, _)| edge == i) {
            result.push(p);
        }
    }
    *polygon = result;
}

#[cfg(test)]
mod tests {
    use super::insert_points_on_edges;
    use glam::Vec3;

    /// Points on an edge go in, in order along it; points off the edges, at a corner or
    /// within the tolerance of one that went in are left out; a polygon that gains none keeps
    /// its vertices as they were.
    #[test]
    fn points_on_edges_are_inserted_in_order_along_them() {
        let square = vec![Vec3::ZERO, Vec3::X, Vec3::new(1.0, 1.0, 0.0), Vec3::Y];
        let tolerance = 1e-4;
        let points = [
            Vec3::new(0.75, 0.0, 0.0),
            Vec3::new(0.25, 0.0, 0.0),
            Vec3::new(0.25 + 0.5e-4, 0.0, 0.0),
            Vec3::new(0.0, 0.5, 0.0),
            Vec3::new(0.5, 0.5, 0.0),
            Vec3::new(1.0, 1.0, 0.0),
            Vec3::new(0.5, 0.01, 0.0),
        ];
        let mut polygon = square.clone();
        insert_points_on_edges(&mut polygon, &points, tolerance);
        let expected = [
            Vec3::ZERO,
            Vec3::new(0.25, 0.0, 0.0),
            Vec3::new(0.75, 0.0, 0.0),
            Vec3::X,
            Vec3::new(1.0, 1.0, 0.0),
            Vec3::Y,
            Vec3::new(0.0, 0.5, 0.0),
        ];
        assert_eq!(polygon.len(), expected.len(), "{polygon:?}");
        for (got, want) in polygon.iter().zip(expected) {
            assert!(got.distance(want) < 1e-6, "{polygon:?}");
        }
        let mut untouched = square.clone();
        insert_points_on_edges(&mut untouched, &points[4..], tolerance);
        assert_eq!(untouched, square);
    }
}
