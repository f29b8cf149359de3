//! Merging coplanar polygons, against the polygons clipped one by one: on random grids (quads
//! and triangles, L-shapes, holes), fans and strips, the area inside random cubes and balls
//! (also straddling edges and corners) is the same, grids become one polygon, and polygons
//! that only touch at a corner or meet at a fold stay apart.

use pm_geom::glam::{Vec3, vec3};
use pm_geom::{
    Aabb, Ball, ClipScratch, CoplanarMerger, GatherVolume, MergeOptions, merge_coplanar_polygons,
    polygon_area, polygon_normal,
};
use proptest::prelude::*;
use std::time::Instant;

/// xorshift64*: the test's own stream, so a proptest seed reproduces a whole case.
struct Rng(u64);

impl Rng {
    fn f32(&mut self) -> f32 {
        self.0 ^= self.0 >> 12;
        self.0 ^= self.0 << 25;
        self.0 ^= self.0 >> 27;
        (self.0.wrapping_mul(0x2545_f491_4f6c_dd1d) >> 40) as f32 / (1u64 << 24) as f32
    }
    fn range(&mut self, lo: f32, hi: f32) -> f32 {
        lo + (hi - lo) * self.f32()
    }
}

/// An `n × m` grid of cells in the plane through `origin` spanned by `u`, `v` (cell size
/// `cell`), its grid points computed once so neighbours share them exactly. `keep(i, j)`
/// says which cells exist; a cell is one quad, or two triangles when `split(i, j)` is true.
fn grid(
    origin: Vec3,
    (u, v): (Vec3, Vec3),
    (n, m): (usize, usize),
    cell: f32,
    keep: impl Fn(usize, usize) -> bool,
    mut split: impl FnMut(usize, usize) -> u8,
) -> Vec<Vec<Vec3>> {
    let point = |i: usize, j: usize| origin + u * (i as f32 * cell) + v * (j as f32 * cell);
    let mut polygons = Vec::new();
    for j in 0..m {
        for i in 0..n {
            if !keep(i, j) {
                continue;
            }
            let [a, b, c, d] = [point(i, j), point(i + 1, j), point(i + 1, j + 1), point(i, j + 1)];
            match split(i, j) {
                0 => polygons.push(vec![a, b, c, d]),
                1 => polygons.extend([vec![a, b, c], vec![a, c, d]]),
                _ => polygons.extend([vec![a, b, d], vec![b, c, d]]),
            }
        }
    }
    polygons
}

/// A frame in a random orientation.
fn random_frame(rng: &mut Rng) -> (Vec3, Vec3) {
    let n = vec3(rng.range(-1., 1.), rng.range(-1., 1.), rng.range(-1., 1.))
        .try_normalize()
        .unwrap_or(Vec3::Y);
    n.any_orthonormal_pair()
}

/// Σ over polygons of the area inside `volume`, in f64.
fn area_inside(volume: &impl GatherVolume, polygons: &[Vec<Vec3>], scratch: &mut ClipScratch) -> f64 {
    polygons
        .iter()
        .map(|p| f64::from(volume.polygon_area_inside(p, polygon_normal(p).unwrap(), scratch)))
        .sum()
}

fn total_area(polygons: &[Vec<Vec3>]) -> f64 {
    polygons.iter().map(|p| f64::from(polygon_area(p))).sum()
}

