//! Photon paths pass through near-specular surfaces as camera paths do
//! ([`pm_trace::bsdf::passes_through`]): a smooth metal panel (roughness 0.1) stores no photon,
//! and the light it reflects onto a diffuse floor arrives there as caustic photons, which the
//! final gather reads at its first hit (stored as indirect, that light was lost to it: the
//! camera's gather rays sample through the panel and find the point light never).

use pm_trace::bsdf::MetallicRoughness;
use pm_trace::glam::Vec3;
use pm_trace::{
    Camera, CreaseAngle, Partitioner, PhotonKind, PointLight, Scene, Surface, TraceOptions, trace_photons,
};

/// A diffuse floor (part 0) and, 1.5 m above it, a metal panel of `roughness` facing down, lit
/// by a point light below it: the panel reflects light down onto the floor.
fn panel_over_floor(roughness: f32) -> Scene {
    let floor = [
        Vec3::new(-2.0, 0.0, -2.0),
        Vec3::new(2.0, 0.0, -2.0),
        Vec3::new(2.0, 0.0, 2.0),
        Vec3::new(-2.0, 0.0, 2.0),
    ];
    let panel = [
        Vec3::new(-0.5, 1.5, -0.5),
        Vec3::new(0.5, 1.5, -0.5),
        Vec3::new(0.5, 1.5, 0.5),
        Vec3::new(-0.5, 1.5, 0.5),
    ];
    let metal = MetallicRoughness::new(Vec3::splat(0.9), 1.0, roughness).unwrap();
    Scene::builder()
        .mesh(
            &floor,
            &[[0, 2, 1], [0, 3, 2]],
            Surface::diffuse(Vec3::splat(0.5)),
        )
        .mesh(
            &panel,
            &[[0, 1, 2], [0, 2, 3]],
            Surface::metallic_roughness(metal),
        )
        .light(PointLight::new(Vec3::new(-0.8, 0.7, 0.0), Vec3::splat(50.0)))
        .camera(Camera::new(
            Vec3::new(0.0, 3.0, 3.0),
            Vec3::new(0.0, -1.0, -1.0).normalize(),
            Vec3::Y,
            1.0,
        ))
        .build()
        .unwrap()
}

#[test]
fn a_near_specular_panel_stores_no_photon_and_casts_caustics() {
    for (roughness, near_specular) in [(0.1, true), (0.6, false)] {
        let partitioned = CreaseAngle::default()
            .partition(panel_over_floor(roughness))
            .unwrap();
        let (scene, assignment) = (partitioned.scene(), partitioned.assignment());
        let options = TraceOptions {
            photons: 20_000,
            ..TraceOptions::default()
        };
        let traced = trace_photons(scene, assignment, &options).unwrap();
        let floor_map = assignment.map_of(pm_trace::PartId(0));
        let (mut on_panel, mut caustic_on_floor) = (0usize, 0usize);
        for (map, photons) in traced.photons_per_map().iter().enumerate() {
            if map as u32 == floor_map {
                caustic_on_floor += photons.iter().filter(|p| p.kind == PhotonKind::Caustic).count();
            } else {
                on_panel += photons.len();
            }
        }
        if near_specular {
            assert_eq!(on_panel, 0, "photons stored on a panel of roughness {roughness}");
            assert!(
                caustic_on_floor > 500,
                "only {caustic_on_floor} caustic photons reflected onto the floor"
            );
        } else {
            assert!(on_panel > 500, "a rough panel stores photons ({on_panel})");
            assert_eq!(
                caustic_on_floor, 0,
                "a rough panel reflects indirect light, not caustics"
            );
        }
    }
}
