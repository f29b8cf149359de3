//! Differential tests of the k-nearest and within queries against brute force, on seeded
//! uniform and box-wall clouds, both metrics, k ∈ {1, 7, 50, 100, 500}.

mod common;

use common::*;
use glam::Vec3;
use pm_kdtree::{Chebyshev, Euclidean, KindMask, Metric, Neighbours, PhotonKind, PhotonTree};

const KS: [usize; 5] = [1, 7, 50, 100, 500];

fn check_cloud<M: Metric>(
    points: &[Vec3],
    kinds: &[PhotonKind],
    tree: &PhotonTree,
    rng: &mut Rng,
    queries: usize,
    distance: fn(Vec3, Vec3) -> f64,
    label: &str,
) {
    let mut out = Neighbours::new();
    let mut seen = vec![false; tree.len()];
    for q in 0..queries {
        // Half the queries anywhere around the cloud (up to half its size outside its bounds, where
        // the search starts from the distance to the bounds), half exactly on a photon.
        let query = if q % 2 == 0 || points.is_empty() {
            rng.vec3() * 2.0 - Vec3::splat(0.5)
        } else {
            points[rng.below(points.len())]
        };
        let (max_distance, mask) = match q % 3 {
            0 => (f32::INFINITY, KindMask::ALL),
            1 => (0.1, KindMask::ALL),
            _ => (0.3, KindMask::NOT_DIRECT),
        };
        let accept = |i: usize| mask.accepts(kinds[i]);
        let mut all = brute_k(points, accept, query, usize::MAX, max_distance as f64, distance);
        all.truncate(*KS.last().unwrap());
        for k in KS {
            tree.nearest_k::<M>(query, k, max_distance, mask, &mut out);
            let what = format!("{label} query {q} at {query} k={k} max={max_distance} mask={mask:?}");
            let want = &all[..all.len().min(k)];
            let mut got: Vec<f64> = out.as_slice().iter().map(|n| n.distance as f64).collect();
            got.sort_by(f64::total_cmp);
            assert_same_distances(&got, want, &what);
            // The reported distances are the true distances of the photons at those indices,
            // of accepted kinds, each found once.
            for n in out.as_slice() {
                let photon = tree.get(n.index);
                assert!(
                    mask.accepts(photon.kind()),
                    "{what}: kind {:?} not in mask",
                    photon.kind()
                );
                let d = distance(photon.position(), query);
                assert!(
                    (d - n.distance as f64).abs() <= 1e-6 * d.max(1e-3),
                    "{what}: distance of {}",
                    n.index
                );
                assert!(!seen[n.index as usize], "{what}: photon {} twice", n.index);
                seen[n.index as usize] = true;
            }
            for n in out.as_slice() {
                seen[n.index as usize] = false;
            }
            assert_eq!(out.is_partial(), want.len() < k, "{what}: partial");
            let extent = if want.len() < k {
                max_distance as f64
            } else {
                want[k - 1]
            };
            assert!(
                out.extent() as f64 == extent
                    || (out.extent() as f64 - extent).abs() <= 1e-6 * extent.max(1e-3),
                "{what}: extent {} vs {extent}",
                out.extent()
            );
        }
        // for_each_within visits exactly the photons within the radius.
        let radius = [0.05f32, 0.15][q % 2];
        let mut within: Vec<f64> = Vec::new();
        tree.for_each_within::<M>(query, radius, |i, d| {
            let truth = distance(tree.position(i), query);
            assert!(
                (truth - d as f64).abs() <= 1e-6 * truth.max(1e-3),
                "{label}: within distance of {i}"
            );
            within.push(d as f64);
        });
        within.sort_by(f64::total_cmp);
        let want = brute_k(points, |_| true, query, usize::MAX, radius as f64, distance);
        assert_same_distances(&within, &want, &format!("{label} within {radius} of {query}"));
    }
}

fn run(n: usize, queries: usize) {
    let seed = seed() ^ n as u64;
    let mut rng = Rng::new(seed);
    for cloud in ["uniform", "box walls"] {
        let points = if cloud == "uniform" {
            uniform(&mut rng, n)
        } else {
            box_walls(&mut rng, n)
        };
        let photons = photons_at(&mut rng, &points);
        let tree = PhotonTree::build(photons).expect("finite positions");
        tree.validate().expect("valid tree");
        assert_eq!(tree.len(), n);
        // Brute force runs over the tree's own order, so kinds line up with indices.
        let points: Vec<Vec3> = (0..n as u32).map(|i| tree.position(i)).collect();
        let kinds: Vec<PhotonKind> = (0..n as u32).map(|i| tree.get(i).kind()).collect();
        let label = format!("{cloud} n={n} seed={seed}");
        check_cloud::<Euclidean>(
            &points,
            &kinds,
            &tree,
            &mut rng,
            queries,
            euclidean,
            &format!("{label} euclidean"),
        );
        check_cloud::<Chebyshev>(
            &points,
            &kinds,
            &tree,
            &mut rng,
            queries,
            chebyshev,
            &format!("{label} chebyshev"),
        );
    }
}

#[test]
fn tiny_trees_match_brute_force() {
    for n in [1, 2, 3, 31, 32, 33, 65] {
        run(n, 12);
    }
}

#[test]
fn thousand_photons_match_brute_force() {
    run(1000, 60);
}

#[test]
fn ten_thousand_photons_match_brute_force() {
    run(10_000, 30);
}

#[test]
fn hundred_thousand_photons_match_brute_force() {
    run(100_000, 12);
}
