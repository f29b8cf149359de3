//! The piece index against hand-made cuts and an f64 brute force.

use super::*;

fn part(p: u32) -> PartSurface {
    PartSurface {
        part: PartId(p),
        surface: 0,
    }
}

/// A unit square in z = 0 cut into a left and a right half: points are located in their
/// half, edge points in the larger (the first listed of equals), points
/// just off within the tolerance in the nearest, and points beyond it nowhere.
#[test]
fn locates_points_among_pieces() {
    let (a, b, c, d, e, f) = (
        Vec3::new(0.0, 0.0, 0.0),
        Vec3::new(0.5, 0.0, 0.0),
        Vec3::new(0.5, 1.0, 0.0),
        Vec3::new(0.0, 1.0, 0.0),
        Vec3::new(1.0, 0.0, 0.0),
        Vec3::new(1.0, 1.0, 0.0),
    );
    let mut index = PieceIndex::new(1e-3);
    let id = index
        .push(
            Vec3::Z,
            Coverage::Dropped,
            [(&[a, b, c, d][..], part(1)), (&[b, e, f, c][..], part(2))],
        )
        .unwrap();
    assert_eq!(id.0, PIECES);
    let list = id.0 & !PIECES;
    assert_eq!(index.locate(list, Vec3::new(0.2, 0.7, 0.0)), Some(part(1)));
    assert_eq!(index.locate(list, Vec3::new(0.8, 0.1, 0.0)), Some(part(2)));
    assert_eq!(index.locate(list, Vec3::new(0.5, 0.5, 0.0)), Some(part(1)));
    assert_eq!(index.locate(list, Vec3::new(1.0005, 0.5, 0.0)), Some(part(2)));
    assert_eq!(index.locate(list, Vec3::new(1.01, 0.5, 0.0)), None);
    // Pieces that cover their face: a point rounded off them is on the nearest.
    let whole = index
        .push(
            Vec3::Z,
            Coverage::Whole,
            [(&[a, b, c][..], part(1)), (&[b, e, f][..], part(2))],
        )
        .unwrap()
        .0
        & !PIECES;
    assert_eq!(index.locate(whole, Vec3::new(1.01, 0.5, 0.0)), Some(part(2)));
    assert_eq!(index.locate(whole, Vec3::new(-3.0, 0.9, 0.0)), Some(part(1)));
}

/// A fan triangle of three corners on one line (a piece outline with a T-junction vertex)
/// contains no point off that line, however rounding tilts its own normal.
#[test]
fn collinear_fan_triangles_contain_nothing() {
    let mut index = PieceIndex::new(1e-6);
    let line = [
        Vec3::new(3.42, 2.44, -1.83),
        Vec3::new(3.42, 2.44, -1.79),
        Vec3::new(3.42, 2.44, -1.74),
    ];
    let square = [
        Vec3::new(3.0, 2.44, -1.0),
        Vec3::new(3.0, 2.44, -0.9),
        Vec3::new(2.9, 2.44, -0.9),
    ];
    let list = index
        .push(
            Vec3::Y,
            Coverage::Dropped,
            [(&line[..], part(1)), (&square[..], part(2))],
        )
        .unwrap()
        .0
        & !PIECES;
    assert_eq!(index.locate(list, Vec3::new(3.0, 2.44, 0.5)), None);
    assert_eq!(index.locate(list, Vec3::new(2.97, 2.44, -0.92)), Some(part(2)));
}

