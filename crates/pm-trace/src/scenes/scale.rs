//! Scenes for measuring how cost grows with the work: Ball & Stejko's rooms with every face split
//! into an `n × n` grid of quads, and a field of many separate cubes. Their light transport is
//! the same at every `n` (the split faces are coplanar), so their images can be compared.

use super::box_mesh::{Facing, box_mesh};
use super::rooms;
use crate::error::SceneError;
use crate::light::point::PointLight;
use crate::material::Surface;
use crate::scene::Scene;
use crate::scene::builder::SceneBuilder;
use glam::Vec3;

/// The largest `n` accepted by [`split_rooms`] (2·6·2·n² = 96M triangles at this bound).
pub const MAX_SPLIT: u32 = 2000;

/// Splits each quad of `(corners, quads)` into an `n × n` grid of quads sharing their
/// vertices, so every split face stays edge-connected (and coplanar) with its neighbours.
pub fn split_quads(corners: &[Vec3], quads: &[[u32; 4]], n: u32) -> (Vec<Vec3>, Vec<[u32; 4]>) {
    let n = n.max(1);
    let side = n + 1;
    let mut positions = Vec::with_capacity(quads.len() * (side * side) as usize);
    let mut faces = Vec::with_capacity(quads.len() * (n * n) as usize);
    for q in quads {
        let [a, b, c, d] = q.map(|i| corners[i as usize]);
        let first = positions.len() as u32;
        for j in 0..side {
            let t = j as f32 / n as f32;
            // Edge a→d and edge b→c at parameter t, then across from one to the other.
            let (left, right) = (a.lerp(d, t), b.lerp(c, t));
            for i in 0..side {
                positions.push(left.lerp(right, i as f32 / n as f32));
            }
        }
        for j in 0..n {
            for i in 0..n {
                let v = first + j * side + i;
                faces.push([v, v + 1, v + side + 1, v + side]);
            }
        }
    }
    (positions, faces)
}

/// `lit-unlit-rooms` with every face of both rooms split into `n × n` coplanar quads
/// (`24 n²` triangles; `n = 1` is the built-in scene). Returns an error for `n = 0` or
/// `n >` [`MAX_SPLIT`].
pub fn split_rooms(n: u32) -> Result<Scene, SceneError> {
    if n == 0 || n > MAX_SPLIT {
        return Err(SceneError::InvalidParameter {
            what: "split_rooms: n".to_string(),
            reason: format!("{n} is outside 1..={MAX_SPLIT}"),
        });
    }
    let mut builder = Scene::builder();
    for x0 in [0.0, rooms::ROOM + rooms::WALL] {
        builder = add_split_room(builder, x0, n);
    }
    builder
        .camera(rooms::rooms_camera())
        .light(PointLight::new(rooms::LIT_ROOM_LIGHT, Vec3::splat(50.0)))
        .build()
}

fn add_split_room(builder: SceneBuilder, x0: f32, n: u32) -> SceneBuilder {
    let (corners, quads) = box_mesh(
        Vec3::new(x0, 0.0, 0.0),
        Vec3::new(x0 + rooms::ROOM, rooms::ROOM, rooms::ROOM),
        Facing::Inward,
    );
    let (positions, faces) = split_quads(&corners, &quads, n);
    let w = Surface::diffuse(Vec3::splat(0.75));
    // box_mesh's last quad is the front wall, hidden from the camera.
    let per_quad = (n * n) as usize;
    let surfaces: Vec<Surface> = (0..faces.len())
        .map(|f| {
            if f / per_quad == 5 {
                w.hidden_from_camera()
            } else {
                w
            }
        })
        .collect();
    builder.mesh_per_face(&positions, &faces, &surfaces)
}

/// The largest cube count accepted by [`cube_field`].
pub const MAX_CUBES: u32 = 10_000_000;

/// `count` separate small cubes (12 triangles each) on a jittered grid over a 10 m floor,
/// lit by a point light above: many objects, each its own photon map under a crease
/// partition. Deterministic for a given `count`.
pub fn cube_field(count: u32) -> Result<Scene, SceneError> {
    if count == 0 || count > MAX_CUBES {
        return Err(SceneError::InvalidParameter {
            what: "cube_field: count".to_string(),
            reason: format!("{count} is outside 1..={MAX_CUBES}"),
        });
    }
    let size = 10.0f32;
    let per_side = (count as f64).sqrt().ceil() as u32;
    let cell = size / per_side as f32;
    let half = 0.3 * cell;
    let floor = [
        Vec3::new(0.0, 0.0, 0.0),
        Vec3::new(0.0, 0.0, size),
        Vec3::new(size, 0.0, size),
        Vec3::new(size, 0.0, 0.0),
    ];
    let mut positions = Vec::with_capacity(count as usize * 8);
    let mut faces: Vec<[u32; 4]> = Vec::with_capacity(count as usize * 6);
    let mut rng = crate::rng::Rng::new(0x5ca1e, count as u64);
    for i in 0..count {
        let (gx, gz) = ((i % per_side) as f32, (i / per_side) as f32);
        let jitter = Vec3::new(rng.next_f32() - 0.5, rng.next_f32(), rng.next_f32() - 0.5) * 0.2 * cell;
        let c = Vec3::new(
            (gx + 0.5) * cell,
            half * (1.0 + 2.0 * rng.next_f32()),
            (gz + 0.5) * cell,
        ) + jitter;
        let (corners, quads) = box_mesh(c - Vec3::splat(half), c + Vec3::splat(half), Facing::Outward);
        let first = positions.len() as u32;
        positions.extend(corners);
        faces.extend(quads.iter().map(|q| q.map(|v| v + first)));
    }
    let white = Surface::diffuse(Vec3::splat(0.7));
    Scene::builder()
        .mesh(&floor, &[[0u32, 1, 2, 3]], white)
        .mesh(&positions, &faces, white)
        .light(PointLight::new(
            Vec3::new(0.5 * size, 0.6 * size, 0.5 * size),
            Vec3::splat(1000.0),
        ))
        .camera(crate::camera::Camera::new(
            Vec3::new(0.5 * size, 0.7 * size, -0.4 * size),
            Vec3::new(0.5 * size, 0.0, 0.5 * size),
            Vec3::Y,
            50f32.to_radians(),
        ))
        .build()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn split_rooms_have_24_n_squared_triangles_and_keep_each_wall_one_map() {
        use crate::partition::Partitioner;
        use crate::partition::crease::CreaseAngle;
        for n in [1, 3] {
            let scene = split_rooms(n).unwrap();
            assert_eq!(scene.part_count() as u32, 12 * n * n);
            // Coplanar split faces are edge-connected: one map per wall, as at n = 1.
            assert_eq!(
                CreaseAngle::default()
                    .partition(scene.clone())
                    .unwrap()
                    .assignment()
                    .map_count(),
                12
            );
        }
        assert!(split_rooms(0).is_err());
        assert!(split_rooms(MAX_SPLIT + 1).is_err());
    }

    #[test]
    fn cube_field_has_one_map_per_cube_and_the_floor() {
        use crate::partition::Partitioner;
        use crate::partition::crease::CreaseAngle;
        let scene = cube_field(50).unwrap();
        assert_eq!(scene.part_count(), 1 + 50 * 6);
        assert_eq!(
            CreaseAngle::default()
                .partition(scene.clone())
                .unwrap()
                .assignment()
                .map_count(),
            1 + 50 * 6
        );
        assert!(cube_field(0).is_err());
    }
}
