//! The public cache query (`RadianceCache::radiance_at`) against truth: a linear scan over a
//! map's cache points, bad input answered with `None`, and the example's own path tracer
//! (`examples/cache_query/tracer.rs`, which reads the cache only through the query) against
//! the built-in final gather over independent seeds.

#[path = "../examples/cache_query/tracer.rs"]
mod tracer;

use photon_maps::render::cache::{CANDIDATES, NORMAL_AGREEMENT};
use photon_maps::render::glam::Vec3;
use photon_maps::render::{
    CacheQuery, EstimatorKind, EstimatorScratch, FinalGatherOptions, Image, Mode, PhotonCache, QueryMap,
    RadianceCache, RenderSettings, RenderStats, Renderer,
};
use photon_maps::trace::{Contact, PartId, Partitioned, Partitioner, Ray, RayKind, Rng, scenes};
use tracer::{CacheTracer, Shot};

fn settings(seed: u64) -> RenderSettings {
    RenderSettings {
        width: 48,
        height: 48,
        samples_per_pixel: 16,
        photons: 50_000,
        seed,
        mode: Mode::FinalGather,
        final_gather: FinalGatherOptions {
            gather_rays: 4,
            ..FinalGatherOptions::default()
        },
        threads: 2,
        ..RenderSettings::default()
    }
}

fn cornell() -> (Partitioned, PhotonCache) {
    let scene = scenes::build("cornell-box").unwrap();
    let partitioned = Contact::default().partition(scene).unwrap();
    let renderer = Renderer::new(EstimatorKind::GeometryCube, settings(1));
    let photons = renderer
        .build_photon_cache(&partitioned, &(), &mut RenderStats::default())
        .unwrap();
    (partitioned, photons)
}

/// The answer by brute force: the map's points within the lookup distance by distance; the
/// nearest if it agrees, else the first that agrees among the `CANDIDATES` nearest.
fn linear_scan(cache: &RadianceCache, map: u32, position: Vec3, normal: Vec3) -> Option<(Vec3, f32)> {
    let mut near: Vec<(f32, Vec3, Vec3)> = cache
        .points(map)?
        .iter()
        .map(|p| (p.position.distance(position), p.normal, p.position))
        .filter(|(d, _, _)| *d <= cache.max_distance())
        .collect();
    near.sort_by(|a, b| a.0.total_cmp(&b.0));
    near.truncate(CANDIDATES);
    near.iter()
        .find(|(_, n, _)| n.dot(normal) >= NORMAL_AGREEMENT)
        .map(|&(d, _, p)| (p, d))
}

#[test]
fn the_query_is_the_nearest_agreeing_point_of_a_linear_scan() {
    let (partitioned, photons) = cornell();
    let scene = partitioned.scene();
    let cache = photons.radiance.as_ref().unwrap();
    let bounds = scene.bounds();
    let mut rng = Rng::new(7, 0);
    let mut scratch = EstimatorScratch::new();
    let (mut answered, mut unanswered) = (0, 0);
    for _ in 0..2000 {
        // A random ray from inside the box: its hit is a random point on some map's surface.
        let origin = bounds.min
            + (bounds.max - bounds.min) * Vec3::new(rng.next_f32(), rng.next_f32(), rng.next_f32());
        let direction = Vec3::new(rng.next_f32() - 0.5, rng.next_f32() - 0.5, rng.next_f32() - 0.5);
        let Some(direction) = direction.try_normalize() else {
            continue;
        };
        let Some(hit) = scene.intersect(&Ray { origin, direction }, f32::INFINITY, RayKind::Other) else {
            continue;
        };
        let map = cache.map_of(hit.part).unwrap();
        let query = CacheQuery {
            position: hit.position,
            normal: hit.normal,
            map: QueryMap::Map(map),
            albedo: Vec3::new(0.2, 0.4, 0.8),
        };
        let answer = cache.radiance_at(&query, &mut scratch);
        let truth = linear_scan(cache, map, hit.position, hit.normal);
        match (answer, truth) {
            (Some(a), Some((p, d))) => {
                // Ties in distance are interchangeable answers; otherwise the same point.
                assert!(
                    a.point.position == p || (a.distance_from(hit.position) - d).abs() <= 1e-7,
                    "query {query:?}: {a:?}, scan {p} at {d}"
                );
                assert_eq!(
                    a.radiance,
                    query.albedo * std::f32::consts::FRAC_1_PI * a.irradiance
                );
                assert_eq!(a.map, map);
                // The part names the same map; the built-in's read is the same answer.
                let by_part = cache.radiance_at(
                    &CacheQuery {
                        map: QueryMap::Part(hit.part),
                        ..query
                    },
                    &mut scratch,
                );
                assert_eq!(by_part, Some(a));
                let by_hit = cache.radiance(scene, &hit, &mut scratch);
                assert_eq!(
                    by_hit,
                    scene.albedo_at(&hit) * std::f32::consts::FRAC_1_PI * a.irradiance
                );
                answered += 1;
            }
            (None, None) => unanswered += 1,
            (a, t) => panic!("query {query:?}: {a:?}, scan {t:?}"),
        }
    }
    assert!(answered > 1500, "{answered} answered, {unanswered} not");
}

