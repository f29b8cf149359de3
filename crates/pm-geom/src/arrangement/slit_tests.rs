//! Slits against hand-made cases: a long wall that stops just short of a face's border closes
//! the slit, a small block near the border of a small face does not cut it across.

use super::*;
use glam::vec3;

/// The four sides of a box over `lo..hi` in x and z, from y = 0 to `height` (open top and
/// bottom, as the walls of a solid standing on a floor).
fn box_sides(lo: Vec3, hi: Vec3, height: f32) -> Vec<Vec<Vec3>> {
    let at = |x: f32, y: f32, z: f32| vec3(x, y, z);
    vec![
        vec![
            at(lo.x, 0.0, lo.z),
            at(lo.x, 0.0, hi.z),
            at(lo.x, height, hi.z),
            at(lo.x, height, lo.z),
        ],
        vec![
            at(hi.x, 0.0, lo.z),
            at(hi.x, height, lo.z),
            at(hi.x, height, hi.z),
            at(hi.x, 0.0, hi.z),
        ],
        vec![
            at(lo.x, 0.0, lo.z),
            at(lo.x, height, lo.z),
            at(hi.x, height, lo.z),
            at(hi.x, 0.0, lo.z),
        ],
        vec![
            at(lo.x, 0.0, hi.z),
            at(hi.x, 0.0, hi.z),
            at(hi.x, height, hi.z),
            at(lo.x, height, hi.z),
        ],
    ]
}

/// A square face `size` wide in y = 0, facing up.
fn square(size: f32) -> Vec<Vec3> {
    vec![
        vec3(0.0, 0.0, 0.0),
        vec3(0.0, 0.0, size),
        vec3(size, 0.0, size),
        vec3(size, 0.0, 0.0),
    ]
}

/// Whether some barrier runs along x = `x` on the floor through the point at `z`.
fn barrier_through(split: &Arrangement, x: f32, z: f32) -> bool {
    split.barriers.iter().any(|[a, b]| {
        (a.x - x).abs() < 1e-5 && (b.x - x).abs() < 1e-5 && a.z.min(b.z) <= z && a.z.max(b.z) >= z
    })
}

/// A 1 m wall, 1 cm thick, standing on a floor from its far border to 5 mm short of the near
/// one, with a 1 cm gap: the slit under the wall's end is narrower than the gap and than a tenth
/// of the wall, so the wall's footprint runs on to the border on both sides and the floor's
/// halves are cut apart.
#[test]
fn a_long_wall_stopping_short_of_the_border_closes_the_slit() {
    let mut input = vec![square(1.0)];
    input.extend(box_sides(vec3(0.45, 0.0, 0.005), vec3(0.46, 0.0, 1.0), 0.5));
    let split = split_polygons_at_intersections(&input, &[], &ArrangementOptions::new(1e-5, 0.01))
        .expect("within bounds");
    for x in [0.45, 0.46] {
        assert!(
            barrier_through(&split, x, 0.002),
            "no barrier closes the slit at x = {x}"
        );
    }
}

/// A 3 mm block standing on a 2 cm button, 5 mm from its border, with a 1.6 cm gap (a letter
/// or a knob on an appliance's panel): its footprint is outlined, and no barrier runs from it
/// across the button (before, each side of the footprint ran on to the border both ways).
#[test]
fn a_small_block_near_the_border_is_outlined_not_run_across_the_face() {
    let mut input = vec![square(0.02)];
    input.extend(box_sides(vec3(0.005, 0.0, 0.005), vec3(0.008, 0.0, 0.008), 0.001));
    let split = split_polygons_at_intersections(&input, &[], &ArrangementOptions::new(1e-6, 0.016))
        .expect("within bounds");
    assert!(!split.barriers.is_empty());
    for [a, b] in &split.barriers {
        for p in [a, b] {
            let inside = |v: f32| (0.005 - 1e-5..=0.008 + 1e-5).contains(&v);
            assert!(
                inside(p.x) && inside(p.z),
                "barrier {a} {b} leaves the block's footprint"
            );
        }
    }
}
