//! PolygonSet: overlap queries against a brute-force scan, degenerate pushes, queries
//! before and after indexing, and thread safety.

use pm_geom::glam::{Vec3, vec3};
use pm_geom::{Aabb, PolygonSet};
use proptest::prelude::*;

fn brute_force(polygons: &[Vec<Vec3>], query: &Aabb) -> Vec<u32> {
    (0..polygons.len() as u32)
        .filter(|&i| Aabb::from_points(&polygons[i as usize]).overlaps(query))
        .collect()
}

fn query(set: &PolygonSet, aabb: &Aabb) -> Vec<u32> {
    let mut found = Vec::new();
    set.for_each_overlapping(aabb, |i| found.push(i));
    found.sort_unstable();
    found
}

fn arb_triangle() -> impl Strategy<Value = Vec<Vec3>> {
    (
        prop::array::uniform3(-5.0f32..5.0),
        prop::array::uniform3(prop::array::uniform3(-0.5f32..0.5)),
    )
        .prop_map(|(c, offsets)| {
            offsets
                .iter()
                .map(|&o| Vec3::from_array(c) + Vec3::from_array(o))
                .collect()
        })
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(64))]

    /// Every polygon whose bounds overlap the query is reported exactly once, and no other,
    /// whether or not the index is built or covers every polygon, in sets small enough to be
    /// scanned and large enough to be indexed.
    #[test]
    fn overlap_queries_match_brute_force(
        triangles in prop_oneof![
            prop::collection::vec(arb_triangle(), 0..7),
            prop::collection::vec(arb_triangle(), 0..300),
        ],
        late in prop::collection::vec(arb_triangle(), 0..10),
        queries in prop::collection::vec((prop::array::uniform3(-6.0f32..6.0), 0.0f32..3.0), 1..20),
    ) {
        let mut set = PolygonSet::new();
        let mut kept = Vec::new();
        for t in &triangles {
            if let Some(i) = set.push(t) {
                prop_assert_eq!(i as usize, kept.len());
                kept.push(t.clone());
            }
        }
        let boxes: Vec<Aabb> = queries.iter().map(|&(c, h)| Aabb::cube(Vec3::from_array(c), h)).collect();
        for b in &boxes {
            prop_assert_eq!(query(&set, b), brute_force(&kept, b));
        }
        set.build_index();
        for t in &late {
            if set.push(t).is_some() {
                kept.push(t.clone());
            }
        }
        for b in &boxes {
            prop_assert_eq!(query(&set, b), brute_force(&kept, b));
        }
        for (i, p) in kept.iter().enumerate() {
            prop_assert_eq!(set.polygon(i as u32), &p[..]);
        }
    }
}

#[test]
fn degenerate_polygons_are_refused() {
    let mut set = PolygonSet::new();
    assert_eq!(set.push(&[Vec3::ZERO, Vec3::X]), None);
    assert_eq!(set.push(&[Vec3::ZERO, Vec3::X, 2.0 * Vec3::X]), None);
    assert_eq!(set.push(&[Vec3::ZERO, Vec3::X, vec3(0., f32::NAN, 0.)]), None);
    assert_eq!(
        set.push(&[Vec3::ZERO, Vec3::X, vec3(0., f32::INFINITY, 0.)]),
        None
    );
    assert!(set.is_empty());
    assert_eq!(set.push(&[Vec3::ZERO, Vec3::X, Vec3::Z]), Some(0));
    assert_eq!(set.normal(0), -Vec3::Y);
    assert!((set.area(0) - 0.5).abs() < 1e-7);
    assert_eq!(set.bounds(), Aabb::new(Vec3::ZERO, vec3(1., 0., 1.)));
}

#[test]
fn unit_grid_query_finds_the_touched_cells() {
    // A 20 × 20 grid of unit floor quads; a cube of half-size 1.5 around a cell centre
    // overlaps the 4 × 4 quads whose bounds reach within it.
    let mut set = PolygonSet::new();
    for i in 0..20 {
        for j in 0..20 {
            let (x, z) = (i as f32, j as f32);
            set.push(&[
                vec3(x, 0., z),
                vec3(x, 0., z + 1.),
                vec3(x + 1., 0., z + 1.),
                vec3(x + 1., 0., z),
            ])
            .unwrap();
        }
    }
    set.build_index();
    assert!((set.total_area() - 400.0).abs() < 1e-3);
    let found = query(&set, &Aabb::cube(vec3(10.5, 0.0, 10.5), 1.4));
    assert_eq!(found.len(), 9);
    let found = query(&set, &Aabb::cube(vec3(10.5, 0.0, 10.5), 1.5));
    assert_eq!(found.len(), 25, "closed boxes: touching bounds count");
    assert!(query(&set, &Aabb::cube(vec3(10.5, 2.0, 10.5), 1.5)).is_empty());
}

#[test]
fn polygon_set_is_send_and_sync() {
    fn shareable<T: Send + Sync>() {}
    shareable::<PolygonSet>();
}
