//! Clipping to a box against analytic areas: axis-aligned rectangles, whole polygons,
//! octant sums, translation and axis-swap invariance, triangles cut by one plane, and the
//! plane split helper.

mod common;

use common::{arb_polygon, close};
use pm_geom::glam::{Vec3, vec3};
use pm_geom::{
    Aabb, ClipScratch, GatherVolume, Plane, clip_polygon_to_aabb, polygon_area, split_convex_polygon_by_plane,
};
use proptest::prelude::*;

fn arb_box() -> impl Strategy<Value = Aabb> {
    (
        prop::array::uniform3(-1.5f32..1.5),
        prop::array::uniform3(0.05f32..2.0),
    )
        .prop_map(|(min, size)| {
            Aabb::new(
                Vec3::from_array(min),
                Vec3::from_array(min) + Vec3::from_array(size),
            )
        })
}

/// Length of `[a0, a1] ∩ [b0, b1]`.
fn overlap(a0: f32, a1: f32, b0: f32, b1: f32) -> f32 {
    (a1.min(b1) - a0.max(b0)).max(0.0)
}

fn clipped_area(polygon: &[Vec3], aabb: &Aabb) -> f32 {
    polygon_area(clip_polygon_to_aabb(polygon, aabb, &mut ClipScratch::new()))
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(512))]

    /// An axis-aligned rectangle in a box keeps exactly the intersection rectangle.
    #[test]
    fn axis_aligned_rectangle_keeps_intersection_rectangle(
        aabb in arb_box(),
        axis in 0usize..3,
        level in -2.0f32..2.0,
        lo in prop::array::uniform2(-2.0f32..2.0),
        size in prop::array::uniform2(0.01f32..2.0),
    ) {
        let (a, b) = ((axis + 1) % 3, (axis + 2) % 3);
        let corner = |s: f32, t: f32| {
            let mut p = Vec3::ZERO;
            p[axis] = level;
            p[a] = lo[0] + s * size[0];
            p[b] = lo[1] + t * size[1];
            p
        };
        let rect = [corner(0., 0.), corner(1., 0.), corner(1., 1.), corner(0., 1.)];
        let inside_level = aabb.min[axis] <= level && level <= aabb.max[axis];
        let expected = if inside_level {
            overlap(lo[0], lo[0] + size[0], aabb.min[a], aabb.max[a])
                * overlap(lo[1], lo[1] + size[1], aabb.min[b], aabb.max[b])
        } else {
            0.0
        };
        let got = clipped_area(&rect, &aabb);
        prop_assert!(close(got, expected, size[0] * size[1], 1e-4), "got {got}, expected {expected}");
        let mut normal = Vec3::ZERO;
        normal[axis] = 1.0;
        let trait_area = aabb.polygon_area_inside(&rect, normal, &mut ClipScratch::new());
        prop_assert!(close(trait_area, expected, size[0] * size[1], 1e-4));
    }

    /// A polygon wholly inside keeps its closed-form area; wholly outside gives nothing.
    #[test]
    fn polygon_inside_keeps_area_outside_gives_zero(poly in arb_polygon(), margin in 0.0f32..1.0, side in 0usize..6) {
        let bounds = Aabb::from_points(&poly.vertices);
        let inside = Aabb::new(bounds.min - Vec3::splat(margin), bounds.max + Vec3::splat(margin));
        let mut scratch = ClipScratch::new();
        let clipped = clip_polygon_to_aabb(&poly.vertices, &inside, &mut scratch);
        prop_assert!(close(polygon_area(clipped), poly.area, poly.area, 1e-4));
        let area = inside.polygon_area_inside(&poly.vertices, poly.normal, &mut scratch);
        prop_assert!(close(area, poly.area, poly.area, 1e-4));
        // A box beyond one side of the bounds.
        let axis = side % 3;
        let mut outside = inside;
        if side < 3 {
            outside.min[axis] = bounds.max[axis] + 1e-3 + margin;
            outside.max[axis] = outside.min[axis] + 1.0;
        } else {
            outside.max[axis] = bounds.min[axis] - 1e-3 - margin;
            outside.min[axis] = outside.max[axis] - 1.0;
        }
        prop_assert!(clip_polygon_to_aabb(&poly.vertices, &outside, &mut scratch).is_empty());
        prop_assert_eq!(outside.polygon_area_inside(&poly.vertices, poly.normal, &mut scratch), 0.0);
    }

    /// The areas in the eight octants of a box add up to the area in the box.
    #[test]
    fn octant_areas_sum_to_box_area(poly in arb_polygon(), aabb in arb_box(), split in prop::array::uniform3(0.1f32..0.9)) {
        let mid = aabb.min + aabb.size() * Vec3::from_array(split);
        let mut scratch = ClipScratch::new();
        let whole = aabb.polygon_area_inside(&poly.vertices, poly.normal, &mut scratch);
        let mut sum = 0.0;
        for octant in 0..8 {
            let pick = |bit: usize, axis: usize| if octant >> bit & 1 == 0 {
                (aabb.min[axis], mid[axis])
            } else {
                (mid[axis], aabb.max[axis])
            };
            let (x, y, z) = (pick(0, 0), pick(1, 1), pick(2, 2));
            let sub = Aabb::new(vec3(x.0, y.0, z.0), vec3(x.1, y.1, z.1));
            sum += sub.polygon_area_inside(&poly.vertices, poly.normal, &mut scratch);
        }
        prop_assert!(close(sum, whole, poly.area, 1e-4), "sum {sum}, whole {whole}");
    }

    /// Moving polygon and box together, or swapping axes in both, changes nothing.
    #[test]
    fn area_is_invariant_under_translation_and_axis_swap(
        poly in arb_polygon(),
        aabb in arb_box(),
        shift in prop::array::uniform3(-10.0f32..10.0),
    ) {
        let area = clipped_area(&poly.vertices, &aabb);
        let t = Vec3::from_array(shift);
        let moved: Vec<Vec3> = poly.vertices.iter().map(|&p| p + t).collect();
        let moved_area = clipped_area(&moved, &Aabb::new(aabb.min + t, aabb.max + t));
        prop_assert!(close(moved_area, area, poly.area, 1e-4), "{moved_area} vs {area}");
        // A cyclic permutation (a rotation) and a swap (a mirror) of the axes.
        for swap in [|p: Vec3| vec3(p.y, p.z, p.x), |p: Vec3| vec3(p.y, p.x, p.z)] {
            let swapped: Vec<Vec3> = poly.vertices.iter().map(|&p| swap(p)).collect();
            let swapped_box = Aabb::new(swap(aabb.min), swap(aabb.max));
            let swapped_area = clipped_area(&swapped, &swapped_box);
            prop_assert!(close(swapped_area, area, poly.area, 1e-4), "{swapped_area} vs {area}");
        }
    }

    /// A triangle cut by one box face: the corner triangle beyond the cut has area
    /// `A · t₁ · t₂` (t the edge fractions from the lone vertex), a closed form.
    #[test]
    fn triangle_cut_by_one_plane_matches_closed_form(
        v in prop::array::uniform3(prop::array::uniform3(-1.0f32..1.0)),
        axis in 0usize..3,
        cut in 0.05f32..0.95,
    ) {
        let tri = v.map(Vec3::from_array);
        let total = polygon_area(&tri);
        prop_assume!(total > 0.05);
        // Lone vertex: the one with the largest coordinate on `axis`.
        let top = (0..3).max_by(|&i, &j| tri[i][axis].total_cmp(&tri[j][axis])).unwrap();
        let (p, q, r) = (tri[top], tri[(top + 1) % 3], tri[(top + 2) % 3]);
        let second = q[axis].max(r[axis]);
        prop_assume!(p[axis] - second > 0.05);
        let level = second + cut * (p[axis] - second);
        let t1 = (p[axis] - level) / (p[axis] - q[axis]);
        let t2 = (p[axis] - level) / (p[axis] - r[axis]);
        let expected = total * (1.0 - t1 * t2);
        let mut aabb = Aabb::from_points(&tri);
        aabb.min -= Vec3::splat(0.1);
        aabb.max += Vec3::splat(0.1);
        aabb.max[axis] = level;
        let got = clipped_area(&tri, &aabb);
        prop_assert!(close(got, expected, total, 1e-4), "got {got}, expected {expected}");
        // The split helper gives the same two parts.
        let plane = Plane::from_point_normal(Vec3::ZERO, { let mut n = Vec3::ZERO; n[axis] = 1.0; n });
        let plane = Plane { offset: level, ..plane };
        let (mut front, mut back) = (Vec::new(), Vec::new());
        split_convex_polygon_by_plane(&tri, &plane, &mut front, &mut back);
        prop_assert!(close(polygon_area(&back), expected, total, 1e-4));
        prop_assert!(close(polygon_area(&front), total * t1 * t2, total, 1e-4));
    }

    /// Splitting by any plane: both parts on their side, areas summing to the whole.
    #[test]
    fn split_parts_partition_the_polygon(poly in arb_polygon(), dir in (0.0f32..1.0, 0.0f32..1.0), offset in -1.5f32..1.5) {
        let plane = Plane::from_point_normal(Vec3::ZERO, common::unit(dir.0, dir.1));
        let plane = Plane { offset, ..plane };
        let (mut front, mut back) = (Vec::new(), Vec::new());
        split_convex_polygon_by_plane(&poly.vertices, &plane, &mut front, &mut back);
        prop_assert!(close(polygon_area(&front) + polygon_area(&back), poly.area, poly.area, 1e-4));
        prop_assert!(front.iter().all(|&p| plane.signed_distance(p) >= -1e-5));
        prop_assert!(back.iter().all(|&p| plane.signed_distance(p) <= 1e-5));
    }

    /// Two triangles sharing an edge, walked in opposite directions, are cut at bitwise
    /// identical points on that edge, so clipped meshes stay watertight.
    #[test]
    fn shared_edge_is_cut_at_identical_points(poly in arb_polygon(), aabb in arb_box()) {
        let v = &poly.vertices;
        prop_assume!(v.len() >= 4);
        let (a, b, c, d) = (v[0], v[1], v[2], v[3]);
        let mut scratch = ClipScratch::new();
        let first = clip_polygon_to_aabb(&[a, b, c], &aabb, &mut scratch).to_vec();
        let second = clip_polygon_to_aabb(&[c, d, a], &aabb, &mut scratch).to_vec();
        let on_shared_edge = |p: Vec3| {
            let t = (p - a).dot(c - a) / (c - a).length_squared();
            (a + (c - a) * t).distance(p) < 1e-6 && p.distance(a) > 1e-3 && p.distance(c) > 1e-3
        };
        for p in first.iter().copied().filter(|&p| on_shared_edge(p)) {
            prop_assert!(second.contains(&p), "{p:?} missing from {second:?}");
        }
    }

    /// Garbage in (any floats, any boxes) never panics and never yields NaN areas.
    #[test]
    fn arbitrary_input_never_panics_or_gives_nan(
        poly in prop::collection::vec(prop::array::uniform3(prop::num::f32::ANY), 0..8),
        min in prop::array::uniform3(prop::num::f32::ANY),
        max in prop::array::uniform3(prop::num::f32::ANY),
        normal in prop::array::uniform3(prop::num::f32::ANY),
    ) {
        let poly: Vec<Vec3> = poly.into_iter().map(Vec3::from_array).collect();
        let aabb = Aabb::new(Vec3::from_array(min), Vec3::from_array(max));
        let area = aabb.polygon_area_inside(&poly, Vec3::from_array(normal), &mut ClipScratch::new());
        prop_assert!(area.is_finite() && area >= 0.0);
    }
}