/// Checks total area and the area inside `volumes` random cubes and balls around `polygons`
/// (centres up to 20 % outside their bounds, sizes from 1 % to 60 % of their diagonal, some
/// centred on a vertex so they straddle edges and corners) against the merged polygons.
fn assert_same_area_everywhere(original: &[Vec<Vec3>], merged: &[Vec<Vec3>], rng: &mut Rng, volumes: usize) {
    let (total, merged_total) = (total_area(original), total_area(merged));
    assert!(
        (total - merged_total).abs() <= 1e-5 * total,
        "total area {total} became {merged_total}"
    );
    let bounds = original
        .iter()
        .fold(Aabb::EMPTY, |b, p| b.union(Aabb::from_points(p)));
    let diagonal = bounds.diagonal();
    let all: Vec<Vec3> = original.iter().flatten().copied().collect();
    let mut scratch = ClipScratch::new();
    for k in 0..volumes {
        let center = if k % 3 == 0 {
            all[(rng.f32() * all.len() as f32) as usize % all.len()]
        } else {
            let t = vec3(rng.range(-0.2, 1.2), rng.range(-0.2, 1.2), rng.range(-0.2, 1.2));
            bounds.min + t * bounds.size()
        };
        let size = diagonal * rng.range(0.01, 0.6);
        // f32 coordinates of magnitude up to `max_coord` are rounded to within ε·max_coord, so
        // the boundary of the region inside a volume (at most 8·size long for the cube, 2π·size
        // for the ball, where a near-tangent plane also moves the disc's edge by as much) may
        // move that far either way: an area error of a few ε·max_coord·8·size, however small
        // the area. Relative 1e-5 covers the rest.
        let max_coord = bounds
            .min
            .abs()
            .max(bounds.max.abs())
            .max(center.abs())
            .max_element();
        let boundary_rounding = 4.0 * f64::from(f32::EPSILON * max_coord * 8.0 * size);
        let tolerance = |a: f64| 1e-5 * a + 1e-6 * f64::from(diagonal * diagonal) + boundary_rounding;
        let cube = Aabb::cube(center, size);
        let (a, b) = (
            area_inside(&cube, original, &mut scratch),
            area_inside(&cube, merged, &mut scratch),
        );
        assert!(
            (a - b).abs() <= tolerance(a),
            "cube {cube:?}: per face {a}, merged {b}"
        );
        let ball = Ball::new(center, size);
        let (a, b) = (
            area_inside(&ball, original, &mut scratch),
            area_inside(&ball, merged, &mut scratch),
        );
        assert!(
            (a - b).abs() <= tolerance(a),
            "ball {ball:?}: per face {a}, merged {b}"
        );
    }
}

fn merge(polygons: &[Vec<Vec3>]) -> Vec<Vec<Vec3>> {
    merge_coplanar_polygons(polygons.iter().map(Vec::as_slice), MergeOptions::DEFAULT)
}

