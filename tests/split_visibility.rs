//! The contact split decides maps, never visibility (issue 33): a ray against the split scene
//! hits what it hits against the scene as given — at the same distance, on a piece lying in
//! an original face with the same surface and side — on random contact configurations (boxes
//! resting on, sunk into or piercing a slab, coplanar faces, unwelded triangle soups, a
//! sliver panel touched near its sharp corner) and on the obvhs kitchen when it has been
//! converted (`scripts/kitchen-gltf.py`; skipped with a message otherwise).
//!
//! A shadow ray from each hit to a random point must be blocked in both scenes or in neither.
//! The truth is the original scene itself: each split hit is checked against the original
//! face its piece came from (its plane and outline), not against the split's own record.
//! Where the original has two coincident faces of different surfaces (z-fighting in the
//! model), either may be seen; the check then asks that the split's face also contains the
//! original hit point.

#[path = "support/kitchen.rs"]
mod kitchen;

use photon_maps::trace::glam::Vec3;
use photon_maps::trace::scenes::box_mesh::{Facing, box_mesh};
use photon_maps::trace::{
    Contact, Partitioned, Partitioner, PointLight, Ray, RayKind, Rng, Scene, SourceFace, Surface,
};
use proptest::prelude::*;
use std::collections::HashMap;

/// The original faces as polygons, by the face the user gave.
fn original_faces(scene: &Scene) -> HashMap<SourceFace, Vec<Vec3>> {
    let mut faces = HashMap::new();
    for m in scene.meshes() {
        let mesh = m.half_edge_mesh();
        for f in mesh.faces() {
            let source = scene.source_face(m.part_of_face(f)).expect("a mesh face");
            faces.insert(source, mesh.face_polygon(f).collect());
        }
    }
    faces
}

/// Whether `p` lies on the convex polygon within `tolerance` (its plane and its outline).
fn on_polygon(polygon: &[Vec3], p: Vec3, tolerance: f32) -> bool {
    let Some(normal) = photon_maps::geom::polygon_normal(polygon) else {
        return false;
    };
    if (p - polygon[0]).dot(normal).abs() > tolerance {
        return false;
    }
    let n = polygon.len();
    (0..n).all(|i| {
        let (a, b) = (polygon[i], polygon[(i + 1) % n]);
        normal.cross(b - a).normalize_or_zero().dot(p - a) >= -tolerance
    })
}

/// The polygon of a mesh part, for messages.
fn piece_polygon(scene: &Scene, part: photon_maps::trace::PartId) -> Vec<Vec3> {
    for m in scene.meshes() {
        let mesh = m.half_edge_mesh();
        if let Some(f) = mesh.faces().find(|&f| m.part_of_face(f) == part) {
            return mesh.face_polygon(f).collect();
        }
    }
    Vec::new()
}

/// A bound on how far off its face the hit of `ray` at `t` on a triangle of the fan of
/// `polygon` (the triangles the scene intersects) may be put by the `f32` triangle test: a
/// few units in the last place of the distances involved, times the triangle's condition
/// `L² / 2A` (longest edge squared over twice the area), which is large for slivers.
fn triangle_test_error(polygon: &[Vec3], ray: &Ray, t: f32) -> f32 {
    let condition = (1..polygon.len().saturating_sub(1))
        .map(|i| {
            let [a, b, c] = [polygon[0], polygon[i], polygon[i + 1]];
            let longest = a
                .distance_squared(b)
                .max(b.distance_squared(c))
                .max(c.distance_squared(a));
            longest / (b - a).cross(c - a).length().max(f32::MIN_POSITIVE)
        })
        .fold(0.0f32, f32::max);
    8.0 * f32::EPSILON * condition * (ray.origin.abs().max_element() + t)
}

