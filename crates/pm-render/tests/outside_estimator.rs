//! An estimator written outside pm-render, as a renderer author would: Jensen's cone filter
//! built from the public k-nearest preamble, the decoded photons (power in watts, squared
//! distance, the shared filters applied) and the scratch the renderer hands it, checked
//! against a brute-force sum over every photon of the map.

use pm_render::prelude::*;
use std::f32::consts::PI;

/// Jensen's cone filter (1996): each of the k nearest photons weighs `1 − d / (k_c r)`, and the
/// sum is normalised by `(1 − 2 / (3 k_c)) π r²`.
struct ConeFilter {
    k_c: f32,
}

/// The cone filter's own per-thread buffer: the weight of each photon.
#[derive(Default)]
struct ConeScratch {
    weights: Vec<f32>,
    /// Queries served by this buffer (to see that the renderer's scratch is reused).
    queries: usize,
}

impl Estimator for ConeFilter {
    fn estimate(
        &self,
        at: SurfacePoint,
        map: MapView<'_>,
        options: &EstimatorOptions,
        weight: &dyn PhotonWeight,
        scratch: &mut EstimatorScratch,
    ) -> Vec3 {
        let Some(r) = find_nearest::<Euclidean>(at, map, options, scratch) else {
            return Vec3::ZERO;
        };
        gather_found(at, map.tree, options, weight, scratch);
        let (_, photons, own) = scratch.split::<ConeScratch>();
        own.queries += 1;
        own.weights.clear();
        let mut power = Vec3::ZERO;
        for p in photons {
            let weight = (1.0 - p.distance_squared.sqrt() / (self.k_c * r)).max(0.0);
            own.weights.push(weight);
            power += p.power * weight;
        }
        power / ((1.0 - 2.0 / (3.0 * self.k_c)) * PI * r * r)
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

/// Photons scattered on the floor y = 0 with varied powers, of all three kinds; one in five
/// arrives from below (it lit the floor's underside).
fn floor_photons(count: usize, seed: u64) -> Vec<Photon> {
    let mut s = seed;
    let kinds = [PhotonKind::Direct, PhotonKind::Indirect, PhotonKind::Caustic];
    (0..count)
        .map(|i| {
            let up = if i % 5 == 4 { -1.0 } else { 1.0 };
            Photon {
                position: Vec3::new(next(&mut s) * 2.0 - 1.0, 0.0, next(&mut s) * 2.0 - 1.0),
                power: Vec3::new(0.5 + next(&mut s), 0.5 + next(&mut s), 0.5 + next(&mut s)) * 1e-3,
                direction: Vec3::new(next(&mut s) - 0.5, -up, next(&mut s) - 0.5).normalize(),
                kind: kinds[i % 3],
            }
        })
        .collect()
}

/// The cone-filter estimate by brute force over the photons in full precision: the k nearest
/// of the kinds asked for, then the sum over those that arrive from above (from the side the
/// floor's normal +y faces) unless `from_below_too`.
fn cone_brute_force(
    photons: &[Photon],
    at: Vec3,
    kinds: KindMask,
    from_below_too: bool,
    k: usize,
    k_c: f32,
) -> Vec3 {
    let mut all: Vec<&Photon> = photons.iter().filter(|p| kinds.accepts(p.kind)).collect();
    all.sort_by(|a, b| a.position.distance(at).total_cmp(&b.position.distance(at)));
    let nearest = &all[..k];
    let r = nearest[k - 1].position.distance(at);
    let sum: Vec3 = nearest
        .iter()
        .filter(|p| from_below_too || p.direction.y < 0.0)
        .map(|p| p.power * (1.0 - p.position.distance(at) / (k_c * r)).max(0.0))
        .sum();
    sum / ((1.0 - 2.0 / (3.0 * k_c)) * PI * r * r)
}

#[test]
fn cone_filter_outside_the_crate_matches_brute_force_with_the_given_scratch() {
    let photons = floor_photons(3000, 7);
    let tree = PhotonTree::build(photons.clone()).unwrap();
    let polygons = PolygonSet::new();
    let map = MapView {
        tree: &tree,
        polygons: &polygons,
    };
    let cone = ConeFilter { k_c: 1.5 };
    // One scratch for every query, as a renderer worker holds one.
    let mut scratch = EstimatorScratch::new();
    let mut s = 99u64;
    let cases = [(KindMask::ALL, true), (KindMask::NOT_DIRECT, false)];
    for (kinds, reject_behind) in cases {
        let options = EstimatorOptions {
            k: 50,
            max_distance: 10.0,
            reject_behind,
            kinds,
            leave_out_boundary: false,
        };
        for _ in 0..20 {
            let at = Vec3::new(next(&mut s) * 1.2 - 0.6, 0.0, next(&mut s) * 1.2 - 0.6);
            let got = cone.irradiance(SurfacePoint::front(at, Vec3::Y), map, &options, &mut scratch);
            let want = cone_brute_force(&photons, at, kinds, !reject_behind, options.k, cone.k_c);
            // Compact photons keep power within 0.35 % per channel.
            assert!(
                (got - want).abs().max_element() <= 5e-3 * want.max_element(),
                "at {at} ({kinds:?}, reject behind {reject_behind}): cone filter {got} but brute force {want}"
            );
            assert_eq!(scratch.neighbours().len(), options.k);
        }
    }
    // The estimator's own buffers live in the scratch it was given, across queries.
    let own = scratch.slot::<ConeScratch>();
    assert_eq!(own.queries, 40);
    assert_eq!(
        own.weights.len(),
        50,
        "no photon is rejected from behind in the last case"
    );
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
        leave_out_boundary: false,
    };
    let at = SurfacePoint::front(Vec3::ZERO, Vec3::Y);
    let mut scratch = EstimatorScratch::new();
    let extent = find_nearest::<Euclidean>(at, map, &options, &mut scratch).unwrap();
    assert!((extent - 0.01).abs() < 1e-6, "extent {extent}");
    assert_eq!(scratch.neighbours().len(), 3);
    gather_found(at, &tree, &options, &Irradiance, &mut scratch);
    assert_eq!(scratch.photons().len(), 2, "the photon from behind is dropped");
    for p in scratch.photons() {
        // Watts, with the map's power scale applied (compact powers keep 0.35 %).
        assert!(
            (p.power - Vec3::ONE).abs().max_element() < 1e-2,
            "power {}",
            p.power
        );
        assert!(p.direction.dot(Vec3::Y) < 0.0);
        assert!((p.distance_squared - 1e-4).abs() < 1e-8, "{}", p.distance_squared);
        assert_eq!(p.kind, PhotonKind::Direct);
        assert!(options.accepts(at, p.kind, p.direction));
    }
    // The shared filters: a photon from behind is refused only while rejection is on, and a
    // kind outside the mask always.
    assert!(at.arrives_from_behind(-down));
    assert!(!options.accepts(at, PhotonKind::Direct, -down));
    let keep_behind = EstimatorOptions {
        reject_behind: false,
        ..options
    };
    assert!(keep_behind.accepts(at, PhotonKind::Direct, -down));
    let no_direct = EstimatorOptions {
        kinds: KindMask::NOT_DIRECT,
        ..options
    };
    assert!(!no_direct.accepts(at, PhotonKind::Direct, down));
    assert!(no_direct.accepts(at, PhotonKind::Caustic, down));
}
