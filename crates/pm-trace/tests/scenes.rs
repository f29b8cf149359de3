//! The built-in scenes: each builds, its meshes pass `validate()`, its camera looks at it,
//! its lights have power, and its geometry is as the report describes.

use pm_trace::glam::Vec3;
use pm_trace::{Material, Ray, RayKind, Scene, scenes};

fn hit_surface_albedo(scene: &Scene, ray: &Ray, kind: RayKind) -> Option<Vec3> {
    let hit = scene.intersect(ray, f32::INFINITY, kind)?;
    match scene.material(&hit) {
        Material::Lambertian { albedo } => Some(*albedo),
        _ => None,
    }
}

#[test]
fn every_built_in_scene_builds_validates_and_is_seen_by_its_camera() {
    for name in scenes::NAMES {
        let scene = scenes::build(name).unwrap_or_else(|e| panic!("{name}: {e}"));
        for m in scene.meshes() {
            m.half_edge_mesh()
                .validate()
                .unwrap_or_else(|e| panic!("{name}: {e}"));
        }
        assert!(!scene.lights().is_empty(), "{name}");
        for light in scene.lights() {
            assert!(light.power().min_element() > 0.0, "{name}: {light:?}");
        }
        // Left and right of the centre: the rooms' centre column looks into their 2 cm wall gap.
        for u in [0.3, 0.7] {
            let ray = scene.camera().ray(u, 0.5, 1.0);
            assert!(
                scene.intersect(&ray, f32::INFINITY, RayKind::Camera).is_some(),
                "{name}: camera sees nothing"
            );
        }
    }
}

#[test]
fn cornell_box_has_the_measured_size_colours_and_a_downward_light() {
    let scene = scenes::build("cornell-box").unwrap();
    let b = scene.bounds();
    assert!(
        (b.max - Vec3::new(0.556, 0.5488, 0.5592)).abs().max_element() < 1e-4
            && b.min.abs().max_element() < 1e-6
    );
    let cam = scene.camera();
    assert!((cam.position() - Vec3::new(0.278, 0.273, -0.8)).length() < 1e-6);
    let from = Vec3::new(0.278, 0.3, 0.3);
    let red = hit_surface_albedo(&scene, &Ray::new(from, Vec3::X), RayKind::Other).unwrap();
    let green = hit_surface_albedo(&scene, &Ray::new(from, -Vec3::X), RayKind::Other).unwrap();
    assert_eq!(red, Vec3::new(0.63, 0.065, 0.05));
    assert_eq!(green, Vec3::new(0.14, 0.45, 0.091));
    // Straight up from under the light: the emitting side faces down.
    let up = Ray::new(Vec3::new(0.278, 0.3, 0.28), Vec3::Y);
    let hit = scene.intersect(&up, f32::INFINITY, RayKind::Camera).unwrap();
    assert_eq!(scene.emission(&hit), Vec3::new(17.0, 12.0, 4.0));
    // The open front lets camera rays out.
    assert!(
        scene
            .intersect(&Ray::new(from, -Vec3::Z), f32::INFINITY, RayKind::Other)
            .is_none()
    );
}

#[test]
fn rooms_hide_their_front_walls_from_the_camera_only() {
    for name in ["lit-unlit-rooms", "colored-rooms", "touching-rooms"] {
        let scene = scenes::build(name).unwrap();
        // A camera ray into the left room passes the front wall and hits the back wall at z = 1.
        let ray = Ray::new(Vec3::new(0.3, 0.3, -1.0), Vec3::Z);
        let cam = scene.intersect(&ray, f32::INFINITY, RayKind::Camera).unwrap();
        assert!((cam.position.z - 1.0).abs() < 1e-4, "{name}: {:?}", cam.position);
        let other = scene.intersect(&ray, f32::INFINITY, RayKind::Other).unwrap();
        assert!(other.position.z.abs() < 1e-4, "{name}");
        // The dividing wall is 2 cm thick, on the image's middle column.
        let mid = scene.camera().ray(0.5, 0.5, 1.0);
        assert!((mid.direction.x).abs() < 1e-6 && (scene.camera().position().x - 1.01).abs() < 1e-6);
    }
    // Colored rooms: a red light on the left, a blue one on the right.
    let scene = scenes::build("colored-rooms").unwrap();
    let powers: Vec<Vec3> = scene.lights().iter().map(|l| l.power()).collect();
    assert!(powers[0].x > powers[0].z && powers[1].z > powers[1].x);
}

#[test]
fn accordion_facets_are_quarter_metre_by_metre_at_right_angles() {
    let scene = scenes::build("accordion").unwrap();
    let mesh = scene.meshes()[0].half_edge_mesh();
    assert_eq!(mesh.face_count(), 8);
    for f in mesh.faces() {
        assert!((mesh.face_area(f) - 0.25).abs() < 1e-5);
    }
    let creases: Vec<f32> = mesh
        .faces()
        .flat_map(|f| mesh.face_half_edges(f).filter_map(|he| mesh.crease_angle(he)))
        .collect();
    assert_eq!(creases.len(), 14, "7 folds, two half-edges each");
    assert!(
        creases
            .iter()
            .all(|a| (a - std::f32::consts::FRAC_PI_2).abs() < 1e-4)
    );
}
