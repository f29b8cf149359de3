//! The arrangement's bounds on overlapping copies: many mutually overlapping faces are
//! refused while they are cut, exact copies are dropped before any pair is examined, and
//! shifted copies meet the bound on pairs.

use super::tests::{TOL, box_faces, options};
use super::*;
use crate::polygon_area;
use glam::vec3;

#[test]
fn fifty_overlapping_triangles_end_fast_within_bounds() {
    // Copies of one triangle, each turned a little about its centre: every pair overlaps.
    let turned = |copies: usize| -> Vec<Vec<Vec3>> {
        (0..copies)
            .map(|i| {
                let angle = i as f32 * 0.013;
                (0..3)
                    .map(|k| {
                        let a = angle + k as f32 * std::f32::consts::TAU / 3.0;
                        vec3(a.cos(), 0.0, a.sin())
                    })
                    .collect()
            })
            .collect()
    };
    // Twelve cut each other into slivers, and only the first copy and the parts of later ones
    // outside all earlier ones survive.
    let split = split_polygons_at_intersections(&turned(12), &[], &options(TOL)).unwrap();
    assert_eq!(split.counts.coplanar_overlap, 12 * 11 / 2);
    let total: f32 = split.polygons.iter().map(|p| polygon_area(p)).sum();
    assert!(total < 2.0, "{total}");
    // Fifty cut each other into hundreds of thousands (11 s of work before the limit per
    // input polygon): refused while they are cut.
    let input = turned(50);
    assert!(matches!(
        split_polygons_at_intersections(&input, &[], &options(TOL)),
        Err(ArrangementError::TooManyPieces {
            limit: ArrangementOptions::MIN_PIECE_LIMIT
        })
    ));
    let tight = ArrangementOptions {
        max_pieces: 1000,
        ..options(TOL)
    };
    assert!(matches!(
        split_polygons_at_intersections(&input, &[], &tight),
        Err(ArrangementError::TooManyPieces { limit: 1000 })
    ));
}

#[test]
fn thousand_copies_of_a_small_mesh() {
    // Exact copies are dropped before any pair is examined; shifted copies pass the pair bound.
    let cube = box_faces(Vec3::ZERO, Vec3::ONE);
    let copies: Vec<Vec<Vec3>> = (0..1000).flat_map(|_| cube.clone()).collect();
    let split = split_polygons_at_intersections(&copies, &[], &options(TOL)).unwrap();
    assert_eq!(split.polygons.len(), 6);
    let shifted: Vec<Vec<Vec3>> = (0..1000)
        .flat_map(|i| {
            let offset = Vec3::splat(i as f32 * 1e-3);
            cube.iter()
                .map(move |f| f.iter().map(|p| *p + offset).collect::<Vec<Vec3>>())
        })
        .collect();
    let bounded = ArrangementOptions {
        max_pairs: 100_000,
        ..options(TOL)
    };
    assert!(matches!(
        split_polygons_at_intersections(&shifted, &[], &bounded),
        Err(ArrangementError::TooManyPairs { limit: 100_000 })
    ));
}