/// What went wrong with one ray, if anything.
fn mismatch(
    original: &Scene,
    faces: &HashMap<SourceFace, Vec<Vec3>>,
    split: &Partitioned,
    ray: &Ray,
    kind: RayKind,
    lamp: Vec3,
) -> Option<String> {
    let far = 4.0 * original.bounds().diagonal() + ray.origin.length();
    let tolerance = 2e-6 * original.bounds().diagonal();
    let a = original.intersect(ray, far, kind);
    let b = split.scene().intersect(ray, far, kind);
    let (a, b) = match (a, b) {
        (None, None) => return None,
        (Some(a), Some(b)) => (a, b),
        (a, b) => return Some(format!("one scene hit, the other not: {a:?} / {b:?}")),
    };
    // Distances measured across the surface: a grazing ray turns a displacement of the
    // surface far below the tolerance (welding moves vertices by up to 10⁻⁶ of a mesh's
    // diagonal) into a long step along the ray.
    let across = a.normal.dot(ray.direction).abs();
    let rounding = triangle_test_error(&piece_polygon(split.scene(), b.part), ray, b.t)
        .max(triangle_test_error(&piece_polygon(original, a.part), ray, a.t));
    let slack = tolerance + rounding;
    if (a.t - b.t).abs() * across > slack {
        let source = split.source_face(b.part);
        return Some(format!(
            "hit at t = {} against {} as given (face {:?}, at {}), split piece of {source:?} at {}: {:?}",
            b.t,
            a.t,
            original.source_face(a.part),
            a.position,
            b.position,
            piece_polygon(split.scene(), b.part)
        ));
    }
    let Some(source) = split.source_face(b.part) else {
        return Some("a split mesh piece without a source face".into());
    };
    let polygon = &faces[&source];
    if !on_polygon(polygon, b.position, slack) {
        return Some(format!(
            "split hit {} is not on its source face {source:?}",
            b.position
        ));
    }
    let original_part = original.meshes()[source.mesh as usize].part_of_face(
        original.meshes()[source.mesh as usize]
            .half_edge_mesh()
            .faces()
            .find(|&f| {
                original.meshes()[source.mesh as usize]
                    .half_edge_mesh()
                    .source_face(f)
                    == source.face as usize
            })
            .expect("the source face is in the original"),
    );
    let surface = original.part_surface(original_part);
    if split.scene().surface(&b) != surface {
        return Some(format!("piece of {source:?} has another surface than its face"));
    }
    let normal = photon_maps::geom::polygon_normal(polygon).unwrap_or_default();
    let facing = ray.direction.dot(normal) < 0.0;
    if b.front_face != facing {
        return Some(format!(
            "piece of {source:?} turned around: {:?} from {polygon:?}",
            piece_polygon(split.scene(), b.part)
        ));
    }
    // A shadow ray from the hit towards a point of the scene is blocked in both or neither.
    let (shadowed, split_shadowed) = (
        original.occluded_from(&a, lamp),
        split.scene().occluded_from(&b, lamp),
    );
    if shadowed != split_shadowed {
        return Some(format!(
            "the shadow ray from {} to {lamp} is blocked as given: {shadowed}, split: {split_shadowed}",
            a.position
        ));
    }
    if original.surface(&a) != split.scene().surface(&b) {
        // Coincident faces of different surfaces: the split may show either, but only where
        // the face it shows really is.
        if !on_polygon(polygon, a.position, slack) {
            return Some(format!(
                "another surface than the original's at {}, and {source:?} is not there",
                a.position
            ));
        }
    }
    None
}

