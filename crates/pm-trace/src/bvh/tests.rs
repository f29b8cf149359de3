//! Tests of the scene's ray queries: the BVH against the flat scan (brute force), rays along
//! axes, shared edges, and distances against closed forms.

use super::closest::Crossing;
use super::*;
use crate::Rng;
use crate::sampling::uniform_sphere;
use glam::Vec2;

/// The flat scan tests every triangle, so it is the brute-force reference for the BVH:
/// both must find the same closest distance (bit for bit) and the same any-hit answer,
/// also for rays starting within 1e-6…1e-4 of a surface (near corners these hit the
/// adjacent wall almost at once; obvhs's node test used to cull such hits).
#[test]
fn the_bvh_finds_exactly_the_hits_of_the_flat_scan() {
    for name in [
        "lit-unlit-rooms",
        "touching-rooms",
        "cornell-box",
        "split-rooms-4",
    ] {
        let scene = crate::scenes::build(name).unwrap();
        let search = scene.search();
        let (triangles, parts): (Vec<[Vec3; 3]>, Vec<PartSurface>) = search
            .triangles
            .iter()
            .map(|r| {
                (
                    r.v,
                    PartSurface {
                        part: r.part,
                        surface: r.surface,
                    },
                )
            })
            .unzip();
        let shapes = search.shapes.clone();
        let scan = SceneBvh::build_with(triangles.clone(), parts.clone(), shapes.clone(), usize::MAX);
        let bvh = SceneBvh::build_with(triangles.clone(), parts, shapes, 0);
        assert!(
            matches!(scan.triangle_search, Search::Scan(_)) && matches!(bvh.triangle_search, Search::Bvh(_))
        );
        assert!(name != "cornell-box" || matches!(bvh.shape_search, Search::Bvh(_)));
        let triangles: Vec<([Vec3; 3], Vec3)> = triangles.iter().map(|v| (*v, triangle_normal(v))).collect();
        let bounds = scene.bounds();
        let mut rng = Rng::new(17, 3);
        let mut near_hits = 0;
        let mut previous = Ray {
            origin: bounds.min,
            direction: Vec3::X,
        };
        for k in 0..100_000 {
            let mut u = || rng.next_f32();
            let origin = if k % 2 == 0 {
                bounds.min + (bounds.max - bounds.min) * Vec3::new(u(), u(), u())
            } else {
                let (v, normal) = triangles[(u() * triangles.len() as f32) as usize % triangles.len()];
                let (a, b) = (u(), u());
                let (a, b) = if a + b > 1.0 { (1.0 - a, 1.0 - b) } else { (a, b) };
                let offset = 1e-6 * 100f32.powf(u()) * if u() < 0.5 { -1.0 } else { 1.0 };
                v[0] + (v[1] - v[0]) * a + (v[2] - v[0]) * b + normal * offset
            };
            // Every fifth ray runs exactly along an axis, or nearly so (a component below
            // obvhs's inverse-direction cut-off of f32::EPSILON).
            let direction = match k % 5 {
                0 => {
                    let mut d = Vec3::ZERO;
                    d[(u() * 3.0) as usize % 3] = if u() < 0.5 { -1.0 } else { 1.0 };
                    if k % 10 == 0 {
                        d[(u() * 3.0) as usize % 3] += 1e-8;
                    }
                    d.normalize()
                }
                _ => uniform_sphere(Vec2::new(u(), u())),
            };
            let ray = Ray { origin, direction };
            let t_max = if k % 3 == 0 { 0.05 } else { f32::INFINITY };
            let part_of = |b: &SceneBvh, (t, hit): (f32, HitPrimitive)| {
                (t.to_bits(), b.part_and_normal(hit, ray.at(t)).unwrap().0)
            };
            let expected = scan
                .closest(&ray, 0.0, t_max, |_| true)
                .map(|h| part_of(&scan, h));
            let found = bvh.closest(&ray, 0.0, t_max, |_| true).map(|h| part_of(&bvh, h));
            assert_eq!(
                found, expected,
                "{name}: closest, ray {k} from {origin} along {direction}"
            );
            assert_eq!(
                bvh.any_hit(&ray, 0.0, t_max),
                expected.is_some(),
                "{name}: any hit, ray {k}"
            );
            // The same ray cast beside the previous one through the interleaved pair search.
            let [_, paired] = bvh.closest_pair([&previous, &ray], t_max, [Leaving::Nothing; 2]);
            let [paired_first, _] = bvh.closest_pair([&previous, &ray], t_max, [Leaving::Nothing; 2]);
            assert_eq!(
                paired.map(|h| part_of(&bvh, h)),
                expected,
                "{name}: closest of a pair, ray {k}"
            );
            let previous_alone = bvh.closest(&previous, 0.0, t_max, |_| true);
            assert_eq!(paired_first, previous_alone, "{name}: first of a pair, ray {k}");
            previous = ray;
            near_hits += expected.is_some_and(|(t, _)| f32::from_bits(t) < 1e-4) as u32;
        }
        assert!(near_hits > 100, "{name}: only {near_hits} hits closer than 1e-4");
    }
}

