//! An estimator written outside pm-render, as a renderer author would: Jensen's cone filter
//! built from the public k-nearest preamble and the scratch the renderer hands it, checked
//! against a brute-force sum over every photon of the map.

use pm_geom::PolygonSet;
use pm_kdtree::{Euclidean, KindMask, Photon, PhotonKind, PhotonTree};
use pm_render::glam::Vec3;
use pm_render::{
    Estimator, EstimatorOptions, EstimatorScratch, MapView, SurfacePoint, find_nearest, gather_found,
};
use std::f32::consts::PI;

/// Jensen's cone filter (1996): each of the k nearest photons weighs `1 − d / (k_c r)`, and the
/// sum is normalised by `(1 − 2 / (3 k_c)) π r²`.
struct ConeFilter {
    k_c: f32,
}

/// The cone filter's own per-thread buffer: the weight of each neighbour.
#[derive(Default)]
struct ConeScratch {
    weights: Vec<f32>,
    /// Queries served by this buffer (to see that the renderer's scratch is reused).
    queries: usize,
}

impl Estimator for ConeFilter {
    fn irradiance(
        &self,
        at: SurfacePoint,
        map: MapView<'_>,
        options: &EstimatorOptions,
        scratch: &mut EstimatorScratch,
    ) -> Vec3 {
        let Some(r) = find_nearest::<Euclidean>(at, map, options, scratch) else {
            return Vec3::ZERO;
        };
        let (neighbours, _, own) = scratch.split::<ConeScratch>();
        own.queries += 1;
        own.weights.clear();
        let mut relative = Vec3::ZERO;
        for n in neighbours {
            let photon = map.tree.get(n.index);
            let weight = (1.0 - n.distance / (self.k_c * r)).max(0.0);
            own.weights.push(weight);
            if !options.reject_behind || photon.direction_l1().dot(at.normal) < 0.0 {
                relative += photon.relative_power() * weight;
            }
        }
        let norm = (1.0 - 2.0 / (3.0 * self.k_c)) * PI * r * r;
        relative * (map.tree.power_scale().watts() / norm)
    }
}

/// SplitMix64, so the test needs no extra crate.
fn next(state: &mut u64) -> f32 {
    *state = state.wrapping_add(0x9E37_79B9_7F4A_7C15);
    let mut z = *state;
    z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
    z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
    ((z ^ (z >> 31)) >> 40) as f32 / (1u64 << 24) as f32
}

/// Photons scattered on the floor y = 0, arriving from above with varied powers.
fn floor_photons(count: usize, seed: u64) -> Vec<Photon> {
    let mut s = seed;
    (0..count)
        .map(|_| Photon {
            position: Vec3::new(next(&mut s) * 2.0 - 1.0, 0.0, next(&mut s) * 2.0 - 1.0),
            power: Vec3::new(0.5 + next(&mut s), 0.5 + next(&mut s), 0.5 + next(&mut s)) * 1e-3,
            direction: Vec3::new(next(&mut s) - 0.5, -1.0, next(&mut s) - 0.5).normalize(),
            kind: PhotonKind::Direct,
        })
        .collect()
}

/// The cone-filter estimate by brute force: every photon's distance, sorted, the k nearest.
fn cone_brute_force(tree: &PhotonTree, at: Vec3, k: usize, k_c: f32) -> Vec3 {
    let mut all: Vec<(f32, Vec3)> = tree
        .iter()
        .map(|p| (p.position().distance(at), p.power(tree.power_scale())))
        .collect();
    all.sort_by(|a, b| a.0.total_cmp(&b.0));
    let nearest = &all[..k];
    let r = nearest[k - 1].0;
    let sum: Vec3 = nearest
        .iter()
        .map(|&(d, power)| power * (1.0 - d / (k_c * r)).max(0.0))
        .sum();
    sum / ((1.0 - 2.0 / (3.0 * k_c)) * PI * r * r)
}

#[test]
fn cone_filter_outside_the_crate_matches_brute_force_with_the_given_scratch() {
    let tree = PhotonTree::build(floor_photons(2000, 7)).unwrap();
    let polygons = PolygonSet::new();
    let map = MapView {
        tree: &tree,
        polygons: &polygons,
    };
    let options = EstimatorOptions {
        k: 50,
        max_distance: 10.0,
        reject_behind: true,
        kinds: KindMask::ALL,
    };
    let cone = ConeFilter { k_c: 1.5 };
    // One scratch for every query, as a renderer worker holds one.
    let mut scratch = EstimatorScratch::new();
    let mut s = 99u64;
    for _ in 0..20 {
        let at = Vec3::new(next(&mut s) * 1.2 - 0.6, 0.0, next(&mut s) * 1.2 - 0.6);
        let got = cone.irradiance(SurfacePoint::front(at, Vec3::Y), map, &options, &mut scratch);
        let want = cone_brute_force(&tree, at, options.k, cone.k_c);
        assert!(
            (got - want).abs().max_element() <= 1e-4 * want.max_element(),
            "at {at}: cone filter {got} but brute force {want}"
        );
        assert_eq!(scratch.neighbours().len(), options.k);
    }
    // The estimator's own buffers live in the scratch it was given, across queries.
    let own = scratch.slot::<ConeScratch>();
    assert_eq!(own.queries, 20);
    assert_eq!(own.weights.len(), options.k);
    assert!(own.weights.iter().all(|w| (0.0..=1.0).contains(w)));
}

#[test]
fn gather_found_decodes_the_neighbours_and_rejects_photons_from_behind() {
    // Two photons above the floor arriving downwards, one arriving upwards (from behind).
    let down = Vec3::new(0.0, -1.0, 0.0);
    let photons = vec![
        Photon {
            position: Vec3::new(0.01, 0.0, 0.0),
            power: Vec3::splat(1.0),
            direction: down,
            kind: PhotonKind::Direct,
        },
        Photon {
            position: Vec3::new(-0.01, 0.0, 0.0),
            power: Vec3::splat(1.0),
            direction: down,
            kind: PhotonKind::Direct,
        },
        Photon {
            position: Vec3::new(0.0, 0.0, 0.01),
            power: Vec3::splat(1.0),
            direction: -down,
            kind: PhotonKind::Direct,
        },
    ];
    let tree = PhotonTree::build(photons).unwrap();
    let polygons = PolygonSet::new();
    let map = MapView {
        tree: &tree,
        polygons: &polygons,
    };
    let options = EstimatorOptions {
        k: 3,
        max_distance: 1.0,
        reject_behind: true,
        kinds: KindMask::ALL,
    };
    let at = SurfacePoint::front(Vec3::ZERO, Vec3::Y);
    let mut scratch = EstimatorScratch::new();
    let extent = find_nearest::<Euclidean>(at, map, &options, &mut scratch).unwrap();
    assert!((extent - 0.01).abs() < 1e-6, "extent {extent}");
    assert_eq!(scratch.neighbours().len(), 3);
    gather_found(at, &tree, &options, &mut scratch);
    assert_eq!(scratch.photons().len(), 2, "the photon from behind is dropped");
    let scale = tree.power_scale().watts();
    for p in scratch.photons() {
        assert!(
            (p.power * scale - Vec3::ONE).abs().max_element() < 1e-2,
            "power {}",
            p.power * scale
        );
        assert!(p.direction.dot(Vec3::Y) < 0.0);
    }
}
