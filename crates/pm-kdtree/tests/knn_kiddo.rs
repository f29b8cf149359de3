//! kiddo 6 `ImmutableKdTree` as a second, independent oracle: the same points, the same
//! queries, k ∈ {1, 7, 50, 100, 500}, Euclidean and Chebyshev, compared by distances.

mod common;

use common::*;
use glam::Vec3;
use kiddo::{Chebyshev as KiddoChebyshev, ImmutableKdTree, SquaredEuclidean};
use pm_kdtree::{Chebyshev, Euclidean, KindMask, Neighbours, PhotonTree};
use std::num::NonZero;

fn sorted(out: &Neighbours) -> Vec<f64> {
    let mut d: Vec<f64> = out.as_slice().iter().map(|n| n.distance as f64).collect();
    d.sort_by(f64::total_cmp);
    d
}

#[test]
fn pm_kdtree_matches_kiddo_on_both_metrics() {
    let seed = seed();
    let mut rng = Rng::new(seed);
    for cloud in ["uniform", "box walls"] {
        let points = if cloud == "uniform" {
            uniform(&mut rng, 100_000)
        } else {
            box_walls(&mut rng, 100_000)
        };
        let tree = PhotonTree::build(photons_at(&mut rng, &points)).expect("builds");
        let arrays: Vec<[f32; 3]> = points.iter().map(|p| p.to_array()).collect();
        let kd = ImmutableKdTree::<f32, 3>::new_from_slice(&arrays).expect("kiddo builds");
        let mut out = Neighbours::new();
        for q in 0..40 {
            let query = rng.vec3() * 1.2 - Vec3::splat(0.1);
            let qa = query.to_array();
            for k in [1usize, 7, 50, 100, 500] {
                let nz = NonZero::new(k).expect("k > 0");
                let what = format!("{cloud} seed={seed} query {q} at {query} k={k}");
                // Unbounded, then bounded by a maximum distance (kiddo: nearest_n + within).
                let max = 0.08f32;

                tree.nearest_k::<Euclidean>(query, k, f32::INFINITY, KindMask::ALL, &mut out);
                let want: Vec<f64> = kd
                    .query(&qa)
                    .nearest_n::<SquaredEuclidean<f32>>(nz)
                    .execute()
                    .iter()
                    .map(|r| (r.distance as f64).sqrt())
                    .collect();
                assert_same_distances(&sorted(&out), &want, &format!("{what} euclidean"));

                tree.nearest_k::<Euclidean>(query, k, max, KindMask::ALL, &mut out);
                let want: Vec<f64> = kd
                    .query(&qa)
                    .nearest_n::<SquaredEuclidean<f32>>(nz)
                    .within(max * max)
                    .execute()
                    .iter()
                    .map(|r| (r.distance as f64).sqrt())
                    .collect();
                assert_same_distances(&sorted(&out), &want, &format!("{what} euclidean within {max}"));

                tree.nearest_k::<Chebyshev>(query, k, f32::INFINITY, KindMask::ALL, &mut out);
                let want: Vec<f64> = kd
                    .query(&qa)
                    .nearest_n::<KiddoChebyshev<f32>>(nz)
                    .execute()
                    .iter()
                    .map(|r| r.distance as f64)
                    .collect();
                assert_same_distances(&sorted(&out), &want, &format!("{what} chebyshev"));

                tree.nearest_k::<Chebyshev>(query, k, max, KindMask::ALL, &mut out);
                let want: Vec<f64> = kd
                    .query(&qa)
                    .nearest_n::<KiddoChebyshev<f32>>(nz)
                    .within(max)
                    .execute()
                    .iter()
                    .map(|r| r.distance as f64)
                    .collect();
                assert_same_distances(&sorted(&out), &want, &format!("{what} chebyshev within {max}"));
            }
        }
    }
}
