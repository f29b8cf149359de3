//! The normal-but-awkward cases: empty trees, k = 0, k beyond the tree, thousands of identical
//! positions, everything on one plane, kind filters, odd maximum distances, non-finite input.

mod common;

use common::*;
use glam::Vec3;
use pm_kdtree::{BuildError, Chebyshev, Euclidean, KindMask, Neighbours, Photon, PhotonKind, PhotonTree};

fn at(position: Vec3, kind: PhotonKind) -> Photon {
    Photon {
        position,
        power: Vec3::ONE,
        direction: Vec3::NEG_Y,
        kind,
    }
}

#[test]
fn empty_tree_finds_nothing_and_reports_the_maximum() {
    let tree = PhotonTree::build(Vec::new()).expect("empty is fine");
    tree.validate().expect("valid");
    assert!(tree.is_empty());
    let mut out = Neighbours::new();
    tree.nearest_k::<Euclidean>(Vec3::ZERO, 10, 2.5, KindMask::ALL, &mut out);
    assert!(out.is_empty() && out.is_partial());
    assert_eq!(out.extent(), 2.5);
    let mut visits = 0;
    tree.for_each_within::<Chebyshev>(Vec3::ZERO, 1e9, |_, _| visits += 1);
    assert_eq!(visits, 0);
    PhotonTree::default()
        .validate()
        .expect("the default tree is the empty tree");
}

#[test]
fn k_zero_finds_nothing_and_is_not_partial() {
    let tree = PhotonTree::build(vec![at(Vec3::ZERO, PhotonKind::Direct)]).expect("builds");
    let mut out = Neighbours::new();
    tree.nearest_k::<Euclidean>(Vec3::ZERO, 0, 1.0, KindMask::ALL, &mut out);
    assert!(out.is_empty() && !out.is_partial());
    assert_eq!(out.extent(), 0.0);
}

#[test]
fn k_larger_than_the_tree_returns_every_photon_and_is_partial() {
    let mut rng = Rng::new(seed());
    let tree = {
        let points = uniform(&mut rng, 40);
        PhotonTree::build(photons_at(&mut rng, &points))
    }
    .expect("builds");
    let mut out = Neighbours::new();
    tree.nearest_k::<Chebyshev>(Vec3::splat(0.5), 1000, f32::INFINITY, KindMask::ALL, &mut out);
    assert_eq!(out.len(), 40);
    assert!(out.is_partial());
    assert_eq!(out.extent(), f32::INFINITY);
    // A k so large that 2k (the candidate buffer's trim size) overflows: same answer.
    for k in [usize::MAX, usize::MAX / 2 + 1] {
        tree.nearest_k::<Euclidean>(Vec3::splat(0.5), k, f32::INFINITY, KindMask::ALL, &mut out);
        assert_eq!((out.len(), out.is_partial()), (40, true), "k = {k}");
    }
    // 40 = k exactly: every photon, not partial, the extent the farthest one's distance.
    tree.nearest_k::<Euclidean>(Vec3::splat(0.5), 40, f32::INFINITY, KindMask::ALL, &mut out);
    let farthest = out.as_slice().iter().fold(0.0f32, |m, n| m.max(n.distance));
    assert_eq!((out.len(), out.is_partial(), out.extent()), (40, false, farthest));
}

#[test]
fn thousands_of_identical_positions() {
    let p = Vec3::new(0.25, 0.5, 0.75);
    let mut photons: Vec<Photon> = (0..5000).map(|_| at(p, PhotonKind::Indirect)).collect();
    photons.push(at(p + Vec3::X, PhotonKind::Indirect));
    let tree = PhotonTree::build(photons).expect("duplicates are fine");
    tree.validate().expect("valid");
    let mut out = Neighbours::new();
    tree.nearest_k::<Euclidean>(p + Vec3::new(0.0, 0.1, 0.0), 100, 1.0, KindMask::ALL, &mut out);
    assert_eq!(out.len(), 100);
    assert!(out.as_slice().iter().all(|n| (n.distance - 0.1).abs() < 1e-6));
    let mut count = 0;
    tree.for_each_within::<Chebyshev>(p, 0.0, |_, d| {
        assert_eq!(d, 0.0);
        count += 1
    });
    assert_eq!(count, 5000, "radius 0 includes the photons exactly at the query");
    // Far away, everything is within reach: the 5001st nearest is the odd one out.
    tree.nearest_k::<Euclidean>(p + Vec3::X, 5001, f32::INFINITY, KindMask::ALL, &mut out);
    assert_eq!(out.len(), 5001);
    assert!((out.extent() - 1.0).abs() < 1e-6);
}