#[test]
fn polygon_touching_box_only_along_an_edge_is_empty() {
    // A unit square in z = 0 whose edge x = 1 lies on the face x = 1 of a box beyond it.
    let square = [
        vec3(0., 0., 0.),
        vec3(1., 0., 0.),
        vec3(1., 1., 0.),
        vec3(0., 1., 0.),
    ];
    let aabb = Aabb::new(vec3(1., -1., -1.), vec3(2., 2., 1.));
    assert!(clip_polygon_to_aabb(&square, &aabb, &mut ClipScratch::new()).is_empty());
}

#[test]
fn clipping_is_allocation_free_once_warm() {
    // The scratch capacity stops growing after the first call on the same sizes.
    let square = [
        vec3(-1., 0., -1.),
        vec3(1., 0., -1.),
        vec3(1., 0., 1.),
        vec3(-1., 0., 1.),
    ];
    let aabb = Aabb::cube(vec3(0.3, 0.0, 0.2), 0.5);
    let mut scratch = ClipScratch::new();
    let first = clip_polygon_to_aabb(&square, &aabb, &mut scratch).as_ptr();
    let again = clip_polygon_to_aabb(&square, &aabb, &mut scratch).as_ptr();
    assert_eq!(first, again, "the result buffer was reallocated");
    assert!((aabb.polygon_area_inside(&square, Vec3::Y, &mut scratch) - 1.0).abs() < 1e-6);
}

