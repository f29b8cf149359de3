//! The two-room scenes: lit and unlit rooms, coloured rooms with floating cubes, and touching
//! rooms whose floor and ceiling run under and over the dividing wall.

use super::box_mesh::{Facing, box_mesh};
use crate::camera::Camera;
use crate::error::SceneError;
use crate::light::point::PointLight;
use crate::material::Surface;
use crate::scene::Scene;
use crate::scene::builder::SceneBuilder;
use glam::Vec3;

/// Inside size of each room, thickness of the dividing wall.
pub(super) const ROOM: f32 = 1.0;
pub(super) const WALL: f32 = 0.02;
/// Where the lit room's point light hangs.
pub(super) const LIT_ROOM_LIGHT: Vec3 = Vec3::new(0.8, 0.5, 0.5);

fn white() -> Surface {
    Surface::diffuse(Vec3::splat(0.75))
}

/// Looks at both rooms from the front (−z) with the dividing wall on the middle column.
pub(super) fn rooms_camera() -> Camera {
    let x = ROOM + WALL * 0.5;
    Camera::new(
        Vec3::new(x, 0.5, -2.2),
        Vec3::new(x, 0.5, 0.5),
        Vec3::Y,
        50f32.to_radians(),
    )
}

/// A closed room with inward normals at `x0`; its front wall (z = 0, facing the camera) is
/// hidden from camera rays.
fn add_room(builder: SceneBuilder, x0: f32) -> SceneBuilder {
    let (corners, faces) = box_mesh(
        Vec3::new(x0, 0.0, 0.0),
        Vec3::new(x0 + ROOM, ROOM, ROOM),
        Facing::Inward,
    );
    let w = white();
    builder.mesh_per_face(&corners, &faces, &[w, w, w, w, w, w.hidden_from_camera()])
}

fn two_rooms() -> SceneBuilder {
    add_room(add_room(Scene::builder(), 0.0), ROOM + WALL).camera(rooms_camera())
}

pub(super) fn lit_unlit_rooms() -> Result<Scene, SceneError> {
    two_rooms()
        .light(PointLight::new(LIT_ROOM_LIGHT, Vec3::splat(50.0)))
        .build()
}

pub(super) fn colored_rooms() -> Result<Scene, SceneError> {
    let mut builder = two_rooms();
    for x0 in [0.0, ROOM + WALL] {
        let c = Vec3::new(x0 + 0.5 * ROOM, 0.5, 0.5);
        let (corners, faces) = box_mesh(c - Vec3::splat(0.15), c + Vec3::splat(0.15), Facing::Outward);
        builder = builder.mesh(&corners, &faces, white());
    }
    builder
        .light(PointLight::new(
            Vec3::new(0.5, 0.85, 0.5),
            Vec3::new(40.0, 4.0, 4.0),
        ))
        .light(PointLight::new(
            Vec3::new(ROOM + WALL + 0.5, 0.85, 0.5),
            Vec3::new(4.0, 4.0, 40.0),
        ))
        .build()
}

pub(super) fn touching_rooms() -> Result<Scene, SceneError> {
    let (x1, x2, x3) = (ROOM, ROOM + WALL, 2.0 * ROOM + WALL);
    let p = |x: f32, y: f32, z: f32| Vec3::new(x, y, z);
    // One mesh: the floor and ceiling span both rooms; the divider's faces stand on the floor
    // and touch the ceiling without sharing an edge with them.
    let quads: [[Vec3; 4]; 10] = [
        [
            p(0.0, 0.0, 0.0),
            p(0.0, 0.0, 1.0),
            p(x3, 0.0, 1.0),
            p(x3, 0.0, 0.0),
        ], // floor, +y
        [
            p(0.0, 1.0, 0.0),
            p(x3, 1.0, 0.0),
            p(x3, 1.0, 1.0),
            p(0.0, 1.0, 1.0),
        ], // ceiling, −y
        [
            p(0.0, 0.0, 0.0),
            p(0.0, 1.0, 0.0),
            p(0.0, 1.0, 1.0),
            p(0.0, 0.0, 1.0),
        ], // x = 0, +x
        [p(x3, 0.0, 0.0), p(x3, 0.0, 1.0), p(x3, 1.0, 1.0), p(x3, 1.0, 0.0)], // x = x3, −x
        [p(x1, 0.0, 0.0), p(x1, 0.0, 1.0), p(x1, 1.0, 1.0), p(x1, 1.0, 0.0)], // divider, left side, −x
        [p(x2, 0.0, 0.0), p(x2, 1.0, 0.0), p(x2, 1.0, 1.0), p(x2, 0.0, 1.0)], // divider, right side, +x
        [
            p(0.0, 0.0, 1.0),
            p(0.0, 1.0, 1.0),
            p(x1, 1.0, 1.0),
            p(x1, 0.0, 1.0),
        ], // left back, −z
        [p(x2, 0.0, 1.0), p(x2, 1.0, 1.0), p(x3, 1.0, 1.0), p(x3, 0.0, 1.0)], // right back, −z
        [
            p(0.0, 0.0, 0.0),
            p(x1, 0.0, 0.0),
            p(x1, 1.0, 0.0),
            p(0.0, 1.0, 0.0),
        ], // left front, +z
        [p(x2, 0.0, 0.0), p(x3, 0.0, 0.0), p(x3, 1.0, 0.0), p(x2, 1.0, 0.0)], // right front, +z
    ];
    let positions: Vec<Vec3> = quads.iter().flatten().copied().collect();
    let faces: Vec<[u32; 4]> = (0..quads.len() as u32)
        .map(|i| [4 * i, 4 * i + 1, 4 * i + 2, 4 * i + 3])
        .collect();
    let w = white();
    let hidden = w.hidden_from_camera();
    let surfaces = [w, w, w, w, w, w, w, w, hidden, hidden];
    Scene::builder()
        .mesh_per_face(&positions, &faces, &surfaces)
        .light(PointLight::new(LIT_ROOM_LIGHT, Vec3::splat(50.0)))
        .camera(rooms_camera())
        .build()
}