/// A rectangle's outline with T-junction corners along its edges keeps four edges, and
/// the corners' order (either winding) does not matter.
#[test]
fn corners_along_an_edge_are_dropped() {
    let mut outline = vec![Vec3::new(0.0, 0.0, 5.0)];
    outline.extend((1..10).map(|i| Vec3::new(0.1 * i as f32, 0.0, 5.0)));
    outline.extend([Vec3::new(1.0, 0.0, 5.0), Vec3::new(1.0, 0.5, 5.0)]);
    outline.extend((0..7).map(|i| Vec3::new(1.0 - 0.13 * i as f32, 0.5, 5.0)));
    outline.push(Vec3::new(0.0, 0.5, 5.0));
    for reversed in [false, true] {
        let mut corners = outline.clone();
        if reversed {
            corners.reverse();
        }
        let mut index = PieceIndex::new(1e-5);
        let list = index
            .push(Vec3::Z, Coverage::Dropped, [(&corners[..], part(3))])
            .unwrap()
            .0
            & !PIECES;
        assert_eq!(index.edge_lines(), 4);
        assert_eq!(index.locate(list, Vec3::new(0.55, 0.25, 5.0)), Some(part(3)));
        assert_eq!(index.locate(list, Vec3::new(0.55, 0.6, 5.0)), None);
    }
}

proptest::proptest! {
    /// A rectangle cut into strips (each outline with T-junction corners along its long
    /// edges, wound either way, listed in any order), a metre wide 10 km out, a micrometre
    /// wide at the origin and 10 km wide 10⁴ km out: a point clear of every cut by four
    /// tolerances is located in its strip, against an f64 brute force.
    #[test]
    fn points_are_located_in_their_strip(
        cuts in proptest::collection::btree_set(1u32..99, 1..8),
        junctions in proptest::collection::vec(0.0f64..1.0, 0..12),
        reversed in proptest::collection::vec(proptest::bool::ANY, 9),
        queries in proptest::collection::vec((0.0f64..1.0, 0.0f64..1.0), 40),
        place in 0usize..3,
    ) {
        // A room-sized face 10 km out, a micrometre-sized one at the origin, and a face 10 km
        // wide 10⁴ km out (where an f32 step is a metre), each with the tolerance the
        // partition would take there: at least eight float steps of its coordinates.
        let (origin, scale) = [
            ([1.0e4f64, -2.0e3, 300.0], 1.0f64),
            ([0.0, 0.0, 0.0], 1e-6),
            ([1.0e7, -6.0e6, 3.0e6], 2.5e3),
        ][place];
        let (width, height) = (4.0 * scale, 1.5 * scale);
        let at = |x: f64, y: f64| Vec3::new((origin[0] + x * width) as f32, (origin[1] + y * height) as f32, origin[2] as f32);
        let mut bounds: Vec<f64> = vec![0.0];
        bounds.extend(cuts.iter().map(|&c| f64::from(c) / 100.0));
        bounds.push(1.0);
        let outlines: Vec<Vec<Vec3>> = bounds
            .windows(2)
            .enumerate()
            .map(|(i, w)| {
                let (x0, x1) = (w[0], w[1]);
                let mut along: Vec<f64> = junctions.iter().map(|t| x0 + t * (x1 - x0)).collect();
                along.sort_by(f64::total_cmp);
                let mut outline = vec![at(x0, 0.0)];
                outline.extend(along.iter().map(|&x| at(x, 0.0)));
                outline.push(at(x1, 0.0));
                outline.push(at(x1, 1.0));
                outline.extend(along.iter().rev().map(|&x| at(x, 1.0)));
                outline.push(at(x0, 1.0));
                if reversed[i % reversed.len()] {
                    outline.reverse();
                }
                outline
            })
            .collect();
        let largest = origin.iter().fold(0.0f64, |m, c| m.max(c.abs())) + width;
        let tolerance = (2.5e-4 * scale).max(8.0 * largest * f64::from(f32::EPSILON)) as f32;
        let mut index = PieceIndex::new(tolerance);
        let list = index
            .push(Vec3::Z, Coverage::Whole, outlines.iter().enumerate().map(|(i, o)| (&o[..], part(i as u32))))
            .unwrap()
            .0
            & !PIECES;
        for (qx, qy) in queries {
            let clear = bounds.iter().all(|&b| ((qx - b) * width).abs() > 4.0 * f64::from(tolerance));
            if !clear {
                continue;
            }
            let strip = bounds.windows(2).position(|w| w[0] < qx && qx < w[1]).unwrap();
            proptest::prop_assert_eq!(index.locate(list, at(qx, qy)), Some(part(strip as u32)));
        }
    }
}
