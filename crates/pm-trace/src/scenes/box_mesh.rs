//! The six faces of an axis-aligned box as quads, wound inwards (a room) or outwards (a
//! solid), from which the built-in scenes are assembled.

use glam::Vec3;

/// Which way a box's faces point.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Facing {
    /// Into the box: a room, seen from inside.
    Inward,
    /// Out of the box: a solid, seen from outside.
    Outward,
}

/// Faces of the box `[min, max]` as quads over the 8 corners `i → (x: bit 0, y: bit 1,
/// z: bit 2)`, in the order floor (y min), ceiling, x min, x max, z max (back), z min (front).
/// `facing` says which way their normals point.
pub fn box_mesh(min: Vec3, max: Vec3, facing: Facing) -> (Vec<Vec3>, Vec<[u32; 4]>) {
    let corners = (0..8)
        .map(|i| {
            Vec3::new(
                if i & 1 != 0 { max.x } else { min.x },
                if i & 2 != 0 { max.y } else { min.y },
                if i & 4 != 0 { max.z } else { min.z },
            )
        })
        .collect();
    let mut faces = vec![
        [0, 4, 5, 1],
        [2, 3, 7, 6],
        [0, 2, 6, 4],
        [1, 5, 7, 3],
        [4, 6, 7, 5],
        [0, 1, 3, 2],
    ];
    if facing == Facing::Outward {
        for f in &mut faces {
            f.reverse();
        }
    }
    (corners, faces)
}