#[test]
fn rays_along_an_axis_find_walls_far_away_just_inside_their_edge() {
    // A wall at x = 10 spanning y, z ∈ [0, 1]; rays along +x at heights just below its top
    // edge. obvhs inverts a zero direction component to 1/f32::EPSILON, not infinity, so
    // its node test would see the slab in y end after t = (1 − y) / f32::EPSILON.
    let wall = |x: f32| {
        [
            [
                Vec3::new(x, 0.0, 0.0),
                Vec3::new(x, 1.0, 0.0),
                Vec3::new(x, 1.0, 1.0),
            ],
            [
                Vec3::new(x, 0.0, 0.0),
                Vec3::new(x, 1.0, 1.0),
                Vec3::new(x, 0.0, 1.0),
            ],
        ]
    };
    let triangles: Vec<[Vec3; 3]> = (0..40).flat_map(|i| wall(10.0 + i as f32)).collect();
    let parts = vec![
        PartSurface {
            part: PartId(0),
            surface: 0
        };
        triangles.len()
    ];
    let scan = SceneBvh::build_with(triangles.clone(), parts.clone(), Vec::new(), usize::MAX);
    let bvh = SceneBvh::build_with(triangles, parts, Vec::new(), 0);
    for below in [1e-7f32, 1e-6, 1e-5, 1e-3] {
        for direction in [Vec3::X, Vec3::new(1.0, 1e-9, 0.0)] {
            let ray = Ray {
                origin: Vec3::new(0.0, 1.0 - below, 0.5),
                direction,
            };
            let expected = scan.closest(&ray, 0.0, f32::INFINITY, |_| true).map(|(t, _)| t);
            assert_eq!(expected, Some(10.0), "{below}");
            let found = bvh.closest(&ray, 0.0, f32::INFINITY, |_| true).map(|(t, _)| t);
            assert_eq!(found, expected, "{below} below the edge along {direction}");
            assert!(bvh.any_hit(&ray, 0.0, f32::INFINITY));
        }
    }
}

#[test]
fn watertight_test_hits_the_shared_edge_of_two_triangles_exactly_once_or_twice_never_zero() {
    // A quad split along its diagonal; rays aimed exactly at the diagonal must hit.
    let q = [
        Vec3::new(0.0, 0.0, 0.0),
        Vec3::new(1.0, 0.0, 0.0),
        Vec3::new(1.0, 1.0, 0.0),
        Vec3::new(0.0, 1.0, 0.0),
    ];
    let t1 = [q[0], q[1], q[2]];
    let t2 = [q[0], q[2], q[3]];
    for i in 0..=100 {
        let s = i as f32 / 100.0;
        let target = Vec3::new(s, s, 0.0);
        let origin = Vec3::new(0.3, 0.7, 1.0);
        let w = WatertightRay::new(origin, (target - origin).normalize());
        let hits = [t1, t2]
            .iter()
            .filter(|t| w.intersect_triangle(t, 0.0, f32::INFINITY).is_finite())
            .count();
        assert!(hits >= 1, "ray to the diagonal at {s} slipped through");
    }
}

#[test]
fn triangle_distance_matches_the_plane_distance() {
    let tri = [
        Vec3::new(-1.0, -1.0, 2.0),
        Vec3::new(1.0, -1.0, 2.0),
        Vec3::new(0.0, 1.0, 2.0),
    ];
    let d = Vec3::new(0.1, 0.05, 1.0).normalize();
    let w = WatertightRay::new(Vec3::ZERO, d);
    let t = w.intersect_triangle(&tri, 0.0, f32::INFINITY);
    assert!((t - 2.0 / d.z).abs() < 1e-5);
    let w = WatertightRay::new(Vec3::ZERO, -d);
    assert_eq!(w.intersect_triangle(&tri, 0.0, f32::INFINITY), f32::INFINITY);
}

