//! The fallback for coplanar regions that are not one convex polygon (an L-shaped floor, a
//! wall with a hole): greedily join neighbouring pieces across shared edges while convex.

use super::outline::{VertexKey, accepts, cancel_spikes, simplify_outline};
use glam::Vec3;
use std::collections::HashSet;

/// At most this many sweeps over a region's shared edges; each sweep after the first joins
/// the pieces the previous one grew (rows of a grid into strips, then strips into one).
const MAX_SWEEPS: usize = 16;

/// An edge `a → b` of piece `p` that piece `q` walks as `b → a` (indices into the region).
#[derive(Clone, Copy, Debug)]
pub(super) struct SharedEdge {
    pub(super) p: u32,
    pub(super) q: u32,
    pub(super) a: Vec3,
    pub(super) b: Vec3,
}

/// Joins the region's `polygons` (convex, coplanar about `normal`, with `areas`) across
/// `shared` edges while each union stays strictly convex with the summed area, and calls
/// `emit` with every resulting polygon (collinear vertices within `tol` removed).
pub(super) fn merge_region(
    polygons: Vec<Vec<Vec3>>,
    areas: &[f64],
    shared: &[SharedEdge],
    normal: Vec3,
    tol: f32,
    emit: &mut impl FnMut(&[Vec3]),
) {
    let mut pieces: Vec<Option<(Vec<Vec3>, f64)>> = polygons
        .into_iter()
        .zip(areas)
        .map(|(p, &a)| Some((p, a)))
        .collect();
    let mut parent: Vec<u32> = (0..pieces.len() as u32).collect();
    let mut failed: HashSet<(u32, u32)> = HashSet::new();
    let mut simplified = Vec::new();
    for _ in 0..MAX_SWEEPS {
        let mut joined = false;
        failed.clear();
        for e in shared {
            let (rp, rq) = (find(&mut parent, e.p), find(&mut parent, e.q));
            if rp == rq || failed.contains(&(rp, rq)) {
                continue;
            }
            let (Some((pp, pa)), Some((qq, qa))) = (&pieces[rp as usize], &pieces[rq as usize]) else {
                continue;
            };
            let area = pa + qa;
            match join(pp, qq, e.a, e.b) {
                Some(union) => {
                    simplify_outline(&union, tol, &mut simplified);
                    if accepts(&simplified, normal, area) {
                        pieces[rp as usize] = Some((union, area));
                        pieces[rq as usize] = None;
                        parent[rq as usize] = rp;
                        joined = true;
                        continue;
                    }
                    failed.insert((rp, rq));
                }
                None => {
                    failed.insert((rp, rq));
                }
            }
        }
        if !joined {
            break;
        }
    }
    for (outline, _) in pieces.into_iter().flatten() {
        simplify_outline(&outline, tol, &mut simplified);
        if simplified.len() >= 3 {
            emit(&simplified);
        } else {
            emit(&outline);
        }
    }
}

fn find(parent: &mut [u32], mut i: u32) -> u32 {
    while parent[i as usize] != i {
        let up = parent[parent[i as usize] as usize];
        parent[i as usize] = up;
        i = up;
    }
    i
}

/// The outline of `p ∪ q` where `p` has the edge `a → b` and `q` has `b → a`: `p` up to `a`,
/// then `q` from `a` round to `b`, then `p` from `b`, with shared edges walked both ways
/// cancelled. `None` when either outline lacks the edge.
fn join(p: &[Vec3], q: &[Vec3], a: Vec3, b: Vec3) -> Option<Vec<Vec3>> {
    let (ka, kb) = (VertexKey::of(a), VertexKey::of(b));
    let edge = |outline: &[Vec3], from: VertexKey, to: VertexKey| {
        let n = outline.len();
        (0..n).find(|&i| VertexKey::of(outline[i]) == from && VertexKey::of(outline[(i + 1) % n]) == to)
    };
    let i = edge(p, ka, kb)?;
    let j = edge(q, kb, ka)?;
    let (np, nq) = (p.len(), q.len());
    let mut union = Vec::with_capacity(np + nq);
    union.extend_from_slice(&p[..=i]);
    // q after a (at j + 1) up to, not including, b (at j).
    union.extend((2..nq).map(|k| q[(j + k) % nq]));
    union.extend((1..np).map(|k| p[(i + k) % np]).take(np - 1 - i));
    // p's vertices after a, starting at b, up to the end of p (the start was copied first).
    cancel_spikes(&mut union);
    Some(union)
}

#[cfg(test)]
mod tests {
    use super::*;
    use glam::vec3;

    #[test]
    fn join_of_two_squares_along_a_shared_edge_is_the_rectangle() {
        let p = [
            vec3(0., 0., 0.),
            vec3(1., 0., 0.),
            vec3(1., 1., 0.),
            vec3(0., 1., 0.),
        ];
        let q = [
            vec3(1., 0., 0.),
            vec3(2., 0., 0.),
            vec3(2., 1., 0.),
            vec3(1., 1., 0.),
        ];
        let union = join(&p, &q, vec3(1., 0., 0.), vec3(1., 1., 0.)).unwrap();
        assert_eq!(union.len(), 6, "{union:?}");
        let mut s = Vec::new();
        simplify_outline(&union, 1e-6, &mut s);
        assert!(accepts(&s, Vec3::Z, 2.0), "{s:?}");
    }
}
