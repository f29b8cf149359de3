//! Values that made black or absurd images instead of errors: a light with no direction, a
//! field of view of a full turn, geometry at the edge of f32's useful range. Each is refused
//! when the scene is built, naming what is wrong.

use pm_trace::glam::Vec3;
use pm_trace::{Camera, DirectionalLight, PointLight, Scene, SceneError, SpotLight, Surface};

fn floor(at: Vec3) -> [Vec3; 4] {
    [
        at,
        at + Vec3::new(0.0, 0.0, 1.0),
        at + Vec3::new(1.0, 0.0, 1.0),
        at + Vec3::new(1.0, 0.0, 0.0),
    ]
}

fn grey() -> Surface {
    Surface::diffuse(Vec3::splat(0.5))
}

#[test]
fn a_light_without_a_direction_is_refused_not_pointed_down() {
    let lit = |light: Box<dyn pm_trace::Light>| {
        Scene::builder()
            .mesh(&floor(Vec3::ZERO), &[[0u32, 1, 2, 3]], grey())
            .light(PointLight::new(Vec3::Y, Vec3::ONE))
            .boxed_light(light)
            .build()
    };
    for light in [
        Box::new(DirectionalLight::new(Vec3::ZERO, Vec3::ONE)) as Box<dyn pm_trace::Light>,
        Box::new(SpotLight::new(Vec3::Y, Vec3::ZERO, 0.5, Vec3::ONE)),
        Box::new(DirectionalLight::new(Vec3::splat(f32::NAN), Vec3::ONE)),
    ] {
        let err = lit(light).unwrap_err();
        assert!(matches!(err, SceneError::InvalidLight { light: 1, .. }), "{err}");
        assert!(err.to_string().contains("direction"), "{err}");
    }
    // A tiny but non-zero direction is a direction.
    assert!(
        lit(Box::new(DirectionalLight::new(
            Vec3::new(0.0, -1e-10, 0.0),
            Vec3::ONE
        )))
        .is_ok()
    );
}

#[test]
fn a_field_of_view_outside_zero_to_pi_is_refused() {
    let with_fov = |fov: f32| {
        Scene::builder()
            .mesh(&floor(Vec3::ZERO), &[[0u32, 1, 2, 3]], grey())
            .light(PointLight::new(Vec3::Y, Vec3::ONE))
            .camera(Camera::new(
                Vec3::new(0.5, 1.0, -1.0),
                Vec3::new(0.5, 0.0, 0.5),
                Vec3::Y,
                fov,
            ))
            .build()
    };
    // tan(fov/2) of 2π comes out a tiny positive number: it used to pass as a narrow view.
    for fov in [
        std::f32::consts::TAU,
        std::f32::consts::PI,
        0.0,
        -0.5,
        4.0,
        f32::NAN,
        f32::INFINITY,
    ] {
        match with_fov(fov) {
            Err(SceneError::InvalidCamera { reason }) => {
                assert!(reason.contains("field of view"), "{reason}")
            }
            other => panic!("fov {fov}: {:?}", other.map(|_| ())),
        }
    }
    for fov in [1e-3, 1.0, 3.1] {
        assert!(with_fov(fov).is_ok(), "fov {fov}");
    }
}

#[test]
fn geometry_at_the_photon_coordinate_limit_is_refused() {
    let at = |x: f32| {
        Scene::builder()
            .mesh(&floor(Vec3::new(x, 0.0, 0.0)), &[[0u32, 1, 2, 3]], grey())
            .mesh(&floor(Vec3::ZERO), &[[0u32, 1, 2, 3]], grey())
            .light(PointLight::new(Vec3::Y, Vec3::ONE))
            .build()
    };
    for x in [1e18, -1e18, 3e38] {
        let err = at(x).map(|_| ()).unwrap_err();
        assert!(matches!(err, SceneError::GeometryOutOfRange { .. }), "{x}: {err}");
    }
    assert!(at(1e6).is_ok());
}