/// The BVH against the flat scan at the large end: 21,600 coplanar-tiled triangles (deep SAH
/// trees over zero-thickness walls) and a fan of 5,000 thin triangles sharing one vertex (the
/// input that made obvhs's own builder quadratic), every ray's closest hit and part equal.
#[test]
fn the_bvh_matches_the_flat_scan_on_many_triangles_and_on_a_fan() {
    let rooms = crate::scenes::scale::split_rooms(30).unwrap();
    let rooms: (Vec<[Vec3; 3]>, Vec<PartSurface>) = rooms
        .search()
        .triangles
        .iter()
        .map(|r| {
            (
                r.v,
                PartSurface {
                    part: r.part,
                    surface: r.surface,
                },
            )
        })
        .unzip();
    let n = 5_000u32;
    let fan: Vec<[Vec3; 3]> = (0..n)
        .map(|i| {
            let angle = |i: u32| i as f32 / n as f32 * std::f32::consts::TAU;
            let rim = |a: f32| Vec3::new(a.cos(), 0.0, a.sin());
            [Vec3::ZERO, rim(angle(i + 1)), rim(angle(i))]
        })
        .collect();
    let fan_parts = (0..n)
        .map(|i| PartSurface {
            part: PartId(i),
            surface: 0,
        })
        .collect();
    for (name, (triangles, parts)) in [("rooms", rooms), ("fan", (fan, fan_parts))] {
        assert!(triangles.len() >= 5_000);
        let scan = SceneBvh::build_with(triangles.clone(), parts.clone(), Vec::new(), usize::MAX);
        let bvh = SceneBvh::build_with(triangles.clone(), parts, Vec::new(), 0);
        let mut rng = Rng::new(23, 1);
        let mut hits = 0;
        for k in 0..3_000 {
            let mut u = || rng.next_f32();
            let origin = if name == "fan" {
                Vec3::new(
                    2.0 * u() - 1.0,
                    if k % 2 == 0 { 0.5 } else { -0.5 },
                    2.0 * u() - 1.0,
                )
            } else {
                Vec3::new(u() * 2.02, u(), u())
            };
            let direction = if name == "fan" {
                // At the fan: anywhere on its disc (a little past the rim too), or exactly at
                // the vertex every triangle shares.
                let (r, a) = (1.05 * u().sqrt(), u() * std::f32::consts::TAU);
                let target = if k % 10 == 0 {
                    Vec3::ZERO
                } else {
                    Vec3::new(r * a.cos(), 0.0, r * a.sin())
                };
                (target - origin).normalize()
            } else {
                uniform_sphere(Vec2::new(u(), u()))
            };
            let ray = Ray { origin, direction };
            let closest = |b: &SceneBvh| b.closest(&ray, 0.0, f32::INFINITY, |_| true);
            let (expected, found) = (closest(&scan), closest(&bvh));
            assert_eq!(
                found.map(|(t, _)| t.to_bits()),
                expected.map(|(t, _)| t.to_bits()),
                "{name}: ray {k}"
            );
            assert_eq!(
                bvh.any_hit(&ray, 0.0, f32::INFINITY),
                expected.is_some(),
                "{name}: ray {k}"
            );
            if let (Some((t, HitPrimitive::Triangle(i))), Some((_, scan_hit))) = (found, expected) {
                // The triangle reported is really hit there. Rays at the fan's shared vertex
                // hit all 5,000 at one distance, where either answer is right; elsewhere the
                // part is the scan's.
                let w = WatertightRay::new(ray.origin, ray.direction);
                assert_eq!(
                    w.intersect_triangle(&bvh.triangles[i as usize].v, 0.0, f32::INFINITY),
                    t
                );
                if name == "rooms" {
                    let part_of = |b: &SceneBvh, h| b.part_and_normal(h, ray.at(t)).unwrap().0;
                    assert_eq!(
                        part_of(&bvh, HitPrimitive::Triangle(i)),
                        part_of(&scan, scan_hit),
                        "ray {k}"
                    );
                }
            }
            hits += expected.is_some() as u32;
        }
        assert!(hits > 1_000, "{name}: only {hits} hits");
    }
}