/// Rays of both kinds: from random points of the scene's bounds (grown by half) in random
/// directions, and aimed at random points of random faces (small pieces get their share);
/// from each hit a shadow ray to a random point of the bounds.
fn check_rays(original: &Scene, split: &Partitioned, count: usize, seed: u64) -> Result<(), String> {
    let faces = original_faces(original);
    let polygons: Vec<&Vec<Vec3>> = {
        let mut keys: Vec<_> = faces.keys().collect();
        keys.sort();
        keys.into_iter().map(|k| &faces[k]).collect()
    };
    let bounds = original.bounds();
    let size = bounds.max - bounds.min;
    let mut rng = Rng::new(seed, 7);
    let mut failures = Vec::new();
    for i in 0..count {
        let mut u = || rng.next_f32();
        let origin = bounds.min - 0.25 * size + Vec3::new(u(), u(), u()) * 1.5 * size;
        let direction = if i % 2 == 0 {
            Vec3::new(u() - 0.5, u() - 0.5, u() - 0.5)
        } else {
            let polygon = polygons[(u() * polygons.len() as f32) as usize % polygons.len()];
            let k = 1 + (u() * (polygon.len() - 2) as f32) as usize % (polygon.len() - 2);
            let (mut s, mut t) = (u(), u());
            if s + t > 1.0 {
                (s, t) = (1.0 - s, 1.0 - t);
            }
            let target = polygon[0] + s * (polygon[k] - polygon[0]) + t * (polygon[k + 1] - polygon[0]);
            target - origin
        };
        let Some(direction) = direction.try_normalize() else {
            continue;
        };
        let ray = Ray::new(origin, direction);
        let kind = if i % 4 < 2 {
            RayKind::Other
        } else {
            RayKind::Camera
        };
        let lamp = bounds.min + Vec3::new(rng.next_f32(), rng.next_f32(), rng.next_f32()) * size;
        if let Some(m) = mismatch(original, &faces, split, &ray, kind, lamp) {
            failures.push(format!("ray {i} from {origin} along {direction}: {m}"));
        }
    }
    if failures.is_empty() {
        Ok(())
    } else {
        let shown: Vec<_> = failures.iter().take(8).cloned().collect();
        Err(format!(
            "{} of {count} rays:\n{}",
            failures.len(),
            shown.join("\n")
        ))
    }
}

/// How a mesh's corners are given: shared by its faces, or repeated for every triangle (as
/// OBJ exports and the kitchen have them).
#[derive(Clone, Copy, Debug)]
enum Corners {
    Shared,
    Soup,
}

/// The box `[min, max]` (faces outward) as the builder's input, in the given corner layout.
fn solid(min: Vec3, max: Vec3, corners: Corners) -> (Vec<Vec3>, Vec<Vec<u32>>) {
    let (positions, quads) = box_mesh(min, max, Facing::Outward);
    match corners {
        Corners::Shared => (positions, quads.iter().map(|q| q.to_vec()).collect()),
        Corners::Soup => {
            let mut soup = Vec::new();
            let mut triangles = Vec::new();
            for q in &quads {
                for tri in [[q[0], q[1], q[2]], [q[0], q[2], q[3]]] {
                    let start = soup.len() as u32;
                    soup.extend(tri.iter().map(|&i| positions[i as usize]));
                    triangles.push(vec![start, start + 1, start + 2]);
                }
            }
            (soup, triangles)
        }
    }
}

/// A scene of the given boxes, each its own mesh of its own colour, lit by one lamp.
fn boxes(list: &[(Vec3, Vec3)], corners: Corners) -> Scene {
    let mut builder = Scene::builder();
    for (k, &(min, max)) in list.iter().enumerate() {
        let (positions, faces) = solid(min, max, corners);
        let albedo = Vec3::new(0.2 + 0.1 * k as f32, 0.5, 0.8 - 0.1 * k as f32);
        builder = builder.mesh(&positions, &faces, Surface::diffuse(albedo));
    }
    builder
        .light(PointLight::new(Vec3::new(0.1, 2.0, 0.2), Vec3::splat(10.0)))
        .build()
        .expect("a valid scene")
}

fn assert_split_keeps_visibility(scene: Scene, seed: u64) -> Result<(), TestCaseError> {
    let split = Contact::default()
        .partition(scene.clone())
        .expect("the split succeeds");
    let counts = split.record().expect("a contact record").counts();
    prop_assert!(
        counts.meetings() > 0,
        "the case must make the split cut: {counts:?}"
    );
    check_rays(&scene, &split, 3000, seed).map_err(TestCaseError::fail)
}

fn corners() -> impl Strategy<Value = Corners> {
    prop_oneof![Just(Corners::Shared), Just(Corners::Soup)]
}

/// The floor slab every case stands on: 2 m × 2 m, 10 cm thick, top at y = 0.
const SLAB: (Vec3, Vec3) = (Vec3::new(-1.0, -0.1, -1.0), Vec3::new(1.0, 0.0, 1.0));