#[test]
fn all_photons_on_one_axis_aligned_plane() {
    let mut rng = Rng::new(seed());
    let points: Vec<Vec3> = (0..20_000)
        .map(|_| Vec3::new(rng.f32(), 0.0, rng.f32()))
        .collect();
    let tree = PhotonTree::build(photons_at(&mut rng, &points)).expect("coplanar is fine");
    tree.validate().expect("valid");
    let mut out = Neighbours::new();
    for _ in 0..50 {
        let q = Vec3::new(rng.f32(), 0.0, rng.f32());
        tree.nearest_k::<Chebyshev>(q, 50, 1.0, KindMask::ALL, &mut out);
        let mut got: Vec<f64> = out.as_slice().iter().map(|n| n.distance as f64).collect();
        got.sort_by(f64::total_cmp);
        assert_same_distances(&got, &brute_k(&points, |_| true, q, 50, 1.0, chebyshev), "floor");
    }
}

#[test]
fn kind_filter_keeps_only_accepted_kinds() {
    // Direct photons close by, indirect ones further away: NOT_DIRECT must skip the close ones.
    let mut photons = Vec::new();
    for i in 0..100 {
        let x = i as f32 * 0.01;
        photons.push(at(Vec3::new(x, 0.0, 0.0), PhotonKind::Direct));
        photons.push(at(Vec3::new(x, 1.0, 0.0), PhotonKind::Indirect));
        photons.push(at(Vec3::new(x, 2.0, 0.0), PhotonKind::Caustic));
    }
    let tree = PhotonTree::build(photons).expect("builds");
    let mut out = Neighbours::new();
    tree.nearest_k::<Euclidean>(Vec3::new(0.5, 0.0, 0.0), 10, 10.0, KindMask::NOT_DIRECT, &mut out);
    assert_eq!(out.len(), 10);
    for n in out.as_slice() {
        assert_eq!(tree.get(n.index).kind(), PhotonKind::Indirect);
    }
    tree.nearest_k::<Euclidean>(
        Vec3::ZERO,
        300,
        10.0,
        KindMask::only(PhotonKind::Caustic),
        &mut out,
    );
    assert_eq!(out.len(), 100);
    assert!(
        out.as_slice()
            .iter()
            .all(|n| tree.get(n.index).kind() == PhotonKind::Caustic)
    );
}

#[test]
fn negative_or_nan_maximum_distance_finds_nothing() {
    let tree = PhotonTree::build(vec![at(Vec3::ZERO, PhotonKind::Direct)]).expect("builds");
    let mut out = Neighbours::new();
    for max in [-1.0, f32::NAN] {
        tree.nearest_k::<Euclidean>(Vec3::ZERO, 1, max, KindMask::ALL, &mut out);
        assert!(out.is_empty() && out.is_partial(), "max {max}");
        let mut visits = 0;
        tree.for_each_within::<Euclidean>(Vec3::ZERO, max, |_, _| visits += 1);
        assert_eq!(visits, 0);
    }
}

#[test]
fn non_finite_positions_are_rejected_with_their_index() {
    for bad in [f32::NAN, f32::INFINITY, f32::NEG_INFINITY] {
        let mut photons: Vec<Photon> = (0..10)
            .map(|i| at(Vec3::splat(i as f32), PhotonKind::Direct))
            .collect();
        photons[7] = at(Vec3::new(0.0, bad, 0.0), PhotonKind::Direct);
        let err = PhotonTree::build(photons).expect_err("non-finite");
        match err {
            BuildError::NonFinitePosition { index, .. } => assert_eq!(index, 7),
            other => panic!("unexpected {other:?}"),
        }
        assert!(err.to_string().contains("photon 7"), "{err}");
    }
}

