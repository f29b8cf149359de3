//! Unbiased estimates on a uniform Poisson photon field, against its exact irradiance:
//! - a k-nearest estimate at an arbitrary point that counts its boundary photon is k/(k − 1)
//!   too bright; with `EstimatorOptions::leave_out_boundary` it is exact (the k-th
//!   neighbour's volume holds a Gamma(k)-distributed expected count μ, and E[(k − 1)/μ] = 1);
//! - the radiance cache's lookups, on a sphere lit evenly from inside (radiance 1
//!   everywhere), average to 1: its points are estimated from the photons that are not
//!   points, so neither a point's own photon nor the emptiness that makes it the nearest
//!   point biases what it answers (each is about one photon in k).

#[path = "support/furnace.rs"]
mod furnace;

use furnace::{furnace, furnace_maps};
use glam::Vec3;
use pm_geom::PolygonSet;
use pm_kdtree::{Photon, PhotonKind, PhotonTree};
use pm_render::{
    Disc, Estimator, EstimatorOptions, EstimatorScratch, GeometryBall, GeometryCube, MapView, RadianceCache,
    SurfacePoint,
};
use pm_trace::{Ray, RayKind, Scene};
use std::f32::consts::PI;

/// SplitMix64.
struct Rand(u64);
impl Rand {
    fn next_f64(&mut self) -> f64 {
        self.0 = self.0.wrapping_add(0x9E37_79B9_7F4A_7C15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
        ((z ^ (z >> 31)) >> 11) as f64 / (1u64 << 53) as f64
    }
    /// Poisson-distributed count of mean `mean` (by inversion; `mean` is a few thousand at
    /// most here, so the normal approximation would do too, but this is exact).
    fn poisson(&mut self, mean: f64) -> usize {
        // Sum of exponential gaps until past `mean`.
        let mut t = 0.0;
        let mut n = 0;
        loop {
            t += -(1.0 - self.next_f64()).ln();
            if t > mean {
                return n;
            }
            n += 1;
        }
    }
}

/// Side of the square the photons fall on (m); its polygon is larger still.
const SIDE: f32 = 2.0;
/// Each photon's power (W).
const POWER: f32 = 1e-3;

/// A Poisson field of mean `mean` photons of power [`POWER`] on the square |x|, |y| ≤ SIDE/2
/// of the plane z = 0, all arriving straight down; the plane's polygon.
fn field(mean: f64, seed: u64) -> (PhotonTree, PolygonSet) {
    let mut rng = Rand(seed);
    let n = rng.poisson(mean);
    let photons: Vec<Photon> = (0..n)
        .map(|_| Photon {
            position: Vec3::new(
                (rng.next_f64() as f32 - 0.5) * SIDE,
                (rng.next_f64() as f32 - 0.5) * SIDE,
                0.0,
            ),
            power: Vec3::splat(POWER),
            direction: Vec3::NEG_Z,
            kind: PhotonKind::Direct,
        })
        .collect();
    let mut polygons = PolygonSet::new();
    polygons
        .push(&[(-2.0, -2.0), (2.0, -2.0), (2.0, 2.0), (-2.0, 2.0)].map(|(x, y)| Vec3::new(x, y, 0.0)))
        .unwrap();
    polygons.build_index();
    (PhotonTree::from_photons(&photons).unwrap(), polygons)
}

/// Mean and standard error of independent replicates.
fn mean_se(values: &[f64]) -> (f64, f64) {
    let n = values.len() as f64;
    let m = values.iter().sum::<f64>() / n;
    let se = (values.iter().map(|v| (v - m).powi(2)).sum::<f64>() / (n - 1.0) / n).sqrt();
    (m, se)
}

/// Over fields (independent replicates), the mean of `estimate` at uniformly scattered points
/// of the central half-square, relative to each field's exact irradiance (its photon count
/// times the power over the square's area).
fn mean_ratio(
    fields: u64,
    estimate: impl Fn(MapView<'_>, SurfacePoint, &mut EstimatorScratch) -> f32,
) -> (f64, f64) {
    let mut scratch = EstimatorScratch::new();
    let per_field: Vec<f64> = (0..fields)
        .map(|f| {
            let (tree, polygons) = field(MEAN, 17 + f);
            let exact = f64::from(tree.len() as f32 * POWER / (SIDE * SIDE));
            let map = MapView {
                tree: &tree,
                polygons: &polygons,
            };
            let mut rng = Rand(1000 + f);
            let queries = 2000;
            let sum: f64 = (0..queries)
                .map(|_| {
                    let p = Vec3::new(
                        (rng.next_f64() as f32 - 0.5) * 0.5 * SIDE,
                        (rng.next_f64() as f32 - 0.5) * 0.5 * SIDE,
                        0.0,
                    );
                    f64::from(estimate(map, SurfacePoint::front(p, Vec3::Z), &mut scratch))
                })
                .sum();
            sum / f64::from(queries) / exact
        })
        .collect();
    mean_se(&per_field)
}

const K: usize = 20;
const FIELDS: u64 = 48;
const MEAN: f64 = 4000.0;

fn options(leave_out_boundary: bool) -> EstimatorOptions {
    EstimatorOptions {
        k: K,
        leave_out_boundary,
        ..EstimatorOptions::with_max_distance(0.4)
    }
}

fn boundary_left_out_is_exact(estimator: &dyn Estimator, name: &str) {
    let (counted, se_c) = mean_ratio(FIELDS, |map, at, s| {
        estimator.irradiance(at, map, &options(false), s).x
    });
    let (left_out, se) = mean_ratio(FIELDS, |map, at, s| {
        estimator.irradiance(at, map, &options(true), s).x
    });
    let bright = K as f64 / (K as f64 - 1.0);
    eprintln!(
        "{name}: counted {counted:.4} ± {se_c:.4} (k/(k−1) = {bright:.4}); left out {left_out:.4} ± {se:.4}"
    );
    assert!(
        se < 0.01 && se_c < 0.01,
        "{name}: too noisy to tell ({se}, {se_c})"
    );
    // Counting the boundary photon is k/(k − 1) too bright (5 % at k = 20) …
    assert!(
        (counted - bright).abs() < 4.0 * se_c,
        "{name}: counted {counted} ± {se_c}"
    );
    // … leaving it out is exact within the replicates' noise (4 standard errors).
    assert!(
        (left_out - 1.0).abs() < 4.0 * se,
        "{name}: left out {left_out} ± {se}"
    );
}

#[test]
fn cube_without_its_boundary_photon_is_exact() {
    boundary_left_out_is_exact(&GeometryCube, "cube");
}

#[test]
fn ball_without_its_boundary_photon_is_exact() {
    boundary_left_out_is_exact(&GeometryBall, "ball");
}

#[test]
fn disc_without_its_boundary_photon_is_exact() {
    boundary_left_out_is_exact(&Disc, "disc");
}

#[test]
fn fewer_than_k_photons_keep_them_all() {
    // Within the maximum distance the extent is fixed beforehand: nothing is left out.
    let (tree, polygons) = field(30.0, 5);
    let map = MapView {
        tree: &tree,
        polygons: &polygons,
    };
    let at = SurfacePoint::front(Vec3::ZERO, Vec3::Z);
    let mut scratch = EstimatorScratch::new();
    let options = |leave| EstimatorOptions {
        k: 100,
        leave_out_boundary: leave,
        ..EstimatorOptions::with_max_distance(0.3)
    };
    let a = GeometryCube.irradiance(at, map, &options(false), &mut scratch);
    let b = GeometryCube.irradiance(at, map, &options(true), &mut scratch);
    assert!(a.x > 0.0);
    assert_eq!(a, b);
}

/// Where a uniformly random direction from the centre meets the furnace.
fn random_hit(scene: &Scene, rng: &mut Rand) -> pm_trace::Hit {
    let z = 2.0 * rng.next_f64() as f32 - 1.0;
    let phi = 2.0 * PI * rng.next_f64() as f32;
    let s = (1.0 - z * z).max(0.0).sqrt();
    let ray = Ray {
        origin: Vec3::ZERO,
        direction: Vec3::new(s * phi.cos(), s * phi.sin(), z),
    };
    scene.intersect(&ray, f32::INFINITY, RayKind::Other).unwrap()
}

/// Over 12 photon seeds, the mean radiance of cache lookups at 4,000 uniform points of the
/// lit sphere, from caches with k = 10 (a bias of one photon in k is 10 %): the cache as built,
/// and one whose points are estimated from all photons, themselves and the other points
/// included (what the cache did before), through `build_with`.
#[test]
fn cache_lookups_average_to_the_exact_radiance() {
    let scene = furnace();
    // The disc: on a sphere the area within chord distance r is exactly πr².
    let options = EstimatorOptions {
        k: 10,
        ..EstimatorOptions::for_scene(&scene.bounds())
    };
    let every = 4;
    let mut scratch = EstimatorScratch::new();
    let (built, from_all): (Vec<f64>, Vec<f64>) = (0..12u64)
        .map(|seed| {
            let maps = furnace_maps(&scene, 20_000, seed);
            let cache = RadianceCache::build(&scene, &maps, &Disc, &options, every).unwrap();
            let trees: Vec<_> = maps.trees().iter().collect();
            let counting_points = RadianceCache::build_with(
                &scene,
                &trees,
                maps.assignment(),
                every,
                options.max_distance,
                |point, scratch| {
                    let map = maps.map(point.map as u32);
                    let view = MapView {
                        tree: map.tree(),
                        polygons: map.geometry(),
                    };
                    // Undo the cache's scaling for the photons it set aside: none are here.
                    Disc.irradiance(point.at, view, &options, scratch) * (every - 1) as f32 / every as f32
                },
            )
            .unwrap();
            let mut rng = Rand(seed + 99);
            let lookups = 4000;
            let (mut a, mut b) = (0.0, 0.0);
            for _ in 0..lookups {
                let hit = random_hit(&scene, &mut rng);
                a += f64::from(cache.radiance(&scene, &hit, &mut scratch).x);
                b += f64::from(counting_points.radiance(&scene, &hit, &mut scratch).x);
            }
            (a / f64::from(lookups), b / f64::from(lookups))
        })
        .unzip();
    let (mean, se) = mean_se(&built);
    let (old, old_se) = mean_se(&from_all);
    eprintln!(
        "cache on the furnace: {mean:.4} ± {se:.4}; counting its points: {old:.4} ± {old_se:.4} (exact 1)"
    );
    assert!(se < 0.01, "too noisy to tell ({se})");
    assert!(
        (mean - 1.0).abs() < 4.0 * se,
        "cache radiance {mean} ± {se}, exact 1"
    );
    // Counting the points is off by several standard errors (here: its own photon and the
    // boundary make it brighter, the emptiness around the chosen point darker).
    assert!(
        (old - 1.0).abs() > 4.0 * old_se,
        "counting its points: {old} ± {old_se}"
    );
}

#[test]
fn a_cache_point_in_every_photon_is_refused_and_the_sparsest_cache_is_empty() {
    let scene = furnace();
    let maps = furnace_maps(&scene, 1_000, 0);
    let options = EstimatorOptions::for_scene(&scene.bounds());
    for every in [0, 1] {
        let err = RadianceCache::build(&scene, &maps, &GeometryCube, &options, every).unwrap_err();
        assert!(err.to_string().contains("2 or more"), "{err}");
    }
    // The other end: one point in 2 holds about half the photons; one in u32::MAX holds
    // none (an empty cache answers nothing), with the others all kept to estimate from.
    let photons: usize = maps.iter().map(|m| m.tree().len()).sum();
    let half = RadianceCache::build(&scene, &maps, &GeometryCube, &options, 2).unwrap();
    assert!(
        half.len().abs_diff(photons / 2) < photons / 10,
        "{} of {photons}",
        half.len()
    );
    assert_eq!(half.set_aside(), 2.0);
    let none = RadianceCache::build(&scene, &maps, &GeometryCube, &options, u32::MAX).unwrap();
    assert!(none.is_empty());
    let kept: usize = (0..maps.len() as u32)
        .filter_map(|m| none.photons(m))
        .map(|t| t.len())
        .sum();
    assert_eq!(kept, photons);
    let hit = random_hit(&scene, &mut Rand(3));
    let mut scratch = EstimatorScratch::new();
    assert_eq!(none.radiance(&scene, &hit, &mut scratch), Vec3::ZERO);
}

/// Where no cache point lies within a small radius of a point (what a consistent renderer's
/// shrinking volumes meet more and more), a fresh fixed-volume estimate there from the
/// cache's own photons (the non-points, scaled for those set aside) is exact on the lit
/// sphere; from all photons it is too dark by the cache points' share 1/n (half, at n = 2),
/// because that neighbourhood is known to hold no cache point.
#[test]
fn fresh_estimates_where_no_point_is_near_use_the_other_photons() {
    use pm_render::FixedVolumeEstimator;
    let scene = furnace();
    let options = EstimatorOptions::for_scene(&scene.bounds());
    let every = 2;
    let mut scratch = EstimatorScratch::new();
    let (fresh, from_all): (Vec<f64>, Vec<f64>) = (0..12u64)
        .map(|seed| {
            let maps = furnace_maps(&scene, 20_000, seed);
            let cache = RadianceCache::build(&scene, &maps, &Disc, &options, every).unwrap();
            // About 2 photons (one cache point) per disc of this radius on the sphere's 4π m².
            let photons = maps.iter().map(|m| m.tree().len()).sum::<usize>() as f32;
            let radius = (2.0 * 4.0 * PI / photons / PI).sqrt();
            let mut rng = Rand(seed + 7);
            let (mut a, mut b, mut n) = (0.0, 0.0, 0);
            while n < 3000 {
                let hit = random_hit(&scene, &mut rng);
                let map = maps.map_of(hit.part);
                if cache
                    .irradiance_within(hit.position, hit.normal, map, radius, &mut scratch)
                    .is_some()
                {
                    continue;
                }
                let at = SurfacePoint {
                    position: hit.position,
                    normal: hit.normal,
                    front_face: hit.front_face,
                };
                let geometry = maps.map(map).geometry();
                let own = MapView {
                    tree: cache.photons(map).unwrap(),
                    polygons: geometry,
                };
                let all = MapView {
                    tree: maps.map(map).tree(),
                    polygons: geometry,
                };
                let to_radiance = 0.5 / PI;
                a += f64::from(
                    Disc.irradiance_within(at, own, radius, &options, &mut scratch).x
                        * cache.set_aside()
                        * to_radiance,
                );
                b += f64::from(
                    Disc.irradiance_within(at, all, radius, &options, &mut scratch).x * to_radiance,
                );
                n += 1;
            }
            (a / f64::from(n), b / f64::from(n))
        })
        .unzip();
    let (mean, se) = mean_se(&fresh);
    let (all, all_se) = mean_se(&from_all);
    eprintln!(
        "fresh estimates where no point is near: {mean:.4} ± {se:.4}; from all photons {all:.4} ± {all_se:.4} (exact 1)"
    );
    assert!(se < 0.02, "too noisy to tell ({se})");
    assert!((mean - 1.0).abs() < 4.0 * se, "fresh {mean} ± {se}, exact 1");
    assert!(all < 1.0 - 4.0 * all_se, "from all photons {all} ± {all_se}");
}

/// The photons a cache keeps to estimate from, scaled by [`RadianceCache::set_aside`], carry
/// their maps' whole power on average over independent photon sets (the passes of a
/// consistent renderer): each photon is kept with probability (n − 1)/n, chosen afresh for
/// every set. Setting aside the same tree slots in every set (by the index alone) kept a
/// share off by a few tenths of a percent, the same way every time.
#[test]
fn the_photons_kept_carry_the_maps_power_once_scaled() {
    let scene = furnace();
    let options = EstimatorOptions::for_scene(&scene.bounds());
    let power = |tree: &PhotonTree| -> f64 {
        let scale = tree.power_scale();
        tree.iter().map(|p| f64::from(p.power(scale).x)).sum()
    };
    // A typical photon count, and the smallest: one path, a map of a photon or two, where a
    // scale by the map's own count ratio would read a sixteenth too dark.
    for (paths, sets, max_se) in [(2_000, 200u64, 0.001), (1, 4_000, 0.015)] {
        check_power_kept(&scene, &options, paths, sets, max_se, power);
    }
}

fn check_power_kept(
    scene: &Scene,
    options: &EstimatorOptions,
    paths: u32,
    sets: u64,
    max_se: f64,
    power: impl Fn(&PhotonTree) -> f64,
) {
    let ratios: Vec<f64> = (0..sets)
        .map(|seed| {
            let maps = furnace_maps(scene, paths, seed);
            let cache = RadianceCache::build(scene, &maps, &Disc, options, 4).unwrap();
            let (mut kept, mut whole) = (0.0, 0.0);
            for (m, map) in maps.iter().enumerate() {
                whole += power(map.tree());
                kept += power(cache.photons(m as u32).unwrap());
            }
            kept * f64::from(cache.set_aside()) / whole
        })
        .collect();
    let (mean, se) = mean_se(&ratios);
    eprintln!("{paths} paths: photons kept, scaled, over the whole: {mean:.5} ± {se:.5} (exact 1)");
    assert!(se < max_se, "too noisy to tell ({se})");
    assert!(
        (mean - 1.0).abs() < 4.0 * se,
        "kept photons carry {mean} ± {se} of the power"
    );
}
