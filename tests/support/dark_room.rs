//! The dark room of the two-room scenes, in image pixels: for leak tests. Include it with
//! `#[path = "support/dark_room.rs"] mod dark_room;` (from `tests/`).

use photon_maps::trace::{RayKind, Scene};

/// The dark room's interior starts here (room 1 m, wall 0.02 m); a margin keeps away from it.
const DARK_ROOM_X: f32 = 1.02 + 0.01;

/// Pixels of a `width × height` image whose four corner rays all hit the dark room: every
/// sample inside them shows it.
pub fn dark_room_pixels(scene: &Scene, width: u32, height: u32) -> Vec<usize> {
    let camera = scene.camera();
    let aspect = width as f32 / height as f32;
    let in_dark = |u: f32, v: f32| {
        let ray = camera.ray(u, v, aspect);
        scene
            .intersect(&ray, f32::INFINITY, RayKind::Camera)
            .is_some_and(|h| h.position.x > DARK_ROOM_X)
    };
    (0..width * height)
        .filter(|&i| {
            let (x, y) = ((i % width) as f32, (i / width) as f32);
            [(0.0, 0.0), (1.0, 0.0), (0.0, 1.0), (1.0, 1.0)]
                .iter()
                .all(|&(dx, dy)| in_dark((x + dx) / width as f32, (y + dy) / height as f32))
        })
        .map(|i| i as usize)
        .collect()
}