/// The property above only checks points that land on the shared edge; this case makes sure
/// some do: the diagonal of a quad crosses the box on two of its faces.
#[test]
fn shared_diagonal_crossing_the_box_is_cut_at_identical_points() {
    let (a, b, c, d) = (
        vec3(0.1, 0.3, 0.05),
        vec3(1.93, 0.2, 0.11),
        vec3(1.9, 1.7, 0.2),
        vec3(0.15, 1.8, 0.13),
    );
    let aabb = Aabb::new(vec3(0.55, 0.0, -1.0), vec3(1.45, 2.0, 1.0));
    let mut scratch = ClipScratch::new();
    let first = clip_polygon_to_aabb(&[a, b, c], &aabb, &mut scratch).to_vec();
    let second = clip_polygon_to_aabb(&[c, d, a], &aabb, &mut scratch).to_vec();
    let on_diagonal: Vec<Vec3> = first
        .iter()
        .copied()
        .filter(|&p| {
            let t = (p - a).dot(c - a) / (c - a).length_squared();
            (a + (c - a) * t).distance(p) < 1e-5
        })
        .collect();
    assert_eq!(
        on_diagonal.len(),
        2,
        "the diagonal enters and leaves the box: {first:?}"
    );
    for p in on_diagonal {
        assert!(second.contains(&p), "{p:?} missing from {second:?}");
    }
}
