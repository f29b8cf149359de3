//! Which face lies across each edge of each input polygon: the faces of one modelled surface
//! (a tessellated floor, the bottom of a rounded object) share their edges, and a near-contact
//! is outlined only where that surface stops coming close, not along every edge inside it.

use glam::Vec3;

/// No face across an edge: a border, or an edge that more than two faces share.
pub(super) const NO_FACE: u32 = u32::MAX;

/// The most edges with one hash that are compared with each other.
const CROWD: usize = 16;

/// For every edge of every polygon (edge `k` runs from vertex `k` to `k + 1`), the polygon
/// across it: the one other polygon with an edge between the same two points (bit for bit, as
/// a welded mesh gives them), or [`NO_FACE`].
pub(super) struct EdgeNeighbours {
    /// Index of each polygon's first edge in `across`, and the total at the end.
    first: Vec<usize>,
    across: Vec<u32>,
}

impl EdgeNeighbours {
    /// Finds the shared edges by sorting the edges on a hash of their end points and comparing
    /// the end points of equal hashes: `O(e log e)` time and 20 bytes per edge while it runs.
    pub(super) fn new<P: AsRef<[Vec3]>>(polygons: &[P]) -> Self {
        let mut first = Vec::with_capacity(polygons.len() + 1);
        let mut total = 0usize;
        for p in polygons {
            first.push(total);
            total += p.as_ref().len();
        }
        first.push(total);
        let ends = |e: u32, p: u32| -> (Vec3, Vec3) {
            let polygon = polygons[p as usize].as_ref();
            let k = e as usize - first[p as usize];
            (polygon[k], polygon[(k + 1) % polygon.len()])
        };
        let mut keyed: Vec<(u64, u32, u32)> = Vec::with_capacity(total);
        for (p, polygon) in polygons.iter().enumerate() {
            let polygon = polygon.as_ref();
            for k in 0..polygon.len() {
                let (a, b) = (polygon[k], polygon[(k + 1) % polygon.len()]);
                keyed.push((edge_key(a, b), (first[p] + k) as u32, p as u32));
            }
        }
        // Edge indices are unique, so the order is the (hash, edge) order.
        keyed.sort_unstable();
        let mut across = vec![NO_FACE; total];
        // The other edge of each run of two (most shared edges), checked below in edge order:
        // read in the hash's order, each check was a cache miss (3.9 s of the split's 4.7 s
        // on a million quads).
        let mut partner = vec![NO_FACE; total];
        let mut start = 0;
        while start < keyed.len() {
            let mut end = start + 1;
            while end < keyed.len() && keyed[end].0 == keyed[start].0 {
                end += 1;
            }
            // Within one hash, the edges between the same two points; a hash collision of
            // different edges only splits the run further. More than `CROWD` edges in one run
            // are many faces on one edge (no neighbour), so the comparison stays bounded. A
            // run of one is a border.
            let run = &keyed[start..end];
            if run.len() == 2 {
                partner[run[0].1 as usize] = run[1].1;
            } else if (3..=CROWD).contains(&run.len()) {
                for &(_, e, p) in run {
                    let (a, b) = ends(e, p);
                    let mut same = run.iter().filter(|&&(_, f, q)| {
                        let (c, d) = ends(f, q);
                        f != e && ((a == c && b == d) || (a == d && b == c))
                    });
                    if let (Some(&(_, _, other)), None) = (same.next(), same.next()) {
                        across[e as usize] = other;
                    }
                }
            }
            start = end;
        }
        drop(keyed);
        for p in 0..polygons.len() {
            for e in first[p]..first[p + 1] {
                let f = partner[e];
                if f == NO_FACE {
                    continue;
                }
                let q = first.partition_point(|&x| x <= f as usize) - 1;
                let ((a, b), (c, d)) = (ends(e as u32, p as u32), ends(f, q as u32));
                if (a == c && b == d) || (a == d && b == c) {
                    across[e] = q as u32;
                    across[f as usize] = p as u32;
                }
            }
        }
        EdgeNeighbours { first, across }
    }

    /// The polygon across each edge of polygon `p`, in edge order.
    pub(super) fn of(&self, p: usize) -> &[u32] {
        &self.across[self.first[p]..self.first[p + 1]]
    }
}

/// A hash of an edge's end points that does not depend on the edge's direction.
fn edge_key(a: Vec3, b: Vec3) -> u64 {
    let point = |p: Vec3| {
        let mut h = 0xcbf2_9ce4_8422_2325u64;
        for c in p.to_array() {
            h = (h ^ u64::from(c.to_bits())).wrapping_mul(0x0000_0100_0000_01b3);
        }
        h ^ (h >> 29)
    };
    let (x, y) = (point(a), point(b));
    x.min(y).wrapping_mul(0x9e37_79b9_7f4a_7c15) ^ x.max(y)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn faces_sharing_an_edge_see_each_other_and_borders_see_none() {
        // Two triangles of a unit square, a third triangle on the diagonal's far side sharing
        // nothing, and a fan of three faces on one edge (non-manifold: no neighbour).
        let v = |x: f32, y: f32| Vec3::new(x, y, 0.0);
        let polygons = vec![
            vec![v(0.0, 0.0), v(1.0, 0.0), v(1.0, 1.0)],
            vec![v(0.0, 0.0), v(1.0, 1.0), v(0.0, 1.0)],
            vec![v(5.0, 0.0), v(6.0, 0.0), v(5.0, 1.0)],
            vec![v(5.0, 0.0), v(6.0, 0.0), Vec3::new(5.0, 0.0, 1.0)],
            vec![v(6.0, 0.0), v(5.0, 0.0), Vec3::new(5.0, 0.0, -1.0)],
        ];
        let n = EdgeNeighbours::new(&polygons);
        assert_eq!(n.of(0), &[NO_FACE, NO_FACE, 1]);
        assert_eq!(n.of(1), &[0, NO_FACE, NO_FACE]);
        assert_eq!(n.of(2)[0], NO_FACE, "three faces on one edge");
        assert_eq!(n.of(3)[0], NO_FACE);
        assert_eq!(n.of(4)[0], NO_FACE);
    }

    #[test]
    fn a_grid_finds_every_inner_edge_as_brute_force_does() {
        let size = 7;
        let mut polygons = Vec::new();
        for i in 0..size {
            for j in 0..size {
                let p = |x: usize, y: usize| Vec3::new(x as f32 * 0.1, y as f32 * 0.1, 0.3);
                polygons.push(vec![p(i, j), p(i + 1, j), p(i + 1, j + 1)]);
                polygons.push(vec![p(i, j), p(i + 1, j + 1), p(i, j + 1)]);
            }
        }
        let n = EdgeNeighbours::new(&polygons);
        for (p, poly) in polygons.iter().enumerate() {
            for k in 0..3 {
                let (a, b) = (poly[k], poly[(k + 1) % 3]);
                let brute: Vec<usize> = (0..polygons.len())
                    .filter(|&q| q != p)
                    .filter(|&q| {
                        (0..3).any(|m| {
                            let (c, d) = (polygons[q][m], polygons[q][(m + 1) % 3]);
                            (a == c && b == d) || (a == d && b == c)
                        })
                    })
                    .collect();
                let expected = if let [q] = brute[..] { q as u32 } else { NO_FACE };
                assert_eq!(n.of(p)[k], expected, "polygon {p} edge {k}");
            }
        }
    }
}