#[test]
fn queries_allocate_nothing_once_the_buffer_is_warm() {
    let mut rng = Rng::new(seed());
    let tree = {
        let points = uniform(&mut rng, 5000);
        PhotonTree::build(photons_at(&mut rng, &points))
    }
    .expect("builds");
    let mut out = Neighbours::new();
    tree.nearest_k::<Euclidean>(Vec3::splat(0.5), 64, 1.0, KindMask::ALL, &mut out);
    let capacity = out.as_slice().as_ptr();
    for _ in 0..100 {
        tree.nearest_k::<Chebyshev>(rng.vec3(), 64, 1.0, KindMask::ALL, &mut out);
        assert_eq!(out.as_slice().as_ptr(), capacity, "the buffer was reallocated");
    }
}

#[test]
fn build_keeps_every_photon() {
    let mut rng = Rng::new(seed());
    let points = box_walls(&mut rng, 70_000); // large enough for the parallel build
    let photons = photons_at(&mut rng, &points);
    let tree = PhotonTree::build(photons.clone()).expect("builds");
    tree.validate().expect("valid");
    let key = |p: &Photon| (p.position.to_array().map(f32::to_bits), p.kind as u8);
    let mut before: Vec<_> = photons.iter().map(key).collect();
    let mut after: Vec<_> = (0..tree.len() as u32).map(|i| key(&tree.photon(i))).collect();
    before.sort_unstable();
    after.sort_unstable();
    assert_eq!(before, after, "the tree holds exactly the input photons");
    let bytes = tree.memory_bytes() as f64 / tree.len() as f64;
    assert!(bytes <= 20.5, "{bytes} bytes per photon");
}

/// Above the parallel threshold the positions are checked and the photons encoded on rayon:
/// the first bad photon is still the one reported, and 1 and 3 threads build the same tree
/// bit for bit, with the same count of channels below the power code's range.
#[test]
fn large_builds_report_the_first_bad_photon_and_match_on_any_thread_count() {
    let mut rng = Rng::new(seed());
    let points = box_walls(&mut rng, 70_000);
    let mut photons = photons_at(&mut rng, &points);
    // Powers across 80 octaves, so some channels fall below the code's range.
    for (i, p) in photons.iter_mut().enumerate() {
        p.power = Vec3::new(1.0, 2f32.powi(-((i % 80) as i32)), 0.5);
        p.direction = Vec3::new(rng.vec3().x - 0.5, 0.3, 1.0);
    }
    let build_on = |threads: usize, photons: &[Photon]| {
        let pool = rayon::ThreadPoolBuilder::new()
            .num_threads(threads)
            .build()
            .expect("pool");
        pool.install(|| PhotonTree::from_photons(photons))
    };
    let one = build_on(1, &photons).expect("builds");
    let three = build_on(3, &photons).expect("builds");
    assert!(
        one.channels_below_range() > 0,
        "the test needs channels below range"
    );
    assert_eq!(one.channels_below_range(), three.channels_below_range());
    let bits = |t: &PhotonTree| {
        (0..t.len() as u32)
            .map(|i| {
                let p = t.photon(i);
                let word = |v: Vec3| v.to_array().map(f32::to_bits);
                (word(p.position), word(p.power), word(p.direction), p.kind as u8)
            })
            .collect::<Vec<_>>()
    };
    assert_eq!(bits(&one), bits(&three));

    photons[65_000].position = Vec3::new(f32::NAN, 0.0, 0.0);
    photons[40_000].position = Vec3::new(0.0, 1e30, 0.0);
    for threads in [1, 3] {
        match build_on(threads, &photons) {
            Err(BuildError::PositionOutOfRange { index, .. }) => assert_eq!(index, 40_000),
            other => panic!("{threads} threads: unexpected {other:?}"),
        }
    }
    photons[40_000].position = Vec3::ZERO;
    match build_on(3, &photons) {
        Err(BuildError::NonFinitePosition { index, .. }) => assert_eq!(index, 65_000),
        other => panic!("unexpected {other:?}"),
    }
}
