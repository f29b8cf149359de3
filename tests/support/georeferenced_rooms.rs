//! The lit and unlit rooms as a georeferenced glTF file: small coordinates in the accessors
//! (1 m rooms), a root node carrying the placement (a translation of up to thousands of
//! kilometres and a uniform scale), and the rooms, a camera and a point lamp as its children.
//! Include it with `#[path = "support/georeferenced_rooms.rs"] mod georeferenced_rooms;`.

#![allow(dead_code)]

use std::path::{Path, PathBuf};

use photon_maps::trace::glam::Vec3;
use photon_maps::trace::scenes::box_mesh::{Facing, box_mesh};

/// Thickness of the slabs, in the file's local metres.
pub const SLAB: f32 = 0.02;

/// How the rooms' walls are modelled.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Walls {
    /// Every wall, the floor and the ceiling a solid box [`SLAB`] thick (outward faces),
    /// single-sided as glTF exports default to; the lit room's inside is `[0, 1]³`, the dark
    /// one's `[1 + SLAB, 2 + SLAB] × [0, 1]²`.
    SolidSlabs,
    /// Two inward boxes `[0, 1]³` and `[1, 2] × [0, 1]²` sharing the plane x = 1 (no
    /// thickness), double-sided.
    SharedWallDoubleSided,
    /// The same two boxes with glTF's default single-sided material.
    SharedWallSingleSided,
}

impl Walls {
    pub const ALL: [Walls; 3] = [
        Walls::SolidSlabs,
        Walls::SharedWallDoubleSided,
        Walls::SharedWallSingleSided,
    ];

    /// Where the dark room's inside starts along x.
    pub fn dark_room_x(self) -> f32 {
        match self {
            Walls::SolidSlabs => 1.0 + SLAB,
            _ => 1.0,
        }
    }

    /// Quads (4 corner indices, counter-clockwise seen from the front) over `positions`.
    fn geometry(self) -> (Vec<Vec3>, Vec<[u32; 4]>) {
        let mut positions = Vec::new();
        let mut quads = Vec::new();
        let mut add = |min: Vec3, max: Vec3, facing: Facing| {
            let (p, q) = box_mesh(min, max, facing);
            let base = positions.len() as u32;
            positions.extend(p);
            quads.extend(q.iter().map(|f| f.map(|i| i + base)));
        };
        match self {
            Walls::SolidSlabs => {
                let (s, x1) = (SLAB, 2.0 + 2.0 * SLAB);
                // Floor and ceiling slabs across both rooms and the outer walls.
                add(
                    Vec3::new(-s, -s, -s),
                    Vec3::new(x1, 0.0, 1.0 + s),
                    Facing::Outward,
                );
                add(
                    Vec3::new(-s, 1.0, -s),
                    Vec3::new(x1, 1.0 + s, 1.0 + s),
                    Facing::Outward,
                );
                add(Vec3::new(-s, 0.0, 0.0), Vec3::new(0.0, 1.0, 1.0), Facing::Outward);
                add(
                    Vec3::new(x1 - s, 0.0, 0.0),
                    Vec3::new(x1, 1.0, 1.0),
                    Facing::Outward,
                );
                add(
                    Vec3::new(-s, 0.0, 1.0),
                    Vec3::new(x1, 1.0, 1.0 + s),
                    Facing::Outward,
                );
                add(Vec3::new(-s, 0.0, -s), Vec3::new(x1, 1.0, 0.0), Facing::Outward);
                // The dividing wall, standing on the floor slab.
                add(
                    Vec3::new(1.0, 0.0, 0.0),
                    Vec3::new(1.0 + s, 1.0, 1.0),
                    Facing::Outward,
                );
            }
            Walls::SharedWallDoubleSided | Walls::SharedWallSingleSided => {
                add(Vec3::ZERO, Vec3::ONE, Facing::Inward);
                add(Vec3::new(1.0, 0.0, 0.0), Vec3::new(2.0, 1.0, 1.0), Facing::Inward);
            }
        }
        (positions, quads)
    }

    fn double_sided(self) -> bool {
        self == Walls::SharedWallDoubleSided
    }
}

/// Which room the camera stands in. Both cameras look away from the shared wall (the lit one
/// at x = 0, the dark one at its far wall): a single-sided wall coincident with another is
/// culled wrongly for camera rays (a separate bug, fixed elsewhere), and a leak into the dark
/// room lights its far wall too.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Room {
    Lit,
    Dark,
}

/// Where a root node puts the rooms: `translation` metres and a uniform `scale`, written to
/// the file as the f32s' shortest decimal text.
#[derive(Clone, Copy, Debug)]
pub struct Placement {
    pub translation: [f32; 3],
    pub scale: f32,
}