fn assert_convex(polygons: &[Vec<Vec3>]) {
    for p in polygons {
        let n = polygon_normal(p).unwrap();
        for i in 0..p.len() {
            let (a, b, c) = (p[i], p[(i + 1) % p.len()], p[(i + 2) % p.len()]);
            assert!((b - a).cross(c - b).dot(n) > 0.0, "not strictly convex: {p:?}");
        }
    }
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(48))]

    /// Grids of quads and triangles (full, L-shaped, with a hole) in random planes.
    #[test]
    fn merged_grids_have_the_same_area_in_any_cube_or_ball(
        seed in 1u64..u64::MAX,
        n in 1usize..14,
        m in 1usize..14,
        shape in 0u8..3,
        triangles in 0u8..3,
    ) {
        let mut rng = Rng(seed);
        let frame = random_frame(&mut rng);
        let origin = vec3(rng.range(-5., 5.), rng.range(-5., 5.), rng.range(-5., 5.));
        let cell = rng.range(0.01, 1.0);
        let keep = |i: usize, j: usize| match shape {
            0 => true,
            1 => !(i >= n / 2 && j >= m / 2 && n > 1 && m > 1),      // L-shape
            _ => !(i == n / 2 && j == m / 2 && n > 2 && m > 2),       // hole
        };
        let mut cells = Rng(seed ^ 0x9e37_79b9);
        let split = |_: usize, _: usize| match triangles {
            0 => 0,
            1 => 1 + (cells.f32() * 2.0) as u8,
            _ => (cells.f32() * 3.0) as u8,
        };
        let original = grid(origin, frame, (n, m), cell, keep, split);
        let merged = merge(&original);
        assert_convex(&merged);
        prop_assert!(merged.len() <= original.len());
        if shape == 0 {
            prop_assert_eq!(merged.len(), 1, "a full grid is one rectangle");
            prop_assert_eq!(merged[0].len(), 4);
        }
        assert_same_area_everywhere(&original, &merged, &mut rng, 40);
    }

    /// Triangle fans over a convex polygon and zig-zag strips of triangles.
    #[test]
    fn merged_fans_and_strips_have_the_same_area_in_any_cube_or_ball(
        seed in 1u64..u64::MAX,
        k in 3usize..40,
        strip in any::<bool>(),
    ) {
        let mut rng = Rng(seed);
        let (u, v) = random_frame(&mut rng);
        let origin = vec3(rng.range(-5., 5.), rng.range(-5., 5.), rng.range(-5., 5.));
        let r = rng.range(0.05, 3.0);
        let original: Vec<Vec<Vec3>> = if strip {
            let (top, bottom): (Vec<Vec3>, Vec<Vec3>) = (0..=k)
                .map(|i| {
                    let x = origin + u * (i as f32 * r);
                    (x + v * r, x)
                })
                .unzip();
            (0..k)
                .flat_map(|i| [vec![bottom[i], bottom[i + 1], top[i]], vec![bottom[i + 1], top[i + 1], top[i]]])
                .collect()
        } else {
            let ring: Vec<Vec3> = (0..k)
                .map(|i| {
                    let t = i as f32 / k as f32 * std::f32::consts::TAU;
                    origin + r * (t.cos() * u + t.sin() * v)
                })
                .collect();
            (0..k).map(|i| vec![origin, ring[i], ring[(i + 1) % k]]).collect()
        };
        let merged = merge(&original);
        assert_convex(&merged);
        prop_assert_eq!(merged.len(), 1, "{} triangles", original.len());
        assert_same_area_everywhere(&original, &merged, &mut rng, 40);
    }
}

#[test]
fn a_100_by_100_grid_of_quads_becomes_one_quad() {
    let original = grid(
        vec3(0., 0., 0.),
        (Vec3::X, Vec3::Z),
        (100, 100),
        0.05,
        |_, _| true,
        |_, _| 0,
    );
    let merged = merge(&original);
    assert_eq!(merged.len(), 1);
    assert_eq!(merged[0].len(), 4);
    assert!((polygon_area(&merged[0]) - 25.0).abs() < 1e-3);
}

#[test]
fn squares_touching_only_at_a_corner_are_not_merged() {
    let a = vec![
        vec3(0., 0., 0.),
        vec3(1., 0., 0.),
        vec3(1., 1., 0.),
        vec3(0., 1., 0.),
    ];
    let b: Vec<Vec3> = a.iter().map(|&p| p + vec3(1., 1., 0.)).collect();
    let merged = merge(&[a.clone(), b.clone()]);
    assert_eq!(merged, vec![a, b]);
}

#[test]
fn coplanar_squares_side_by_side_without_a_shared_edge_are_not_merged() {
    // Touching along x = 1 but with their own, unwelded vertices half a unit apart.
    let a = vec![
        vec3(0., 0., 0.),
        vec3(1., 0., 0.),
        vec3(1., 1., 0.),
        vec3(0., 1., 0.),
    ];
    let b = vec![
        vec3(1., 0.5, 0.),
        vec3(2., 0.5, 0.),
        vec3(2., 1.5, 0.),
        vec3(1., 1.5, 0.),
    ];
    assert_eq!(merge(&[a.clone(), b.clone()]).len(), 2);
}

#[test]
fn an_accordion_fold_is_not_merged() {
    // Strips sharing edges, alternately tilted up and down by 10°, then by 0.5°.
    for degrees in [10.0f32, 0.5] {
        let rise = degrees.to_radians().tan();
        let ridge = |i: usize| vec3(i as f32, if i % 2 == 1 { rise } else { 0.0 }, 0.0);
        let strips: Vec<Vec<Vec3>> = (0..6)
            .map(|i| {
                let (a, b) = (ridge(i), ridge(i + 1));
                vec![a, a + Vec3::Z, b + Vec3::Z, b]
            })
            .collect();
        let merged = merge(&strips);
        assert_eq!(merged.len(), strips.len(), "{degrees}° folds merged");
    }
}

