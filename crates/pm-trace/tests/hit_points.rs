//! Hit points at the ends of the size range: a ray's hit on a triangle lies where the ray
//! meets the triangle's plane, for a thin sliver as for a triangle of edges near the largest
//! the scene builder keeps (larger ones, whose area leaves f32, are dropped as degenerate).

use pm_trace::glam::Vec3;
use pm_trace::{Camera, Hit, PointLight, Ray, RayKind, Scene, Surface};

fn one_triangle(corners: [Vec3; 3]) -> Scene {
    Scene::builder()
        .mesh(&corners, &[[0, 1, 2]], Surface::diffuse(Vec3::splat(0.5)))
        .light(PointLight::new(Vec3::new(0.0, 1.0, 0.0), Vec3::ONE))
        .camera(Camera::new(Vec3::new(0.0, 1.0, 0.0), Vec3::ZERO, Vec3::Z, 1.0))
        .build()
        .unwrap()
}

#[test]
fn hits_lie_where_the_ray_meets_the_plane_for_huge_and_sliver_triangles() {
    // Edges of 2·10⁹ m: |e₁ × e₂|² is about 10³⁷, near the top of f32.
    let big = 1e9f32;
    let huge = one_triangle([
        Vec3::new(-big, 0.0, -big),
        Vec3::new(0.0, 0.0, big),
        Vec3::new(big, 0.0, -big),
    ]);
    // A sliver 2 m long and 10 µm wide, its corners 1.4° sharp at the ends.
    let sliver = one_triangle([
        Vec3::new(-1.0, 0.0, 0.0),
        Vec3::new(0.0, 0.0, 1e-5),
        Vec3::new(1.0, 0.0, 0.0),
    ]);
    for (scene, target, height) in [
        (&huge, Vec3::new(3.0, 0.0, 2.0), 1e4f32),
        (&sliver, Vec3::new(0.25, 0.0, 2e-6), 1.0),
    ] {
        let origin = Vec3::new(0.3, height, -0.2);
        let ray = Ray::new(origin, (target - origin).normalize());
        let hit = scene.intersect(&ray, f32::INFINITY, RayKind::Other).unwrap();
        assert!(
            hit.position.y.abs() <= hit.error(),
            "{hit:?} is off the plane by more than its bound"
        );
        let along = hit.position.distance(target);
        assert!(along < 1e-5 * height, "hit {} against {target}", hit.position);
    }
}

/// Half the top of the sliver panel case's kick plate, alone in a scene: 1.98 m long and 1 cm
/// deep, 0.29° sharp at one end (condition about 200).
fn kick_plate_sliver() -> Scene {
    one_triangle([
        Vec3::new(-0.99, 0.0484, 0.5),
        Vec3::new(0.99, 0.0484, 0.51),
        Vec3::new(0.99, 0.0484, 0.5),
    ])
}

/// Calls `f` with each hit on `sliver` of 200,000 rays from above aimed at random points of it
/// (100,191 hit), and the stream the rays were drawn from; returns the number of hits.
fn for_each_sliver_hit(sliver: &Scene, mut f: impl FnMut(&Hit, &mut dyn FnMut() -> f32)) -> u32 {
    let mut rng = pm_trace::Rng::new(5, 0);
    let mut u = || rng.next_f32();
    let mut hits = 0;
    for _ in 0..200_000 {
        let target = Vec3::new(-0.99 + 1.98 * u(), 0.0484, 0.5 + 0.01 * u());
        let origin = Vec3::new(-1.5 + 3.0 * u(), 0.0484 + 1.0 * u().max(1e-3), -1.0 + 3.0 * u());
        let ray = Ray::new(origin, (target - origin).normalize());
        if let Some(hit) = sliver.intersect(&ray, f32::INFINITY, RayKind::Other) {
            hits += 1;
            f(&hit, &mut u);
        }
    }
    hits
}

/// A shadow ray leaving a sliver never finds the sliver itself: with the triangle alone in the
/// scene, nothing may block a light above it. (The triangle test's distance errs by the
/// triangle's condition `L² / 2A` times its corners' rounding, so before a ray leaving a
/// triangle skipped that triangle, 36 of these 100,191 shadow rays were blocked by their own
/// surface, as `tests/split_visibility.rs` found on its sliver panel.)
#[test]
fn a_shadow_ray_never_meets_its_own_sliver() {
    let sliver = kick_plate_sliver();
    let mut shadowed = 0;
    let hits = for_each_sliver_hit(&sliver, |hit, u| {
        let lamp = Vec3::new(-1.0 + 2.0 * u(), 0.1 + u(), -1.0 + 2.0 * u());
        shadowed += sliver.occluded_from(hit, lamp) as u32;
    });
    assert!(hits > 50_000, "only {hits} hits");
    assert_eq!(
        shadowed, 0,
        "{shadowed} of {hits} shadow rays met their own sliver"
    );
}

/// A ray spawned off a sliver never meets the sliver again when it is searched as leaving it
/// (`Scene::intersect_from`): alone in the scene, the sliver leaves nothing to hit. (Searched
/// as any ray, `Scene::intersect`, 29 of these 100,191 spawned rays met their own sliver, by
/// the triangle test's rounding: the path would lose a bounce there. The count is printed.)
#[test]
fn a_spawned_ray_never_meets_its_own_sliver() {
    let sliver = kick_plate_sliver();
    let (mut again_as_any, mut again_leaving) = (0, 0);
    let hits = for_each_sliver_hit(&sliver, |hit, u| {
        // Leaving into the side the ray came from.
        let d = Vec3::new(u() - 0.5, u(), u() - 0.5).normalize() * Vec3::new(1.0, hit.normal.y.signum(), 1.0);
        let spawned = sliver.spawn_ray(hit, d);
        again_as_any += sliver
            .intersect(&spawned, f32::INFINITY, RayKind::Other)
            .is_some() as u32;
        again_leaving += sliver
            .intersect_from(hit, &spawned, f32::INFINITY, RayKind::Other)
            .is_some() as u32;
    });
    println!("{again_as_any} of {hits} spawned rays met their own sliver when searched as any ray");
    assert!(hits > 50_000, "only {hits} hits");
    assert_eq!(
        again_leaving, 0,
        "{again_leaving} of {hits} spawned rays met their own sliver"
    );
}
