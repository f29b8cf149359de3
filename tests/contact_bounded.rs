//! The contact split is bounded before its output is paid for: inputs that cut themselves into
//! grids (near-copies of one mesh, thousands of squares turned by a hair) are refused with a
//! typed error while the faces are cut, and geometry flattened to zero thickness (solids scaled
//! to a plane) is split without blowing up. Each case runs in well under a second.

use photon_maps::trace::glam::Vec3;
use photon_maps::trace::scenes::box_mesh::{Facing, box_mesh};
use photon_maps::trace::{
    Camera, Contact, PartitionError, Partitioner, PointLight, Rng, Scene, SceneBuilder, Surface,
};

fn finish(builder: SceneBuilder) -> Scene {
    builder
        .light(PointLight::new(Vec3::new(0.5, 0.5, 2.0), Vec3::ONE))
        .camera(Camera::new(Vec3::new(0.0, 0.0, 5.0), Vec3::ZERO, Vec3::Y, 1.0))
        .build()
        .unwrap()
}

fn white() -> Surface {
    Surface::diffuse(Vec3::splat(0.5))
}

/// 51 copies of a room with a box in it, each 10⁻⁴ of the room's size from the last: every
/// face comes within the gap of its 50 copies, which cut it into a 50 × 50 grid (1.5 million
/// pieces from 612 faces, 53 s and 2.6 GB before the bound; refused in 0.15 s now).
#[test]
fn near_copies_of_a_room_are_refused_while_they_are_cut() {
    let mut builder = Scene::builder();
    for i in 0..51 {
        let o = Vec3::splat(i as f32 * 1e-4);
        let (room, room_faces) = box_mesh(o, o + Vec3::ONE, Facing::Inward);
        let (block, block_faces) = box_mesh(
            o + Vec3::new(0.3, 0.0, 0.3),
            o + Vec3::new(0.6, 0.3, 0.6),
            Facing::Outward,
        );
        builder = builder
            .mesh(&room, &room_faces, white())
            .mesh(&block, &block_faces, white());
    }
    let error = Contact::default().partition(finish(builder)).unwrap_err();
    assert!(matches!(error, PartitionError::Split(_)), "{error:?}");
    let message = error.to_string();
    assert!(message.contains("more than 100000 pieces"), "{message}");
}

/// 3,000 squares, each turned 10⁻⁷ rad from the last about their common centre: every pair
/// overlaps in one plane, so the cut segments alone pass the bound.
#[test]
fn squares_turned_by_a_hair_are_refused() {
    let mut builder = Scene::builder();
    for i in 0..3000 {
        let (s, c) = (i as f32 * 1e-7).sin_cos();
        let corners: Vec<Vec3> = [(-1.0f32, -1.0f32), (1.0, -1.0), (1.0, 1.0), (-1.0, 1.0)]
            .iter()
            .map(|&(x, y)| Vec3::new(c * x - s * y, s * x + c * y, 0.0))
            .collect();
        builder = builder.mesh(&corners, &[[0, 1, 2, 3]], white());
    }
    let error = Contact::default().partition(finish(builder)).unwrap_err();
    assert!(error.to_string().contains("pieces"), "{error}");
}

/// 100 overlapping boxes flattened onto one plane (a node scale of [1, 1, 0]): their side
/// faces have no area and their tops and bottoms all lie in z = 0, overlapping. The split
/// finishes, with a bounded number of parts.
#[test]
fn boxes_flattened_to_a_plane_are_split() {
    let mut rng = Rng::new(7, 0);
    let mut builder = Scene::builder();
    for _ in 0..100 {
        let corner = Vec3::new(rng.next_f32(), rng.next_f32(), rng.next_f32()) * 4.0;
        let (vertices, faces) = box_mesh(corner, corner + Vec3::ONE, Facing::Outward);
        let flat: Vec<Vec3> = vertices.iter().map(|p| Vec3::new(p.x, p.y, 0.0)).collect();
        builder = builder.mesh(&flat, &faces, white());
    }
    let partitioned = Contact::default().partition(finish(builder)).unwrap();
    assert!(partitioned.assignment().map_count() > 0);
    let parts = partitioned.scene().part_count();
    assert!(parts > 0 && parts < 100_000, "{parts} parts");
}
