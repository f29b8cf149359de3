//! Watertightness: a million random rays from inside closed meshes never escape (obvhs's own
//! triangle test lets about 1 in 200,000 through; ours must let none).

mod common;

use pm_trace::glam::{Vec2, Vec3};
use pm_trace::sampling::uniform_sphere;
use pm_trace::{Ray, RayKind, Rng, Scene, Surface, scenes};
use rayon::prelude::*;

/// Rays from uniform points in `[lo, hi]` in uniform directions; returns how many miss.
fn escapes(scene: &Scene, lo: Vec3, hi: Vec3, rays: u32, seed: u64) -> u32 {
    (0..rays / 10_000)
        .into_par_iter()
        .map(|chunk| {
            let mut rng = Rng::new(seed, chunk as u64);
            let mut missed = 0;
            for _ in 0..10_000 {
                let u = Vec3::new(rng.next_f32(), rng.next_f32(), rng.next_f32());
                let origin = lo + (hi - lo) * u;
                let direction = uniform_sphere(Vec2::new(rng.next_f32(), rng.next_f32()));
                if scene
                    .intersect(&Ray { origin, direction }, f32::INFINITY, RayKind::Other)
                    .is_none()
                {
                    missed += 1;
                }
            }
            missed
        })
        .sum()
}

#[test]
fn no_ray_escapes_a_closed_icosphere() {
    let (positions, faces) = common::icosphere(Vec3::new(0.1, 0.2, 0.3), 1.0, 3);
    let scene = Scene::builder()
        .mesh(&positions, &faces, Surface::diffuse(Vec3::splat(0.5)))
        .build()
        .unwrap();
    assert_eq!(scene.part_count(), 1280);
    let c = Vec3::new(0.1, 0.2, 0.3);
    assert_eq!(
        escapes(&scene, c - Vec3::splat(0.5), c + Vec3::splat(0.5), 1_000_000, 1),
        0
    );
}

#[test]
fn no_ray_escapes_either_closed_room() {
    let scene = scenes::build("lit-unlit-rooms").unwrap();
    let inset = Vec3::splat(1e-3);
    assert_eq!(escapes(&scene, inset, Vec3::ONE - inset, 1_000_000, 2), 0);
    let right = Vec3::new(1.02, 0.0, 0.0);
    assert_eq!(
        escapes(&scene, right + inset, right + Vec3::ONE - inset, 1_000_000, 3),
        0
    );
}

#[test]
fn no_ray_escapes_the_touching_rooms_with_t_junctions() {
    let scene = scenes::build("touching-rooms").unwrap();
    let inset = Vec3::splat(1e-3);
    assert_eq!(escapes(&scene, inset, Vec3::ONE - inset, 500_000, 4), 0);
    let right = Vec3::new(1.02, 0.0, 0.0);
    assert_eq!(
        escapes(&scene, right + inset, right + Vec3::ONE - inset, 500_000, 5),
        0
    );
}

#[test]
fn axis_aligned_ray_with_negative_zero_components_does_not_escape() {
    // Found by the test above: obvhs culled every node for a −0.0 direction component.
    let scene = scenes::build("lit-unlit-rooms").unwrap();
    let origin = Vec3::new(1.5628955, 0.3796295, 0.6155055);
    for direction in [
        Vec3::new(-0.0, -0.0, 1.0),
        Vec3::new(-0.0, 1.0, 0.0),
        Vec3::new(1.0, -0.0, -0.0),
    ] {
        let hit = scene.intersect(&Ray { origin, direction }, f32::INFINITY, RayKind::Other);
        assert!(hit.is_some(), "{direction:?} escaped");
    }
}