proptest! {
    // The cases come from a fixed seed, so every run (CI's included) draws the same ones; change
    // the seed to explore. Failures found so far are kept in
    // split_visibility.proptest-regressions and run first.
    #![proptest_config(ProptestConfig {
        rng_seed: proptest::test_runner::RngSeed::Fixed(20_261_203),
        ..ProptestConfig::with_cases(24)
    })]

    /// A box resting on the slab, sunk a little into it or floating within the gap above it.
    #[test]
    fn resting_and_sunk_boxes(
        x in -0.8f32..0.4, z in -0.8f32..0.4, w in 0.05f32..0.4, h in 0.05f32..0.8,
        lift in prop_oneof![Just(0.0f32), -0.02f32..0.0, 0.0f32..0.004],
        corners in corners(), seed in 0u64..1000,
    ) {
        let scene = boxes(&[SLAB, (Vec3::new(x, lift, z), Vec3::new(x + w, lift + h, z + w))], corners);
        assert_split_keeps_visibility(scene, seed)?;
    }

    /// A post through the slab and a second box through the post.
    #[test]
    fn piercing_boxes(
        x in -0.8f32..0.6, z in -0.8f32..0.6, w in 0.03f32..0.2, y in 0.1f32..0.6,
        corners in corners(), seed in 0u64..1000,
    ) {
        let post = (Vec3::new(x, -0.3, z), Vec3::new(x + w, 0.9, z + w));
        let bar = (Vec3::new(x - 0.2, y, z + 0.3 * w), Vec3::new(x + w + 0.2, y + 0.05, z + 0.6 * w));
        assert_split_keeps_visibility(boxes(&[SLAB, post, bar], corners), seed)?;
    }

    /// Two boxes sharing part of a face plane (side by side, overlapping in the plane where
    /// they touch, or one stacked on the other with coplanar sides).
    #[test]
    fn coplanar_faces(
        x in -0.8f32..0.2, w in 0.1f32..0.5, shift in -0.3f32..0.3, corners in corners(), seed in 0u64..1000,
    ) {
        let a = (Vec3::new(x, 0.0, -0.2), Vec3::new(x + w, 0.4, 0.2));
        let b = (Vec3::new(x + w, 0.0, -0.2 + shift), Vec3::new(x + 2.0 * w, 0.3, 0.2 + shift));
        let c = (Vec3::new(x, 0.4, -0.2), Vec3::new(x + w, 0.6, 0.2 + shift.abs()));
        assert_split_keeps_visibility(boxes(&[SLAB, a, b, c], corners), seed)?;
    }

    /// A long kick plate (its triangles 1.4° sharp at the ends, as in the kitchen) on the slab,
    /// touched near a sharp corner by a thin panel: cuts crowd into the corner, micrometres
    /// apart, and the pieces there are slivers. (It does not reproduce the kitchen's dropped
    /// pieces, whose cut vertices came from several faces; `a_face_pinched_by_welding_keeps_its_area`
    /// in pm-geom's mesh tests and the kitchen case below do.)
    #[test]
    fn sliver_panel_touched_near_its_sharp_corner(
        near in 1e-5f32..1e-3, depth in 0.01f32..0.05, corners in corners(), seed in 0u64..1000,
    ) {
        let plate = (Vec3::new(-0.99, 0.0, 0.5), Vec3::new(0.99, 0.0484, 0.5 + depth));
        let panel = (Vec3::new(-0.99 + near, 0.0, 0.3), Vec3::new(-0.99 + near + 0.02, 0.6, 0.6));
        assert_split_keeps_visibility(boxes(&[SLAB, plate, panel], corners), seed)?;
    }
}

/// The kitchen of the obvhs crate, converted by `scripts/kitchen-gltf.py` (to
/// `target/kitchen/kitchen.gltf`, or where `PM_KITCHEN_GLTF` says): 200,000 rays, none of
/// which may see a different surface or distance after the split, nor a shadow ray from its
/// hit blocked differently. (Before the split scene's rays met the faces as given, 2 shadow
/// rays disagreed, and at 1,000 drawn cases the sliver panel and the resting boxes each found
/// one more; 1,000 cases of every case above pass now.)
#[test]
fn kitchen_split_keeps_visibility() {
    let Some(scene) = kitchen::load_kitchen(&kitchen::kitchen_path()) else {
        return;
    };
    let split = Contact::default()
        .partition(scene.clone())
        .expect("the split succeeds");
    check_rays(&scene, &split, 200_000, 1).unwrap();
}
