//! Surfaces that come close as a whole, against hand-made cases: a tessellated panel over a
//! floor, flat or tilted, and raised lettering; each is outlined once where it stops coming
//! close, not along its own triangles.

use super::contact_tests::{floor_with_box, groups_at, mesh_of};
use super::*;
use glam::vec3;

/// A panel over the 3 × 3 floor's middle square (1..2 in x and z), tessellated into `n × n`
/// quads of two triangles each, facing down; its height at `(x, z)` is `height(x, z)`.
fn tessellated_panel(n: usize, height: impl Fn(f32, f32) -> f32) -> Vec<Vec<Vec3>> {
    let at = |i: usize, k: usize| {
        let (x, z) = (1.0 + i as f32 / n as f32, 1.0 + k as f32 / n as f32);
        vec3(x, height(x, z), z)
    };
    let mut triangles = Vec::new();
    for i in 0..n {
        for k in 0..n {
            // Wound to face down, towards the floor.
            triangles.push(vec![at(i, k), at(i + 1, k), at(i + 1, k + 1)]);
            triangles.push(vec![at(i, k), at(i + 1, k + 1), at(i, k + 1)]);
        }
    }
    triangles
}

/// For each point on the floor (y = 0, input polygon 0), the group of floor pieces it lies in,
/// where groups are floor pieces connected across edges no barrier covers, as a contact
/// partition joins them.
fn floor_groups_within_barriers(split: &Arrangement, points: &[Vec3]) -> Vec<usize> {
    let floor: Vec<Vec<Vec3>> = split
        .polygons
        .iter()
        .zip(&split.source)
        .filter(|&(_, &s)| s == 0)
        .map(|(p, _)| p.clone())
        .collect();
    let mesh = mesh_of(&floor);
    let barriers = BarrierSet::new(split.barriers.clone(), 1e-5);
    let positions = mesh.positions();
    groups_at(
        &mesh,
        points,
        |_| true,
        |he| {
            let (p, q) = (
                positions[mesh.origin(he).0 as usize],
                positions[mesh.target(he).0 as usize],
            );
            !barriers.covers_edge(p, q)
        },
    )
}

/// Every barrier lies on the border of the floor's middle square (the panel's outline), and
/// the floor under the panel is one group, apart from the floor around it.
fn assert_outlined_once(split: &Arrangement) {
    assert_outlined_once_around(split, 1.0, 2.0);
}

/// Every barrier lies on the border of the square from `lo` to `hi` in x and z (an outline
/// around the floor's middle square), and the floor under it is one group, apart from the
/// floor around it.
fn assert_outlined_once_around(split: &Arrangement, lo: f32, hi: f32) {
    let on_outline = |p: Vec3| {
        let d = (p.x - lo)
            .abs()
            .min((p.x - hi).abs())
            .min((p.z - lo).abs())
            .min((p.z - hi).abs());
        d <= 1e-4 && p.y.abs() <= 1e-4
    };
    for [a, b] in &split.barriers {
        assert!(
            on_outline(*a) && on_outline(*b) && on_outline((*a + *b) * 0.5),
            "barrier {a} {b}"
        );
    }
    let under = [
        vec3(1.1, 0.0, 1.1),
        vec3(1.9, 0.0, 1.1),
        vec3(1.5, 0.0, 1.5),
        vec3(1.1, 0.0, 1.9),
        vec3(1.9, 0.0, 1.9),
    ];
    let mut groups = floor_groups_within_barriers(split, &under);
    groups.dedup();
    assert_eq!(groups.len(), 1, "the floor under the panel is one group");
    let around = floor_groups_within_barriers(split, &[vec3(0.5, 0.0, 0.5), vec3(2.5, 0.0, 2.5)]);
    assert_eq!(around[0], around[1]);
    assert_ne!(around[0], groups[0], "the floor under the panel is cut off");
}

/// A tessellated panel lying flat 1 mm over the floor, facing it (within a 1 cm gap), and
/// resting on it: the floor is cut along the panel's outline only, not along the edges between
/// its triangles, which lie inside the contact (before, each triangle's footprint was a piece
/// of its own behind barriers: 32 maps under a 4 × 4 panel instead of one).
#[test]
fn a_tessellated_panel_facing_the_floor_is_outlined_not_fragmented() {
    for height in [0.001, 0.0] {
        let mut input = vec![floor_with_box().swap_remove(0)];
        input.extend(tessellated_panel(4, |_, _| height));
        let split = split_polygons_at_intersections(&input, &[], &ArrangementOptions::new(1e-5, 0.01))
            .expect("within bounds");
        assert!(split.counts.meetings() > 0, "{:?}", split.counts);
        assert_outlined_once(&split);
    }
}

