//! The contact split's rays meet the faces as given and take the part of the piece the point
//! lies in. Checked against brute force on the built-in scenes the split cuts: every hit of
//! random rays lies on the polygon of the part it reports (distance computed from the
//! polygon's edges, not through the piece index), and at the same distance as the hit in the
//! scene as given (the duplicated floor of `solid-rooms-double-floor` included, whose hidden
//! copy the split drops: a ray meeting it passes on to the copy kept at the same distance).

use pm_trace::glam::Vec3;
use pm_trace::{Contact, Partitioner, Ray, RayKind, Rng, Scene, scenes};

/// The distance from `p` to the planar polygon `poly` (Newell normal; edges without length
/// skipped): the distance off its plane, or beyond its farthest edge line when outside.
/// The split's pieces are convex, so inside every edge line is inside the polygon.
fn distance_to_polygon(poly: &[Vec3], p: Vec3) -> f32 {
    let n = (0..poly.len())
        .map(|j| poly[j].cross(poly[(j + 1) % poly.len()]))
        .sum::<Vec3>()
        .normalize();
    let mut out = n.dot(p - poly[0]).abs();
    for j in 0..poly.len() {
        let (a, b) = (poly[j], poly[(j + 1) % poly.len()]);
        if let Some(inward) = n.cross(b - a).try_normalize() {
            out = out.max(-inward.dot(p - a));
        }
    }
    out
}

/// Random rays from inside the scene's bounds.
fn random_rays(scene: &Scene, count: usize, seed: u64) -> Vec<Ray> {
    let b = scene.bounds();
    let mut rng = Rng::new(seed, 0);
    (0..count)
        .map(|_| {
            let o = b.min + (b.max - b.min) * Vec3::new(rng.next_f32(), rng.next_f32(), rng.next_f32());
            let d = Vec3::new(rng.next_f32() - 0.5, rng.next_f32() - 0.5, rng.next_f32() - 0.5);
            Ray::new(o, d.try_normalize().unwrap_or(Vec3::Y))
        })
        .collect()
}

#[test]
fn split_hits_lie_on_their_parts_polygon_where_the_scene_as_given_is_hit() {
    for name in [
        "solid-rooms-pierce",
        "solid-rooms-sunk-box",
        "touching-rooms",
        "solid-rooms-tee",
    ] {
        let given = scenes::build(name).unwrap();
        let split = Contact::default().partition(given.clone()).unwrap();
        assert!(
            split.scene().part_count() > given.part_count(),
            "{name}: the split cut nothing, so this checks nothing"
        );
        let tolerance = Contact::default().tolerance(&given);
        let mut hits = 0;
        for ray in random_rays(&given, 20_000, 7) {
            let a = given.intersect(&ray, f32::INFINITY, RayKind::Other);
            let b = split.scene().intersect(&ray, f32::INFINITY, RayKind::Other);
            let (Some(a), Some(b)) = (a, b) else {
                assert_eq!(a.is_some(), b.is_some(), "{name}: {ray:?} hit in one scene only");
                continue;
            };
            hits += 1;
            assert_eq!(
                a.t, b.t,
                "{name}: {ray:?} met the split scene at another distance"
            );
            let mut distance = f32::INFINITY;
            split.scene().for_each_part_polygon(b.part, |poly| {
                distance = distance.min(distance_to_polygon(poly, b.position));
            });
            assert!(
                distance <= tolerance,
                "{name}: {ray:?} hit {:?} at {}, {distance} m off its part {:?}",
                b.position,
                b.t,
                b.part
            );
            assert_eq!(
                split.source_face(b.part),
                given.source_face(a.part),
                "{name}: {ray:?} hit a piece of another face"
            );
        }
        assert!(hits > 10_000, "{name}: only {hits} of the rays hit");
    }
}
