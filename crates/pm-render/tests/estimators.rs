//! Estimators against closed forms: the cube and the ball on one plane give Σ Φ / A exactly,
//! the geometry spreading conserves energy over random polygons, and the disc estimator
//! matches the Poisson expectation on uniformly scattered photons.

use glam::Vec3;
use pm_geom::{Aabb, Ball, ClipScratch, GatherVolume, PolygonSet};
use pm_kdtree::{KindMask, Photon, PhotonKind, PhotonTree};
use pm_render::{
    Disc, Estimator, EstimatorKind, EstimatorOptions, EstimatorScratch, GatheredPhoton, GeometryBall,
    GeometryCube, MapView, SurfacePoint, irradiance_in_volume,
};
use std::f32::consts::{PI, SQRT_2};

/// SplitMix64: a tiny seeded generator so the tests need no extra crate.
struct Rand(u64);
impl Rand {
    fn next_f32(&mut self) -> f32 {
        self.0 = self.0.wrapping_add(0x9E37_79B9_7F4A_7C15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
        ((z ^ (z >> 31)) >> 40) as f32 / (1u64 << 24) as f32
    }
    fn range(&mut self, lo: f32, hi: f32) -> f32 {
        lo + (hi - lo) * self.next_f32()
    }
    fn unit_vector(&mut self) -> Vec3 {
        loop {
            let v = Vec3::new(
                self.range(-1.0, 1.0),
                self.range(-1.0, 1.0),
                self.range(-1.0, 1.0),
            );
            if let Some(u) = v.try_normalize().filter(|_| v.length_squared() <= 1.0) {
                return u;
            }
        }
    }
    /// A unit direction travelling into the side of the surface that `normal` points out of.
    fn incoming(&mut self, normal: Vec3) -> Vec3 {
        let v = self.unit_vector();
        if v.dot(normal) < -0.05 {
            v
        } else {
            self.incoming(normal)
        }
    }
}

fn photon(position: Vec3, power: Vec3, direction: Vec3) -> Photon {
    Photon {
        position,
        power,
        direction,
        kind: PhotonKind::Direct,
    }
}

/// The tilted plane x + y = 0 through the origin, spanned by `u` and `w`.
const TILT_N: Vec3 = Vec3::new(
    std::f32::consts::FRAC_1_SQRT_2,
    std::f32::consts::FRAC_1_SQRT_2,
    0.0,
);
const TILT_U: Vec3 = Vec3::new(
    std::f32::consts::FRAC_1_SQRT_2,
    -std::f32::consts::FRAC_1_SQRT_2,
    0.0,
);
const TILT_W: Vec3 = Vec3::Z;

/// Photons on the tilted plane around the origin, and the plane itself as a big quad.
fn tilted_plane_map(n: usize, seed: u64) -> (Vec<Photon>, PolygonSet) {
    let mut rng = Rand(seed);
    let photons = (0..n)
        .map(|_| {
            let p = TILT_U * rng.range(-1.0, 1.0) + TILT_W * rng.range(-1.0, 1.0);
            let power = Vec3::new(rng.range(0.1, 1.0), rng.range(0.1, 1.0), rng.range(0.1, 1.0));
            photon(p, power, rng.incoming(TILT_N))
        })
        .collect();
    let mut polygons = PolygonSet::new();
    // Counter-clockwise seen from +TILT_N (w × u = TILT_N), so the polygon faces the photons.
    assert!(TILT_W.cross(TILT_U).dot(TILT_N) > 0.99);
    let quad = [(-3.0, -3.0), (-3.0, 3.0), (3.0, 3.0), (3.0, -3.0)].map(|(a, b)| TILT_U * a + TILT_W * b);
    polygons.push(&quad).unwrap();
    polygons.build_index();
    (photons, polygons)
}

/// The k nearest of the tree's photons by brute force under `dist`: (their total decoded power,
/// the k-th distance).
fn brute_nearest(tree: &PhotonTree, k: usize, dist: impl Fn(Vec3) -> f32) -> (Vec3, f32) {
    let mut d: Vec<(f32, Vec3)> = (0..tree.len() as u32)
        .map(|i| (dist(tree.position(i)), tree.power(i)))
        .collect();
    d.sort_by(|a, b| a.0.total_cmp(&b.0));
    (d[..k].iter().map(|x| x.1).sum(), d[k - 1].0)
}

fn assert_close(got: Vec3, want: Vec3, rel: f32) {
    let err = (got - want).abs().max_element() / want.abs().max_element();
    assert!(err <= rel, "got {got}, want {want} (relative error {err})");
}

#[test]
fn cube_on_one_plane_is_power_over_area_in_cube() {
    let (photons, polygons) = tilted_plane_map(2000, 1);
    let tree = PhotonTree::from_photons(&photons).unwrap();
    let map = MapView {
        tree: &tree,
        polygons: &polygons,
    };
    let mut scratch = EstimatorScratch::new();
    let at = SurfacePoint::front(Vec3::ZERO, TILT_N);
    for k in [1, 7, 100, 555] {
        let (power, h) = brute_nearest(&tree, k, |p| p.abs().max_element());
        // The cube [-h, h]³ cuts the plane x + y = 0 in a rectangle 2√2h (along u) by 2h (along w).
        let area = 4.0 * SQRT_2 * h * h;
        let options = EstimatorOptions {
            k,
            ..EstimatorOptions::with_max_distance(10.0)
        };
        let e = GeometryCube.irradiance(at, map, &options, &mut scratch);
        assert_close(e, power / area, 1e-4);
    }
}

#[test]
fn ball_on_one_plane_is_power_over_disc_area() {
    let (photons, polygons) = tilted_plane_map(2000, 2);
    let tree = PhotonTree::from_photons(&photons).unwrap();
    let map = MapView {
        tree: &tree,
        polygons: &polygons,
    };
    let mut scratch = EstimatorScratch::new();
    let at = SurfacePoint::front(Vec3::ZERO, TILT_N);
    for k in [3, 100, 400] {
        let (power, r) = brute_nearest(&tree, k, |p| p.length());
        let options = EstimatorOptions {
            k,
            ..EstimatorOptions::with_max_distance(10.0)
        };
        let e = GeometryBall.irradiance(at, map, &options, &mut scratch);
        assert_close(e, power / (PI * r * r), 1e-4);
    }
}

#[test]
fn fewer_than_k_photons_use_the_maximum_distance() {
    let (photons, polygons) = tilted_plane_map(50, 3);
    let tree = PhotonTree::from_photons(&photons).unwrap();
    let map = MapView {
        tree: &tree,
        polygons: &polygons,
    };
    let mut scratch = EstimatorScratch::new();
    let at = SurfacePoint::front(Vec3::ZERO, TILT_N);
    let max = 1.5; // holds every photon in both metrics (they lie within |a|, |b| ≤ 1)
    let options = EstimatorOptions {
        k: 100,
        ..EstimatorOptions::with_max_distance(max)
    };
    let total: Vec3 = (0..tree.len() as u32).map(|i| tree.power(i)).sum();
    assert_close(
        Disc.irradiance(at, map, &options, &mut scratch),
        total / (PI * max * max),
        1e-5,
    );
    assert_close(
        GeometryBall.irradiance(at, map, &options, &mut scratch),
        total / (PI * max * max),
        1e-4,
    );
    // Cube of half 1.5 on the plane: u extent limited by |a|/√2 ≤ 1.5, w by |b| ≤ 1.5.
    let cube_area = (2.0 * SQRT_2 * max) * (2.0 * max);
    assert_close(
        GeometryCube.irradiance(at, map, &options, &mut scratch),
        total / cube_area,
        1e-4,
    );
}

#[test]
fn disc_matches_the_poisson_expectation_on_uniform_photons() {
    // N photons uniform on the unit square y = 0, Φ = 1/N each: true irradiance 1 W/m².
    // For a Poisson process, E[k Φ / (π r_k²)] = ρ Φ k / (k − 1).
    let n = 100_000;
    let mut rng = Rand(4);
    let photons: Vec<Photon> = (0..n)
        .map(|_| {
            photon(
                Vec3::new(rng.next_f32(), 0.0, rng.next_f32()),
                Vec3::splat(1.0 / n as f32),
                -Vec3::Y,
            )
        })
        .collect();
    let tree = PhotonTree::build(photons).unwrap();
    let polygons = PolygonSet::new();
    let map = MapView {
        tree: &tree,
        polygons: &polygons,
    };
    let k = 50;
    let options = EstimatorOptions {
        k,
        ..EstimatorOptions::with_max_distance(0.5)
    };
    let mut scratch = EstimatorScratch::new();
    let queries = 600;
    let mean: Vec3 = (0..queries)
        .map(|_| {
            let at = SurfacePoint::front(Vec3::new(rng.range(0.1, 0.9), 0.0, rng.range(0.1, 0.9)), Vec3::Y);
            Disc.irradiance(at, map, &options, &mut scratch)
        })
        .sum::<Vec3>()
        / queries as f32;
    assert_close(mean, Vec3::splat(k as f32 / (k - 1) as f32), 0.02);
}

#[test]
fn reject_behind_drops_photons_from_the_back() {
    let front = photon(Vec3::new(0.01, 0.0, 0.0), Vec3::splat(1.0), -Vec3::Y);
    let back = photon(Vec3::new(-0.01, 0.0, 0.0), Vec3::splat(4.0), Vec3::Y);
    let tree = PhotonTree::build(vec![front, back]).unwrap();
    let polygons = PolygonSet::new();
    let map = MapView {
        tree: &tree,
        polygons: &polygons,
    };
    let at = SurfacePoint::front(Vec3::ZERO, Vec3::Y);
    let mut options = EstimatorOptions {
        k: 2,
        ..EstimatorOptions::with_max_distance(1.0)
    };
    let mut scratch = EstimatorScratch::new();
    let r2 = PI * 0.01 * 0.01;
    assert_close(
        Disc.irradiance(at, map, &options, &mut scratch),
        (front.power + back.power) / r2,
        1e-5,
    );
    options.reject_behind = true;
    assert_close(
        Disc.irradiance(at, map, &options, &mut scratch),
        front.power / r2,
        1e-5,
    );
}

#[test]
fn kind_mask_selects_photons() {
    let mut direct = Photon {
        position: Vec3::ZERO,
        power: Vec3::ONE,
        direction: -Vec3::Y,
        kind: PhotonKind::Direct,
    };
    let indirect = Photon {
        position: Vec3::new(0.1, 0.0, 0.0),
        power: Vec3::splat(2.0),
        kind: PhotonKind::Indirect,
        ..direct
    };
    direct.position.z = 0.05;
    let tree = PhotonTree::build(vec![direct, indirect]).unwrap();
    let polygons = PolygonSet::new();
    let map = MapView {
        tree: &tree,
        polygons: &polygons,
    };
    let at = SurfacePoint::front(Vec3::ZERO, Vec3::Y);
    let options = EstimatorOptions {
        k: 1,
        kinds: KindMask::NOT_DIRECT,
        ..EstimatorOptions::with_max_distance(1.0)
    };
    let e = Disc.irradiance(at, map, &options, &mut EstimatorScratch::new());
    assert_close(e, Vec3::splat(2.0) / (PI * 0.01), 1e-3);
}

/// A random convex polygon: a regular-ish n-gon around `center` in a random plane.
fn random_convex(rng: &mut Rand, center: Vec3, radius: f32) -> Vec<Vec3> {
    let n = rng.unit_vector();
    let u = n.any_orthonormal_vector();
    let w = n.cross(u);
    let sides = 3 + (rng.next_f32() * 6.0) as usize;
    let mut angles: Vec<f32> = (0..sides).map(|_| rng.range(0.0, 2.0 * PI)).collect();
    angles.sort_by(f32::total_cmp);
    // Points on a circle in angular order form a convex polygon.
    angles
        .iter()
        .map(|a| center + (u * a.cos() + w * a.sin()) * radius)
        .collect()
}

#[test]
fn geometry_spreading_conserves_energy_over_random_polygons() {
    let mut rng = Rand(5);
    let mut scratch = EstimatorScratch::new();
    let mut clip = ClipScratch::new();
    for case in 0..60 {
        let mut polygons = PolygonSet::new();
        let count = 1 + case % 6;
        for _ in 0..count {
            let c = Vec3::new(rng.range(-0.4, 0.4), rng.range(-0.4, 0.4), rng.range(-0.4, 0.4));
            let radius = rng.range(0.2, 1.0);
            polygons.push(&random_convex(&mut rng, c, radius));
        }
        polygons.build_index();
        let photons: Vec<GatheredPhoton> = (0..40)
            .map(|_| GatheredPhoton {
                power: Vec3::splat(rng.range(0.1, 1.0)),
                // Any length: the estimate uses only ratios of cosines with it.
                direction: rng.unit_vector() * rng.range(0.3, 3.0),
                kind: PhotonKind::Direct,
                distance_squared: 0.0,
            })
            .collect();
        let cube = Aabb::cube(Vec3::ZERO, 0.5);
        let ball = Ball::new(Vec3::ZERO, 0.5);
        check_conservation(&cube, &polygons, &photons, &mut scratch, &mut clip);
        check_conservation(&ball, &polygons, &photons, &mut scratch, &mut clip);
    }
}

/// Σ_f A_f E_f (E_f the estimate seen from face f, constant for a fixed volume) must equal the
/// power of the photons that some enclosed face faces.
fn check_conservation<V: GatherVolume>(
    volume: &V,
    polygons: &PolygonSet,
    photons: &[GatheredPhoton],
    scratch: &mut EstimatorScratch,
    clip: &mut ClipScratch,
) {
    let mut assigned = Vec3::ZERO;
    let mut expected = Vec3::ZERO;
    let faces: Vec<(f32, Vec3)> = (0..polygons.len() as u32)
        .map(|i| {
            (
                volume.polygon_area_inside(polygons.polygon(i), polygons.normal(i), clip),
                polygons.normal(i),
            )
        })
        .collect();
    for &(area, normal) in &faces {
        assigned += area * irradiance_in_volume(volume, normal, photons, polygons, scratch);
    }
    for p in photons {
        if faces.iter().any(|&(a, n)| a > 0.0 && n.dot(p.direction) < 0.0) {
            expected += p.power;
        }
    }
    if expected == Vec3::ZERO {
        assert_eq!(assigned, Vec3::ZERO);
    } else {
        assert_close(assigned, expected, 1e-4);
    }
}

#[test]
fn empty_map_gives_zero() {
    let tree = PhotonTree::build(Vec::new()).unwrap();
    let polygons = PolygonSet::new();
    let map = MapView {
        tree: &tree,
        polygons: &polygons,
    };
    let at = SurfacePoint::front(Vec3::ZERO, Vec3::Y);
    let options = EstimatorOptions::with_max_distance(1.0);
    for kind in EstimatorKind::ALL {
        assert_eq!(
            kind.irradiance(at, map, &options, &mut EstimatorScratch::new()),
            Vec3::ZERO
        );
    }
}