impl Placement {
    /// The translation the file states: its decimal text (which need not be the f32's exact
    /// value: 0.6 × 6.4e6 in f32 is 3,840,000.25, written "3840000.3") as the nearest f64, as
    /// the loader reads it.
    pub fn translation_in_file(&self) -> [f64; 3] {
        self.translation.map(|v| format!("{v:?}").parse().unwrap())
    }

    /// The scale the file states, as the nearest f64 to its decimal text.
    pub fn scale_in_file(&self) -> f64 {
        format!("{:e}", self.scale).parse().unwrap()
    }
}

/// The lamp's position in the lit room, local metres.
pub const LAMP: [f32; 3] = [0.5, 0.7, 0.5];

/// Writes `dir/rooms.gltf`: `walls` under a root node placed by `placement`, with a
/// perspective camera (vertical field of view 1.4 rad) in `room` and a point lamp in the lit
/// room, both children of the root. The lamp's intensity grows with the scale squared, so
/// every radiance in the image is the same at every scale.
pub fn write_rooms(dir: &Path, walls: Walls, room: Room, placement: Placement) -> PathBuf {
    let (positions, quads) = walls.geometry();
    let mut bin: Vec<u8> = positions
        .iter()
        .flat_map(|p| p.to_array())
        .flat_map(f32::to_le_bytes)
        .collect();
    let index_offset = bin.len();
    let indices: Vec<u32> = quads
        .iter()
        .flat_map(|q| [q[0], q[1], q[2], q[0], q[2], q[3]])
        .collect();
    bin.extend(indices.iter().flat_map(|i| i.to_le_bytes()));
    let (lo, hi) = positions
        .iter()
        .fold((Vec3::INFINITY, Vec3::NEG_INFINITY), |(lo, hi), &p| {
            (lo.min(p), hi.max(p))
        });
    let hex: String = bin.iter().map(|b| format!("%{b:02X}")).collect();
    // glTF cameras look down their node's −Z: a quarter turn about +Y looks along −X (lit
    // room, towards x = 0), a quarter turn the other way along +X (dark room, its far wall).
    let h = std::f32::consts::FRAC_1_SQRT_2;
    let (eye, rotation) = match room {
        Room::Lit => ([0.8, 0.5, 0.5], [0.0, h, 0.0, h]),
        Room::Dark => ([walls.dark_room_x() + 0.2, 0.5, 0.5], [0.0, -h, 0.0, h]),
    };
    let s = placement.scale;
    // Radiant intensity 2 s² / (4π) W/sr, as candela under the loader's 683 lm/W.
    let candela = 683.0 * 2.0 * f64::from(s).powi(2) / (4.0 * std::f64::consts::PI);
    let json = format!(
        r#"{{"asset":{{"version":"2.0"}},
        "extensionsUsed":["KHR_lights_punctual"],
        "extensions":{{"KHR_lights_punctual":{{"lights":[{{"type":"point","intensity":{candela:e}}}]}}}},
        "buffers":[{{"byteLength":{len},"uri":"data:application/octet-stream,{hex}"}}],
        "bufferViews":[{{"buffer":0,"byteLength":{index_offset}}},
                       {{"buffer":0,"byteOffset":{index_offset},"byteLength":{index_len}}}],
        "accessors":[{{"bufferView":0,"componentType":5126,"count":{vertices},"type":"VEC3",
                       "min":{lo:?},"max":{hi:?}}},
                     {{"bufferView":1,"componentType":5125,"count":{index_count},"type":"SCALAR"}}],
        "materials":[{{"pbrMetallicRoughness":{{"baseColorFactor":[0.7,0.7,0.7,1.0],"metallicFactor":0.0,"roughnessFactor":1.0}},"doubleSided":{double}}}],
        "meshes":[{{"primitives":[{{"attributes":{{"POSITION":0}},"indices":1,"material":0}}]}}],
        "cameras":[{{"type":"perspective","perspective":{{"yfov":1.4,"znear":0.001,"aspectRatio":1.0}}}}],
        "nodes":[{{"translation":{t:?},"scale":[{s:e},{s:e},{s:e}],"children":[1,2,3]}},
                 {{"mesh":0}},
                 {{"camera":0,"translation":{eye:?},"rotation":{rotation:?}}},
                 {{"translation":{LAMP:?},"extensions":{{"KHR_lights_punctual":{{"light":0}}}}}}],
        "scenes":[{{"nodes":[0]}}],"scene":0}}"#,
        len = bin.len(),
        index_len = bin.len() - index_offset,
        vertices = positions.len(),
        index_count = indices.len(),
        lo = lo.to_array(),
        hi = hi.to_array(),
        double = walls.double_sided(),
        t = placement.translation,
    );
    let path = dir.join("rooms.gltf");
    std::fs::write(&path, json).unwrap();
    path
}
