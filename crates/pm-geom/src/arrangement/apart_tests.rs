//! Faces side by side in planes a few degrees apart, each within the tolerance of the other's
//! plane over a stretch (letters on one panel, one of them a sliver whose plane rounding tilts):
//! they do not meet, however their sections line up along the planes' common line.

use super::*;
use glam::vec3;

/// Face B in a plane 5° from face A's, ending on the planes' common line (the x axis); face A
/// beside it in z = 0, from `start` to 0.1 mm past the line, so A lies within the 10 µm
/// tolerance of B's plane and B's end edge lies in A's plane.
fn side_by_side(start: f32) -> Vec<Vec<Vec3>> {
    let slope = 5f32.to_radians().tan();
    let b = vec![
        vec3(0.0, 0.0, 0.0),
        vec3(0.0, -0.001, -0.001 * slope),
        vec3(0.001, -0.001, -0.001 * slope),
        vec3(0.001, 0.0, 0.0),
    ];
    let a = vec![
        vec3(0.0, start, 0.0),
        vec3(0.001, start, 0.0),
        vec3(0.001, 0.0001, 0.0),
        vec3(0.0, 0.0001, 0.0),
    ];
    vec![a, b]
}

#[test]
fn faces_side_by_side_in_planes_a_few_degrees_apart_do_not_meet() {
    // 50 µm apart across the line: no meeting, no cut, no barrier (with a 1 mm gap, so that
    // the pair is looked at).
    let split =
        split_polygons_at_intersections(&side_by_side(0.00005), &[], &ArrangementOptions::new(1e-5, 1e-3))
            .expect("within bounds");
    assert_eq!(split.counts.meetings(), 0, "{:?}", split.counts);
    assert_eq!(split.polygons.len(), 2);
    assert!(split.barriers.is_empty(), "{:?}", split.barriers);
}

#[test]
fn faces_reaching_across_the_common_line_still_meet() {
    // The control: A reaching 0.1 mm to the other side of the line overlaps B's end there (A
    // lies in B's plane within the tolerance), so they still meet.
    let split =
        split_polygons_at_intersections(&side_by_side(-0.0001), &[], &ArrangementOptions::new(1e-5, 1e-5))
            .expect("within bounds");
    assert!(split.counts.meetings() > 0, "{:?}", split.counts);
}