/// A tessellated panel tilted 1.2° over the floor (2 mm above it at x = 1, 23 mm at x = 2),
/// all within a 3 cm gap: the near-contact outlines its footprint, not each triangle's.
#[test]
fn a_tilted_tessellated_panel_near_the_floor_is_outlined_not_fragmented() {
    let mut input = vec![floor_with_box().swap_remove(0)];
    input.extend(tessellated_panel(4, |x, _| 0.002 + (x - 1.0) * 0.021));
    let split = split_polygons_at_intersections(&input, &[], &ArrangementOptions::new(1e-5, 0.03))
        .expect("within bounds");
    assert!(split.counts.near_contact > 0, "{:?}", split.counts);
    assert_outlined_once(&split);
}

/// A block of raised lettering over the floor's middle square: a cap at `height` tessellated
/// into `n × n` quads (facing up, as a solid's top), and four walls of `n` quads each that run
/// down from the cap's border to `foot` above the floor, flaring out by `draft` at the foot.
/// Cap and walls share their vertices bit for bit; the walls' feet are open, as exports leave
/// them.
fn raised_block(n: usize, height: f32, foot: f32, draft: f32) -> Vec<Vec<Vec3>> {
    let mut polygons: Vec<Vec<Vec3>> = tessellated_panel(n, |_, _| height)
        .into_iter()
        .map(|mut t| {
            t.reverse();
            t
        })
        .collect();
    let centre = vec3(1.5, 0.0, 1.5);
    let border = |t: f32, side: usize| match side {
        0 => vec3(1.0 + t, height, 1.0),
        1 => vec3(2.0, height, 1.0 + t),
        2 => vec3(2.0 - t, height, 2.0),
        _ => vec3(1.0, height, 2.0 - t),
    };
    for side in 0..4 {
        let at = |k: usize| {
            // The cap's own vertices, computed as `tessellated_panel` computes them.
            let p = border(k as f32 / n as f32, side);
            let snap = |x: f32| 1.0 + ((x - 1.0) * n as f32).round() / n as f32;
            vec3(snap(p.x), height, snap(p.z))
        };
        for k in 0..n {
            let (a, b) = (at(k), at(k + 1));
            // Flared away from the square's middle, corners along both sides.
            let flare = |x: f32| (x - 1.5).signum() * draft * ((x - 1.5).abs() >= 0.5) as u8 as f32;
            let down = |p: Vec3| vec3(p.x + flare(p.x), foot, p.z + flare(p.z));
            let mut quad = [a, b, down(b), down(a)];
            let normal = (quad[1] - quad[0]).cross(quad[2] - quad[0]);
            if normal.dot(quad[0] - centre) < 0.0 {
                quad.reverse();
            }
            polygons.push(vec![quad[0], quad[1], quad[2]]);
            polygons.push(vec![quad[0], quad[2], quad[3]]);
        }
    }
    polygons
}

/// Raised lettering or a knob on a panel: a tessellated cap 3 mm up, its walls down to the
/// floor (resting, or hovering 0.5 mm), upright or flaring out by 0.5 mm. The floor is cut
/// once, along the walls' feet, not also along the cap's border (before, the cap's border and
/// the feet each cut the floor, leaving a sliver piece between them behind barriers).
#[test]
fn raised_lettering_is_outlined_along_its_foot_only() {
    for (foot, draft) in [(0.0, 0.0005), (0.0005, 0.0005), (0.0005, 0.0)] {
        let mut input = vec![floor_with_box().swap_remove(0)];
        input.extend(raised_block(4, 0.003, foot, draft));
        let split = split_polygons_at_intersections(&input, &[], &ArrangementOptions::new(1e-5, 0.01))
            .expect("within bounds");
        assert!(split.counts.meetings() > 0, "{:?}", split.counts);
        println!("foot {foot}, draft {draft}"); // names the failing case
        assert_outlined_once_around(&split, 1.0 - draft, 2.0 + draft);
    }
}
