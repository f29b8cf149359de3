//! Two rooms modelled on one wall plane: each an inward box, the two sharing the plane x = 0
//! with no thickness between them, one lit by a point light, the camera in the other. With
//! glTF's default single-sided surfaces the camera must not see through the shared wall: the
//! lit room's wall shows its back to the camera (culled) at the very distance where the dark
//! room's wall shows its front (kept). The dark room is exactly black in every mode, with
//! single- and double-sided walls, and the camera ray stops on the dark room's own wall.

use photon_maps::render::glam::Vec3;
use photon_maps::render::{EstimatorKind, FinalGatherOptions, Image, Mode, RenderSettings, Renderer};
use photon_maps::trace::scenes::box_mesh::{Facing, box_mesh};
use photon_maps::trace::{
    Camera, Contact, CreaseAngle, Partitioned, Partitioner, PointLight, Ray, RayKind, Scene, Sides, Surface,
};

/// The lit room spans x ∈ [−1, 0], the dark one x ∈ [0, 1]; both are unit boxes facing in,
/// of the given sides. The camera stands in the dark room looking at the shared wall.
fn rooms(sides: Sides) -> Scene {
    let lit_white = Surface::diffuse(Vec3::splat(0.7)).with_sides(sides);
    let dark_white = Surface::diffuse(Vec3::splat(0.5)).with_sides(sides);
    let (lit, lit_faces) = box_mesh(
        Vec3::new(-1.0, 0.0, 0.0),
        Vec3::new(0.0, 1.0, 1.0),
        Facing::Inward,
    );
    let (dark, dark_faces) = box_mesh(Vec3::ZERO, Vec3::ONE, Facing::Inward);
    Scene::builder()
        .mesh(&lit, &lit_faces, lit_white)
        .mesh(&dark, &dark_faces, dark_white)
        .light(PointLight::new(Vec3::new(-0.5, 0.7, 0.5), Vec3::splat(2.0)))
        .camera(Camera::new(
            Vec3::new(0.9, 0.5, 0.5),
            Vec3::new(0.0, 0.45, 0.5),
            Vec3::Y,
            1.6,
        ))
        .build()
        .unwrap()
}

fn render(partitioned: &Partitioned, mode: Mode) -> Image {
    let settings = RenderSettings {
        width: 16,
        height: 16,
        samples_per_pixel: 2,
        photons: 4_000,
        k: 30,
        mode,
        seed: 5,
        threads: 2,
        final_gather: FinalGatherOptions {
            gather_rays: 4,
            ..FinalGatherOptions::default()
        },
        ..RenderSettings::default()
    };
    Renderer::new(EstimatorKind::GeometryCube, settings)
        .render(partitioned, &())
        .unwrap()
        .image
}

#[test]
fn a_camera_ray_stops_on_its_own_rooms_wall_where_the_other_rooms_back_is_culled() {
    for sides in [Sides::Single, Sides::Double, Sides::Front] {
        let scene = rooms(sides);
        // Straight at the shared wall, and at a slant near a corner (where the rooms'
        // triangles meet and a tie between the coincident walls is likeliest).
        for target in [Vec3::new(0.0, 0.5, 0.5), Vec3::new(0.0, 0.01, 0.99)] {
            let origin = Vec3::new(0.9, 0.5, 0.5);
            let ray = Ray {
                origin,
                direction: (target - origin).normalize(),
            };
            let hit = scene.intersect(&ray, f32::INFINITY, RayKind::Camera).unwrap();
            assert!(hit.position.x.abs() < 1e-5, "{sides:?}: hit at {}", hit.position);
            assert!(
                hit.front_face || sides != Sides::Single,
                "{sides:?}: a culled back face was kept"
            );
            if sides == Sides::Single {
                // The front the camera meets there is the dark room's (albedo 0.5).
                let albedo = scene.albedo_at(&hit);
                assert_eq!(
                    albedo,
                    Vec3::splat(0.5),
                    "{sides:?}: the lit room's wall was seen"
                );
            }
        }
    }
}

#[test]
fn the_dark_room_behind_a_shared_wall_is_exactly_black_in_every_mode() {
    for sides in [Sides::Single, Sides::Double] {
        let scene = rooms(sides);
        let crease = CreaseAngle::default().partition(scene.clone()).unwrap();
        let contact = Contact::default().partition(scene.clone()).unwrap();
        for mode in Mode::ALL {
            for (maps, partitioned) in [("crease", &crease), ("contact", &contact)] {
                let image = render(partitioned, mode);
                let lit = image.pixels().iter().filter(|p| **p != Vec3::ZERO).count();
                let brightest = image.pixels().iter().map(|p| p.max_element()).fold(0.0, f32::max);
                assert_eq!(
                    lit, 0,
                    "{sides:?}, {mode}, {maps} maps: {lit} lit pixels (brightest {brightest})"
                );
            }
        }
    }
}
