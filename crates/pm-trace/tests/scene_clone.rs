//! Scenes and their builders clone, and a scene can be re-aimed without a rebuild: a second
//! viewpoint or a second partition of the same scene is cheap.

use pm_trace::glam::Vec3;
use pm_trace::{
    Camera, CreaseAngle, Partitioner, PointLight, Ray, RayKind, Scene, SceneError, Surface, scenes,
};

#[test]
fn scene_builder_clones_with_its_lights() {
    let floor = [
        Vec3::new(-1.0, 0.0, -1.0),
        Vec3::new(-1.0, 0.0, 1.0),
        Vec3::new(1.0, 0.0, 1.0),
        Vec3::new(1.0, 0.0, -1.0),
    ];
    let builder = Scene::builder()
        .mesh(&floor, &[[0u32, 1, 2, 3]], Surface::diffuse(Vec3::splat(0.5)))
        .light(PointLight::new(Vec3::new(0.0, 2.0, 0.0), Vec3::splat(100.0)));
    let copy = builder.clone();
    let a = builder
        .light(PointLight::new(Vec3::new(0.5, 2.0, 0.0), Vec3::splat(50.0)))
        .build()
        .unwrap();
    let b = copy.build().unwrap();
    assert_eq!(a.lights().len(), 2);
    assert_eq!(b.lights().len(), 1, "the copy keeps its own lights");
    assert_eq!(b.lights()[0].power(), Vec3::splat(100.0));
}

#[test]
fn scene_clones_and_takes_another_camera() {
    let scene = scenes::build("cornell-box").unwrap();
    let clone = scene.clone();
    assert_eq!(clone.part_count(), scene.part_count());
    assert_eq!(clone.lights().len(), scene.lights().len());
    assert_eq!(
        CreaseAngle::default()
            .partition(clone.clone())
            .unwrap()
            .assignment()
            .clone(),
        CreaseAngle::default()
            .partition(scene.clone())
            .unwrap()
            .assignment()
            .clone()
    );
    // The clone answers ray queries as the original does.
    let ray = Ray::new(scene.bounds().center(), Vec3::new(0.3, -1.0, 0.2).normalize());
    assert_eq!(
        clone.intersect(&ray, f32::INFINITY, RayKind::Other),
        scene.intersect(&ray, f32::INFINITY, RayKind::Other)
    );

    let eye = scene.camera().position() + Vec3::new(0.1, 0.0, 0.0);
    let camera = Camera::new(eye, scene.bounds().center(), Vec3::Y, 0.8);
    let moved = scene.clone().with_camera(camera).unwrap();
    assert_eq!(*moved.camera(), camera);
    assert_ne!(*scene.camera(), camera, "the original keeps its camera");

    let broken = Camera::new(Vec3::NAN, Vec3::ZERO, Vec3::Y, 0.8);
    assert!(matches!(
        scene.with_camera(broken),
        Err(SceneError::InvalidCamera { .. })
    ));
}
