//! Splitting faces along contacts keeps their vertex attributes: a floor with vertex colours
//! that are a linear function of position, tilted vertex normals and a texture, crossed by a
//! wall standing on it, is split by [`Contact`]; at every point the albedo equals the closed
//! form (factor × colour(p) × texel) and the shading normal is what it was before the split.

use std::sync::Arc;

use pm_trace::glam::{Vec2, Vec3};
use pm_trace::{
    Contact, Partitioner, PointLight, Ray, RayKind, Sampler, Scene, Surface, Texture, VertexAttributes, Wrap,
};

/// The floor's colour at `p`, linear in position (so interpolation over any triangle is exact).
fn colour(p: Vec3) -> Vec3 {
    Vec3::new(0.5 + 0.3 * p.x, 0.5 + 0.2 * p.z, 0.7)
}

/// A 2 m floor of two triangles with colours, normals and a two-texel texture (left texel
/// white, right texel grey 50 % in linear units), and a wall standing on it along x = 0.3.
fn scene() -> Scene {
    let floor = [
        Vec3::new(-1.0, 0.0, -1.0),
        Vec3::new(-1.0, 0.0, 1.0),
        Vec3::new(1.0, 0.0, 1.0),
        Vec3::new(1.0, 0.0, -1.0),
    ];
    let normals = floor.map(|p| Vec3::new(0.3 * p.x, 1.0, 0.2 * p.z).normalize());
    // sRGB 188 decodes to about 0.5029 (IEC 61966-2-1).
    let texture = Arc::new(Texture::from_srgb8(2, 1, vec![[255; 3], [188; 3]]).unwrap());
    let sampler = Sampler {
        wrap_u: Wrap::ClampToEdge,
        wrap_v: Wrap::ClampToEdge,
        nearest: true,
    };
    let wall = [
        Vec3::new(0.3, 0.0, -1.0),
        Vec3::new(0.3, 1.0, -1.0),
        Vec3::new(0.3, 1.0, 1.0),
        Vec3::new(0.3, 0.0, 1.0),
    ];
    Scene::builder()
        .attributed_mesh(
            &floor,
            &[[0, 1, 2], [0, 2, 3]],
            Surface::diffuse(Vec3::splat(0.9)),
            VertexAttributes {
                uvs: Some(floor.iter().map(|p| Vec2::new((p.x + 1.0) / 2.0, 0.5)).collect()),
                colors: Some(floor.iter().map(|&p| colour(p)).collect()),
                normals: Some(normals.to_vec()),
                base_color_texture: Some((texture, sampler)),
                ..VertexAttributes::default()
            },
        )
        .mesh(&wall, &[[0u32, 1, 2, 3]], Surface::diffuse(Vec3::splat(0.5)))
        .light(PointLight::new(Vec3::new(-0.5, 0.8, 0.0), Vec3::splat(10.0)))
        .build()
        .unwrap()
}

/// The floor hit straight below `(x, z)`.
fn floor_hit(scene: &Scene, x: f32, z: f32) -> pm_trace::Hit {
    let hit = scene
        .intersect(&Ray::new(Vec3::new(x, 0.5, z), Vec3::NEG_Y), 10.0, RayKind::Other)
        .unwrap();
    assert!(hit.position.y.abs() < 1e-5);
    hit
}

#[test]
fn split_floor_keeps_colours_texture_and_normals() {
    let before = scene();
    let floor_parts = before.meshes()[0].half_edge_mesh().face_count();
    let partitioned = Contact::default().partition(before.clone()).unwrap();
    let split = partitioned.scene();
    let split_parts = split.meshes()[0].half_edge_mesh().face_count();
    assert!(
        split_parts > floor_parts,
        "the wall must split the floor ({split_parts} pieces)"
    );
    let mut checked = 0;
    for i in 0..40 {
        for j in 0..40 {
            let (x, z) = (-0.975 + i as f32 * 0.05, -0.975 + j as f32 * 0.05);
            let hit = floor_hit(split, x, z);
            let texel = if x < 0.0 { 1.0 } else { 0.502_886_5 };
            let truth = 0.9 * colour(hit.position) * texel;
            let albedo = split.albedo_at(&hit);
            assert!(
                (albedo - truth).abs().max_element() < 1e-4,
                "({x}, {z}): albedo {albedo}, closed form {truth}"
            );
            let old = before.shading_normal_at(&floor_hit(&before, x, z));
            let new = split.shading_normal_at(&hit);
            assert!(
                (old - new).length() < 1e-5,
                "({x}, {z}): normal {new}, before {old}"
            );
            assert!(
                (new - Vec3::Y).length() > 1e-3,
                "({x}, {z}): the normal is interpolated"
            );
            checked += 1;
        }
    }
    assert_eq!(checked, 1600);
}