#[test]
fn flipped_or_offset_coplanar_neighbours_are_not_merged() {
    let a = vec![
        vec3(0., 0., 0.),
        vec3(1., 0., 0.),
        vec3(1., 1., 0.),
        vec3(0., 1., 0.),
    ];
    // Shares the edge the same way round (a back face): not a neighbour.
    let flipped = vec![
        vec3(1., 0., 0.),
        vec3(1., 1., 0.),
        vec3(2., 1., 0.),
        vec3(2., 0., 0.),
    ];
    assert_eq!(merge(&[a.clone(), flipped]).len(), 2);
    // Shares the edge but its far side is lifted by 1e-3 (a thousandth of the size): a crease.
    let lifted = vec![
        vec3(1., 0., 0.),
        vec3(2., 0., 1e-3),
        vec3(2., 1., 1e-3),
        vec3(1., 1., 0.),
    ];
    assert_eq!(merge(&[a, lifted]).len(), 2);
}

#[test]
fn an_edge_used_by_three_polygons_joins_none_of_them() {
    let a = vec![
        vec3(0., 0., 0.),
        vec3(1., 0., 0.),
        vec3(1., 1., 0.),
        vec3(0., 1., 0.),
    ];
    let b = vec![
        vec3(1., 0., 0.),
        vec3(2., 0., 0.),
        vec3(2., 1., 0.),
        vec3(1., 1., 0.),
    ];
    let c = vec![
        vec3(1., 0., 0.),
        vec3(1., 0., -1.),
        vec3(1., 1., -1.),
        vec3(1., 1., 0.),
    ];
    let c_reversed: Vec<Vec3> = c.iter().rev().copied().collect();
    assert_eq!(merge(&[a.clone(), b.clone(), c]).len(), 3);
    assert_eq!(merge(&[a, b, c_reversed]).len(), 3);
}

#[test]
fn degenerate_polygons_are_rejected_like_polygon_set_does() {
    let mut merger = CoplanarMerger::new(MergeOptions::DEFAULT);
    assert!(!merger.push(&[Vec3::ZERO, Vec3::X]));
    assert!(!merger.push(&[Vec3::ZERO, Vec3::X, 2.0 * Vec3::X]));
    assert!(!merger.push(&[Vec3::ZERO, Vec3::X, Vec3::splat(f32::NAN)]));
    assert!(merger.is_empty());
    let mut count = 0;
    merger.merge(|_| count += 1);
    assert_eq!(count, 0);
}

#[test]
fn merging_240k_triangles_of_six_walls_gives_six_polygons() {
    // Timed for the record only (no timing assertions: machines are noisy); the time is
    // printed. Six separate 5 m × 10 m walls in random planes, each 100 × 200 cells split into two
    // triangles (the split rooms have 10^4 quads per map; this is all in one merger).
    let mut rng = Rng(7);
    let mut polygons = Vec::new();
    for w in 0..6 {
        let origin = vec3(w as f32 * 12.0, rng.range(-5., 5.), rng.range(-5., 5.));
        polygons.extend(grid(
            origin,
            random_frame(&mut rng),
            (100, 200),
            0.05,
            |_, _| true,
            |_, _| 1,
        ));
    }
    assert_eq!(polygons.len(), 240_000);
    let mut merger = CoplanarMerger::default();
    let start = Instant::now();
    for p in &polygons {
        assert!(merger.push(p));
    }
    let mut merged = Vec::new();
    merger.merge(|p| merged.push(p.to_vec()));
    let elapsed = start.elapsed();
    assert_eq!(merged.len(), 6, "one polygon per wall");
    eprintln!(
        "merged 240k triangles into {} polygons in {elapsed:?}",
        merged.len()
    );
}
