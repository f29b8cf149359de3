//! The `Metric` trait implemented outside the crate: Manhattan (L1) distance with only
//! `distance` written, every other method left at its default, checked against brute force.

mod common;

use common::*;
use glam::Vec3;
use pm_kdtree::{KindMask, Metric, Neighbours, PhotonTree};

#[derive(Clone, Copy)]
struct Manhattan;

impl Metric for Manhattan {
    fn distance(a: Vec3, b: Vec3) -> f32 {
        (a - b).abs().element_sum()
    }
}

fn manhattan(a: Vec3, b: Vec3) -> f64 {
    (a.as_dvec3() - b.as_dvec3()).abs().element_sum()
}

#[test]
fn manhattan_metric_from_outside_matches_brute_force() {
    let seed = seed();
    let mut rng = Rng::new(seed);
    let points = uniform(&mut rng, 20_000);
    let tree = PhotonTree::build(photons_at(&mut rng, &points)).expect("builds");
    let points: Vec<Vec3> = (0..tree.len() as u32).map(|i| tree.position(i)).collect();
    let mut out = Neighbours::new();
    for q in 0..40 {
        let query = rng.vec3();
        for k in [1, 7, 50, 100] {
            tree.nearest_k::<Manhattan>(query, k, 0.3, KindMask::ALL, &mut out);
            let mut got: Vec<f64> = out.as_slice().iter().map(|n| n.distance as f64).collect();
            got.sort_by(f64::total_cmp);
            let want = brute_k(&points, |_| true, query, k, 0.3, manhattan);
            assert_same_distances(&got, &want, &format!("seed={seed} query {q} k={k}"));
        }
        let mut count = 0;
        tree.for_each_within::<Manhattan>(query, 0.1, |_, _| count += 1);
        assert_eq!(
            count,
            brute_k(&points, |_| true, query, usize::MAX, 0.1, manhattan).len()
        );
    }
}
