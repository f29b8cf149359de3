//! The arrangement is the same on any number of threads: crowded faces (more candidate
//! partners than a wave holds), many cuts and T-junctions, and the bounds' errors.

use super::*;
use crate::polygon_area;
use glam::vec3;

fn on_threads<T: Send>(threads: usize, f: impl FnOnce() -> T + Send) -> T {
    rayon::ThreadPoolBuilder::new()
        .num_threads(threads)
        .build()
        .expect("a test pool")
        .install(f)
}

/// `n` unit squares tilted 30° about x, stacked 1e-4 apart along z: every pair's bounds
/// overlap (each face has up to n − 1 candidate partners), none meets.
fn tilted_stack(n: usize) -> Vec<Vec<Vec3>> {
    let (s, c) = 30f32.to_radians().sin_cos();
    (0..n)
        .map(|i| {
            let z = i as f32 * 1e-4;
            [(0.0, 0.0), (1.0, 0.0), (1.0, 1.0), (0.0, 1.0)]
                .iter()
                .map(|&(x, y)| vec3(x, y * c, z + y * s))
                .collect()
        })
        .collect()
}

/// A floor crossed by `n` thin walls at random places and angles (a fixed stream), which cut
/// the floor and each other: many cuts per face and many T-junctions.
fn crossed_floor(n: usize) -> Vec<Vec<Vec3>> {
    let mut next = test_stream::stream();
    let mut faces = vec![vec![
        vec3(0.0, 0.0, 0.0),
        vec3(10.0, 0.0, 0.0),
        vec3(10.0, 10.0, 0.0),
        vec3(0.0, 10.0, 0.0),
    ]];
    for _ in 0..n {
        let (x, y, a) = (next() * 10.0, next() * 10.0, next() * std::f32::consts::PI);
        let d = vec3(a.cos(), a.sin(), 0.0) * (0.5 + next() * 2.0);
        let p = vec3(x, y, -0.5);
        faces.push(vec![
            p,
            p + d,
            p + d + vec3(0.0, 0.0, 1.0),
            p + vec3(0.0, 0.0, 1.0),
        ]);
    }
    faces
}

#[test]
fn one_thread_four_and_sixty_four_give_the_same_pieces() {
    let options = ArrangementOptions::new(1e-5, 1e-5);
    for faces in [crossed_floor(600), tilted_stack(4_300)] {
        let solids = vec![None; faces.len()];
        // Everything but how long it took.
        let untimed = |a: Arrangement| Arrangement {
            seconds: ArrangementSeconds::default(),
            ..a
        };
        let one = on_threads(1, || split_polygons_at_intersections(&faces, &solids, &options)).map(untimed);
        for threads in [4, 64] {
            let many = on_threads(threads, || {
                split_polygons_at_intersections(&faces, &solids, &options)
            })
            .map(untimed);
            assert_eq!(one, many, "{threads} threads");
        }
    }
    // Against the input itself: every face is cut (the walls pierce the floor and each other)
    // and its pieces keep its area.
    let faces = crossed_floor(600);
    let crossed = on_threads(4, || {
        split_polygons_at_intersections(&faces, &vec![None; 601], &options)
    })
    .expect("within the bounds");
    assert!(crossed.counts.piercing > 600, "{:?}", crossed.counts);
    assert!(
        crossed.polygons.len() > 2 * faces.len(),
        "{} pieces",
        crossed.polygons.len()
    );
    for (source, face) in faces.iter().enumerate() {
        let pieces: f32 = crossed
            .polygons
            .iter()
            .zip(&crossed.source)
            .filter(|(_, s)| **s == source)
            .map(|(p, _)| polygon_area(p))
            .sum();
        let area = polygon_area(face);
        assert!(
            (pieces - area).abs() <= 1e-4 * area,
            "face {source}: {pieces} against {area}"
        );
    }
}

#[test]
fn one_thread_and_sixty_four_fail_on_the_same_bound() {
    let faces = tilted_stack(4_300);
    let solids = vec![None; faces.len()];
    let crossed = crossed_floor(600);
    let crossed_solids = vec![None; crossed.len()];
    let pairs = ArrangementOptions {
        max_pairs: 1_000_000,
        ..ArrangementOptions::new(1e-5, 1e-5)
    };
    let pieces = ArrangementOptions {
        max_pieces: 700,
        ..ArrangementOptions::new(1e-5, 1e-5)
    };
    let vertices = ArrangementOptions {
        max_vertices: 6_000,
        ..ArrangementOptions::new(1e-5, 1e-5)
    };
    for (faces, solids, options, expected) in [
        (
            &faces,
            &solids,
            pairs,
            ArrangementError::TooManyPairs { limit: 1_000_000 },
        ),
        (
            &crossed,
            &crossed_solids,
            pieces,
            ArrangementError::TooManyPieces { limit: 700 },
        ),
        (
            &crossed,
            &crossed_solids,
            vertices,
            ArrangementError::TooManyVertices { limit: 6_000 },
        ),
    ] {
        let one = on_threads(1, || split_polygons_at_intersections(faces, solids, &options));
        let many = on_threads(64, || split_polygons_at_intersections(faces, solids, &options));
        assert_eq!(one, Err(expected.clone()));
        assert_eq!(many, Err(expected));
    }
}