/// A stack of 40,000 overlapping triangles that every test ray crosses, searched with a filter
/// that accepts one surface in seven: each node test finds all its children, so the traversal
/// stack grows past its inline part and spills, and the nearest-first order and the culling
/// behind the current hit both decide which of thousands of candidates is returned. The BVH
/// must agree with the flat scan on every ray, from below, from above, and from inside.
#[test]
fn the_bvh_matches_the_flat_scan_through_a_deep_stack_of_layers() {
    let layers = 40_000u32;
    let mut rng = Rng::new(29, 0);
    let triangles: Vec<[Vec3; 3]> = (0..layers)
        .map(|i| {
            let z = i as f32 * 1e-3;
            let (dx, dy) = (rng.next_f32() - 0.5, rng.next_f32() - 0.5);
            [
                Vec3::new(-2.0 + dx, -2.0 + dy, z),
                Vec3::new(2.0 + dx, -2.0, z),
                Vec3::new(dx, 2.0 + dy, z),
            ]
        })
        .collect();
    let parts: Vec<PartSurface> = (0..layers)
        .map(|i| PartSurface {
            part: PartId(i),
            surface: i % 7,
        })
        .collect();
    let scan = SceneBvh::build_with(triangles.clone(), parts.clone(), Vec::new(), usize::MAX);
    let bvh = SceneBvh::build_with(triangles, parts, Vec::new(), 0);
    let top = layers as f32 * 1e-3;
    for k in 0..300 {
        let mut u = || rng.next_f32();
        let origin = Vec3::new(
            0.4 * u() - 0.2,
            0.4 * u() - 0.2,
            [-1.0, top + 1.0, top * u()][k % 3],
        );
        let toward = if k % 3 == 1 { -1.0 } else { 1.0 };
        let direction = Vec3::new(0.1 * u() - 0.05, 0.1 * u() - 0.05, toward).normalize();
        let ray = Ray { origin, direction };
        let surface = k as u32 % 7;
        let accept = |c: &Crossing| c.surface == surface;
        let part = |b: &SceneBvh, hit: Option<(f32, HitPrimitive)>| {
            hit.map(|(t, h)| (t, b.part_and_normal(h, ray.at(t)).unwrap().0))
        };
        let expected = part(&scan, scan.closest(&ray, 0.0, f32::INFINITY, accept));
        let found = part(&bvh, bvh.closest(&ray, 0.0, f32::INFINITY, accept));
        assert!(expected.is_some(), "ray {k} should cross accepted layers");
        assert_eq!(found, expected, "ray {k}");
        assert_eq!(
            bvh.any_hit(&ray, 0.0, f32::INFINITY),
            scan.any_hit(&ray, 0.0, f32::INFINITY),
            "ray {k}"
        );
    }
}

/// The top of the triangle range: a million triangles (the rooms with every face split
/// 205 × 205), random rays from inside against the flat scan over all of them (the brute
/// force), one at a time and in pairs.
#[test]
fn the_bvh_matches_the_flat_scan_at_a_million_triangles() {
    let rooms = crate::scenes::scale::split_rooms(205).unwrap();
    let (triangles, parts): (Vec<[Vec3; 3]>, Vec<PartSurface>) = rooms
        .search()
        .triangles
        .iter()
        .map(|r| {
            (
                r.v,
                PartSurface {
                    part: r.part,
                    surface: r.surface,
                },
            )
        })
        .unzip();
    assert!(triangles.len() > 1_000_000, "{}", triangles.len());
    let scan = SceneBvh::build_with(triangles, parts, Vec::new(), usize::MAX);
    let bvh = rooms.search();
    let mut rng = Rng::new(31, 0);
    let rays: Vec<Ray> = (0..200)
        .map(|_| {
            let mut u = || rng.next_f32();
            Ray {
                origin: Vec3::new(u() * 2.02, u(), u()),
                direction: uniform_sphere(Vec2::new(u(), u())),
            }
        })
        .collect();
    let part = |b: &SceneBvh, ray: &Ray, hit: Option<(f32, HitPrimitive)>| {
        hit.map(|(t, h)| (t.to_bits(), b.part_and_normal(h, ray.at(t)).unwrap().0))
    };
    for (k, pair) in rays.chunks_exact(2).enumerate() {
        let paired = bvh.closest_pair([&pair[0], &pair[1]], f32::INFINITY, [Leaving::Nothing; 2]);
        for (ray, found) in pair.iter().zip(paired) {
            let expected = part(&scan, ray, scan.closest(ray, 0.0, f32::INFINITY, |_| true));
            assert!(expected.is_some(), "rays from inside the rooms hit a wall");
            assert_eq!(
                part(bvh, ray, bvh.closest(ray, 0.0, f32::INFINITY, |_| true)),
                expected,
                "pair {k}"
            );
            assert_eq!(part(bvh, ray, found), expected, "pair {k}, paired");
        }
    }
}
