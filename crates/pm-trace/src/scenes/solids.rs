//! The two rooms of `lit-unlit-rooms` built as modellers build them: floor and ceiling slabs
//! under and over both rooms, and every wall a solid box, with the dividing wall standing on the
//! slabs, running through them, stopping just short of them, and with a box sunk into the
//! floor, a duplicated floor, and a T-junction of walls. The left room holds a point light, the
//! right one nothing, so its true radiance is zero (up to what passes a gap).

use super::box_mesh::{Facing, box_mesh};
use super::rooms::{LIT_ROOM_LIGHT, ROOM, WALL, rooms_camera};
use crate::error::SceneError;
use crate::light::point::PointLight;
use crate::material::Surface;
use crate::scene::Scene;
use crate::scene::builder::SceneBuilder;
use glam::Vec3;

/// Thickness of the slabs and outer walls.
const SHELL: f32 = 0.1;

/// Names of the solid-room scenes, for [`super::build`].
pub const SOLID_NAMES: [&str; 6] = [
    "solid-rooms-stand",
    "solid-rooms-pierce",
    "solid-rooms-gap",
    "solid-rooms-sunk-box",
    "solid-rooms-double-floor",
    "solid-rooms-tee",
];

/// The width of the gap in `solid-rooms-gap`: 0.1 % of the scene's bounding-box diagonal.
pub fn solid_rooms_gap() -> f32 {
    let size = shell_max() - shell_min();
    1e-3 * size.length()
}

fn shell_min() -> Vec3 {
    Vec3::new(-SHELL, -SHELL, -SHELL)
}

fn shell_max() -> Vec3 {
    Vec3::new(2.0 * ROOM + WALL + SHELL, ROOM + SHELL, ROOM + SHELL)
}

fn white() -> Surface {
    Surface::diffuse(Vec3::splat(0.75))
}

fn solid(builder: SceneBuilder, min: Vec3, max: Vec3, surface: Surface) -> SceneBuilder {
    let (corners, faces) = box_mesh(min, max, Facing::Outward);
    builder.mesh(&corners, &faces, surface)
}

/// The shell: floor and ceiling slabs across both rooms, outer walls standing on the floor slab
/// and meeting the ceiling slab, the front one hidden from the camera.
fn shell() -> SceneBuilder {
    let (lo, hi) = (shell_min(), shell_max());
    let x3 = 2.0 * ROOM + WALL;
    let w = white();
    let mut b = Scene::builder().camera(rooms_camera());
    b = solid(b, lo, Vec3::new(hi.x, 0.0, hi.z), w); // floor slab
    b = solid(b, Vec3::new(lo.x, ROOM, lo.z), hi, w); // ceiling slab
    b = solid(b, Vec3::new(lo.x, 0.0, 0.0), Vec3::new(0.0, ROOM, ROOM), w); // left
    b = solid(b, Vec3::new(x3, 0.0, 0.0), Vec3::new(hi.x, ROOM, ROOM), w); // right
    b = solid(b, Vec3::new(lo.x, 0.0, ROOM), Vec3::new(hi.x, ROOM, hi.z), w); // back
    solid(
        b,
        Vec3::new(lo.x, 0.0, lo.z),
        Vec3::new(hi.x, ROOM, 0.0),
        w.hidden_from_camera(),
    ) // front
}

/// The dividing wall from height `y0` to `y1`, over depth `z0..z1`.
fn divider(builder: SceneBuilder, y0: f32, y1: f32, z0: f32, z1: f32) -> SceneBuilder {
    solid(
        builder,
        Vec3::new(ROOM, y0, z0),
        Vec3::new(ROOM + WALL, y1, z1),
        white(),
    )
}

/// Builds the solid-room scene `name` (one of [`SOLID_NAMES`]), or `None` for another name.
pub(super) fn solid_rooms(name: &str) -> Option<Result<Scene, SceneError>> {
    let b = shell();
    let b = match name {
        "solid-rooms-stand" => divider(b, 0.0, ROOM, 0.0, ROOM),
        "solid-rooms-pierce" => divider(b, -0.05, ROOM + 0.05, -0.05, ROOM + 0.05),
        "solid-rooms-gap" => {
            let gap = solid_rooms_gap();
            divider(b, gap, ROOM - gap, 0.0, ROOM)
        }
        "solid-rooms-sunk-box" => {
            let b = divider(b, 0.0, ROOM, 0.0, ROOM);
            // A 0.3 m box in the lit room, sunk halfway into the floor slab.
            solid(b, Vec3::new(0.2, -0.05, 0.3), Vec3::new(0.5, 0.05, 0.6), white())
        }
        "solid-rooms-double-floor" => {
            let b = divider(b, 0.0, ROOM, 0.0, ROOM);
            // A floor quad exported twice over the slab's top, across both rooms.
            let (lo, hi) = (shell_min(), shell_max());
            let quad = [
                Vec3::new(lo.x, 0.0, lo.z),
                Vec3::new(lo.x, 0.0, hi.z),
                Vec3::new(hi.x, 0.0, hi.z),
                Vec3::new(hi.x, 0.0, lo.z),
            ];
            b.mesh(&quad, &[[0u32, 1, 2, 3]], white())
                .mesh(&quad, &[[0u32, 1, 2, 3]], white())
        }
        "solid-rooms-tee" => {
            let b = divider(b, 0.0, ROOM, 0.0, ROOM);
            // A wall in the lit room running into the divider (it pierces the divider's box).
            solid(
                b,
                Vec3::new(0.5, 0.0, 0.69),
                Vec3::new(ROOM + 0.01, ROOM, 0.71),
                white(),
            )
        }
        _ => return None,
    };
    Some(
        b.light(PointLight::new(LIT_ROOM_LIGHT, Vec3::splat(50.0)))
            .build(),
    )
}