#[test]
fn bad_queries_get_no_answer_and_no_panic() {
    let (partitioned, photons) = cornell();
    let scene = partitioned.scene();
    let cache = photons.radiance.as_ref().unwrap();
    let mut scratch = EstimatorScratch::new();
    // A good query: the floor's centre, seen from above.
    let ray = Ray {
        origin: scene.bounds().center(),
        direction: Vec3::NEG_Y,
    };
    let hit = scene.intersect(&ray, f32::INFINITY, RayKind::Other).unwrap();
    let good = CacheQuery::at_hit(scene, &hit);
    let answer = cache
        .radiance_at(&good, &mut scratch)
        .expect("the lit floor has cache points");
    let bad = [
        CacheQuery {
            map: QueryMap::Map(u32::MAX),
            ..good
        },
        CacheQuery {
            map: QueryMap::Map(cache.map_count() as u32),
            ..good
        },
        CacheQuery {
            map: QueryMap::Part(PartId(u32::MAX)),
            ..good
        },
        CacheQuery {
            position: Vec3::NAN,
            ..good
        },
        CacheQuery {
            position: Vec3::new(f32::INFINITY, 0.0, 0.0),
            ..good
        },
        CacheQuery {
            normal: Vec3::ZERO,
            ..good
        },
        CacheQuery {
            normal: Vec3::new(f32::NAN, 1.0, 0.0),
            ..good
        },
        CacheQuery {
            normal: -good.normal,
            ..good
        },
        CacheQuery {
            position: Vec3::splat(1e30),
            ..good
        },
    ];
    for query in bad {
        assert_eq!(cache.radiance_at(&query, &mut scratch), None, "{query:?}");
    }
    // A normal that is not unit is normalised: the same answer as the unit one.
    let long = CacheQuery {
        normal: good.normal * 3.0,
        ..good
    };
    assert_eq!(cache.radiance_at(&long, &mut scratch), Some(answer));
}

/// Per-seed means of the whole image and of its four quadrants (5 regions × 3 channels).
fn region_means(image: &Image) -> Vec<f32> {
    let (w, h) = (image.width() / 2, image.height() / 2);
    let mut means = vec![image.mean()];
    for (x, y) in [(0, 0), (w, 0), (0, h), (w, h)] {
        means.push(image.mean_in_rect(x, y, w, h).unwrap());
    }
    means.iter().flat_map(|m| m.to_array()).collect()
}

/// The example's own tracer, reading the cache only through `radiance_at`, against the
/// built-in final gather on the same cache and settings: 12 independent seeds each, Welch's t
/// of the difference of the mean over seeds for the whole image and each quadrant, each
/// channel (15 statistics, about 22 degrees of freedom) within 4 (two-sided p ≈ 0.0006 each).
#[test]
fn the_outside_tracer_matches_the_built_in_final_gather_within_noise() {
    let (partitioned, photons) = cornell();
    let scene = partitioned.scene();
    let cache = photons.radiance.as_ref().unwrap();
    const SEEDS: u64 = 12;
    let mut own = Vec::new();
    let mut builtin = Vec::new();
    for seed in 0..SEEDS {
        let s = settings(100 + seed);
        let renderer = Renderer::new(EstimatorKind::GeometryCube, s);
        let image = renderer
            .render_from_cache(scene, &photons, &(), &mut RenderStats::default())
            .unwrap();
        builtin.push(region_means(&image));
        let tracer = CacheTracer {
            scene,
            maps: &photons.maps,
            cache,
            estimator: renderer.estimator(),
            options: s.estimator_options(&scene.bounds()),
            gather_rays: s.final_gather.gather_rays,
            corner: s.final_gather.corner_distance_in(&scene.bounds()),
        };
        let shot = Shot {
            width: s.width,
            height: s.height,
            samples: s.samples_per_pixel,
            seed: 200 + seed,
        };
        own.push(region_means(&tracer.render(shot).unwrap()));
    }
    let n = SEEDS as f64;
    let stats = |runs: &[Vec<f32>], i: usize| {
        let mean = runs.iter().map(|r| f64::from(r[i])).sum::<f64>() / n;
        let var = runs.iter().map(|r| (f64::from(r[i]) - mean).powi(2)).sum::<f64>() / (n - 1.0);
        (mean, var)
    };
    let mut worst = 0.0f64;
    for i in 0..own[0].len() {
        let (a, va) = stats(&own, i);
        let (b, vb) = stats(&builtin, i);
        let se = (va / n + vb / n).sqrt();
        let t = (a - b) / se;
        println!(
            "statistic {i}: own {a:.5}, built-in {b:.5}, difference {:+.3} % ± {:.3} % (one s.e.), t = {t:+.2}",
            100.0 * (a - b) / b,
            100.0 * se / b
        );
        worst = worst.max(t.abs());
        assert!(t.abs() < 4.0, "statistic {i}: own {a}, built-in {b}, t = {t}");
    }
    println!("largest |t| {worst:.2}");
}
