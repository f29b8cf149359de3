//! `doorway-rooms-N`: a row of `N` lit rooms joined by doorways, seen from inside the first.
//! The camera sees about one room of what the `N` lights light; light from the next rooms
//! reaches it only through the doorways. The scene for camera-driven emission.

use super::rooms::{ROOM, WALL};
use crate::camera::Camera;
use crate::error::SceneError;
use crate::light::point::PointLight;
use crate::material::Surface;
use crate::scene::Scene;
use glam::Vec3;

/// The most rooms [`doorway_rooms`] builds.
pub const MAX_DOORWAY_ROOMS: u32 = 256;

/// The doorway in each dividing wall: `z` from `DOOR_Z.0` to `DOOR_Z.1`, `y` up to `DOOR_HEIGHT`.
const DOOR_Z: (f32, f32) = (0.35, 0.65);
const DOOR_HEIGHT: f32 = 0.75;
/// Each room's point light: where it hangs in the room, and its power per channel.
const LIGHT_AT: Vec3 = Vec3::new(0.5, 0.8, 0.5);
const LIGHT_POWER: f32 = 2.0;

/// Quads as they are added: corners and faces.
#[derive(Default)]
struct Quads {
    corners: Vec<Vec3>,
    faces: Vec<[u32; 4]>,
}

impl Quads {
    /// The rectangle `corner`, `corner + u`, `corner + u + v`, `corner + v`, facing `u × v`.
    fn rect(&mut self, corner: Vec3, u: Vec3, v: Vec3) {
        let i = self.corners.len() as u32;
        self.corners
            .extend([corner, corner + u, corner + u + v, corner + v]);
        self.faces.push([i, i + 1, i + 2, i + 3]);
    }

    /// The wall in the plane `x`, facing +x (`facing_plus`) or −x, with the doorway cut out
    /// when `door` says so.
    fn side_wall(&mut self, x: f32, normal: Side, door: Door) {
        let pieces: &[(f32, f32, f32, f32)] = match door {
            Door::None => &[(0.0, ROOM, 0.0, ROOM)],
            Door::Cut => &[
                (0.0, DOOR_Z.0, 0.0, ROOM),
                (DOOR_Z.1, ROOM, 0.0, ROOM),
                (DOOR_Z.0, DOOR_Z.1, DOOR_HEIGHT, ROOM),
            ],
        };
        for &(z0, z1, y0, y1) in pieces {
            let (dz, dy) = (Vec3::Z * (z1 - z0), Vec3::Y * (y1 - y0));
            let corner = Vec3::new(x, y0, z0);
            match normal {
                Side::PlusX => self.rect(corner, dy, dz),
                Side::MinusX => self.rect(corner, dz, dy),
            }
        }
    }

    /// The doorway's tunnel through the dividing wall from `x` to `x + WALL`: its two sides,
    /// top and floor, facing into it.
    fn tunnel(&mut self, x: f32) {
        let (w, dz) = (Vec3::X * WALL, Vec3::Z * (DOOR_Z.1 - DOOR_Z.0));
        let h = Vec3::Y * DOOR_HEIGHT;
        self.rect(Vec3::new(x, 0.0, DOOR_Z.0), w, h);
        self.rect(Vec3::new(x, 0.0, DOOR_Z.1), h, w);
        self.rect(Vec3::new(x, DOOR_HEIGHT, DOOR_Z.0), w, dz);
        self.rect(Vec3::new(x, 0.0, DOOR_Z.0), dz, w);
    }
}

#[derive(Clone, Copy)]
enum Side {
    PlusX,
    MinusX,
}

#[derive(Clone, Copy, PartialEq)]
enum Door {
    None,
    Cut,
}

/// `n` unit rooms in a row along +x, each lit by a 2 W point light under its ceiling, each
/// dividing wall (2 cm thick) pierced by a doorway 0.3 m wide and 0.75 m high; the camera
/// stands in the first room, looking across it at the doorway to the second. Errors for
/// `n = 0` or `n >` [`MAX_DOORWAY_ROOMS`].
pub fn doorway_rooms(n: u32) -> Result<Scene, SceneError> {
    if n == 0 || n > MAX_DOORWAY_ROOMS {
        return Err(SceneError::InvalidParameter {
            what: "doorway_rooms: n".to_string(),
            reason: format!("{n} is outside 1..={MAX_DOORWAY_ROOMS}"),
        });
    }
    let mut q = Quads::default();
    let mut builder = Scene::builder();
    for i in 0..n {
        let x0 = i as f32 * (ROOM + WALL);
        let (x, y, z) = (Vec3::X * ROOM, Vec3::Y * ROOM, Vec3::Z * ROOM);
        let o = Vec3::new(x0, 0.0, 0.0);
        q.rect(o, z, x); // floor, facing up
        q.rect(o + y, x, z); // ceiling, facing down
        q.rect(o + z, y, x); // back, facing -z
        q.rect(o, x, y); // front, facing +z
        let left = if i > 0 { Door::Cut } else { Door::None };
        let right = if i + 1 < n { Door::Cut } else { Door::None };
        q.side_wall(x0, Side::PlusX, left);
        q.side_wall(x0 + ROOM, Side::MinusX, right);
        if right == Door::Cut {
            q.tunnel(x0 + ROOM);
        }
        builder = builder.light(PointLight::new(o + LIGHT_AT, Vec3::splat(LIGHT_POWER)));
    }
    builder
        .mesh(&q.corners, &q.faces, Surface::diffuse(Vec3::splat(0.75)))
        .camera(Camera::new(
            Vec3::new(0.1, 0.55, 0.08),
            Vec3::new(0.95, 0.35, 0.6),
            Vec3::Y,
            70f32.to_radians(),
        ))
        .build()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::ray::Ray;
    use crate::scene::RayKind;

    /// Parts (quads) per room (floor, ceiling, back, front, side walls with their cuts, tunnels) and
    /// one light per room; a ray through a doorway passes into the next room, one beside it
    /// stops at the dividing wall; the range is refused outside 1..=256.
    #[test]
    fn rooms_are_joined_only_through_their_doorways() {
        for n in [1u32, 2, 5] {
            let scene = doorway_rooms(n).unwrap();
            assert_eq!(scene.lights().len(), n as usize);
            let quads = 4 * n + 2 + 3 * 2 * (n - 1) + 4 * (n - 1);
            assert_eq!(scene.part_count(), quads as usize, "n = {n}");
        }
        let scene = doorway_rooms(3).unwrap();
        let through = Ray::new(Vec3::new(0.5, 0.3, 0.5), Vec3::X);
        let hit = scene.intersect(&through, f32::INFINITY, RayKind::Other).unwrap();
        assert!(
            (hit.position.x - (3.0 * ROOM + 2.0 * WALL)).abs() < 1e-4,
            "{}",
            hit.position
        );
        let beside = Ray::new(Vec3::new(0.5, 0.3, 0.2), Vec3::X);
        let hit = scene.intersect(&beside, f32::INFINITY, RayKind::Other).unwrap();
        assert!((hit.position.x - ROOM).abs() < 1e-4, "{}", hit.position);
        let above = Ray::new(Vec3::new(0.5, 0.8, 0.5), Vec3::X);
        let hit = scene.intersect(&above, f32::INFINITY, RayKind::Other).unwrap();
        assert!((hit.position.x - ROOM).abs() < 1e-4, "{}", hit.position);
        assert!(doorway_rooms(0).is_err());
        assert!(doorway_rooms(MAX_DOORWAY_ROOMS + 1).is_err());
    }
}
