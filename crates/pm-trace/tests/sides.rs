//! Emitter sidedness and back-face culling against closed forms: a two-sided quad emits
//! twice a one-sided one's power, half of it to each side; its irradiance is the same on
//! both sides (the rectangle's configuration factor); camera rays pass through the backs of
//! single-sided faces while photon and shadow rays do not.

mod common;

use pm_trace::Partitioner;
use pm_trace::glam::Vec3;
use pm_trace::{
    AreaLight, Light, Material, PhotonKind, PointLight, Ray, RayKind, Rng, Scene, Sides, SingleMap, Surface,
    TraceOptions, trace_photons,
};
use std::f64::consts::PI;

/// The unit quad at height `y` in x, z ∈ [0, 1], its front facing +y.
fn quad_light(y: f32, radiance: Vec3) -> AreaLight {
    AreaLight::quad(Vec3::new(0.0, y, 0.0), Vec3::Z, Vec3::X, radiance)
}

/// Configuration factor from a point to a parallel rectangle `a × b` at distance `h`, the
/// point on the normal through one of its corners (Howell's catalogue, C-11).
fn corner_factor(a: f64, b: f64, h: f64) -> f64 {
    let (x, y) = (a / h, b / h);
    let (sx, sy) = ((1.0 + x * x).sqrt(), (1.0 + y * y).sqrt());
    (x / sx * (y / sx).atan() + y / sy * (x / sy).atan()) / (2.0 * PI)
}

#[test]
fn two_sided_quad_emits_twice_the_power_half_to_each_side() {
    let radiance = Vec3::new(2.0, 1.0, 0.5);
    let one = quad_light(0.5, radiance);
    let two = quad_light(0.5, radiance).with_sides(Sides::Double);
    // Φ = π L A per emitting side, A = 1 m².
    let expected = radiance * std::f32::consts::PI;
    assert!((one.power() - expected).abs().max_element() < 1e-5);
    assert!((two.power() - 2.0 * expected).abs().max_element() < 1e-5);
    // Photons of the one-sided quad all leave upwards; of the two-sided one, half downwards.
    let n = 100_000u32;
    for (light, expected_down) in [(&one, 0.0), (&two, 0.5)] {
        let down = (0..n)
            .filter(|&i| {
                let e = light.emit(&mut Rng::new(3, i as u64));
                assert_eq!(e.weight, Vec3::ONE);
                e.ray.direction.y < 0.0
            })
            .count() as f64
            / n as f64;
        let se = (0.25 / n as f64).sqrt();
        assert!(
            (down - expected_down).abs() <= 4.0 * se,
            "{down} of the photons go down, expected {expected_down} ± 4 × {se}"
        );
    }
}

#[test]
fn two_sided_quad_in_a_black_box_stores_its_doubled_power() {
    // A unit cube of black walls around a two-sided quad across its middle: every photon is
    // absorbed at its first hit, so the stored power is the light's power, split evenly
    // between the halves above and below the quad within the binomial noise.
    let (corners, faces) = common::unit_box();
    let radiance = Vec3::splat(1.5);
    let scene = Scene::builder()
        .mesh(&corners, &faces, Surface::diffuse(Vec3::ZERO))
        .light(
            AreaLight::quad(Vec3::new(0.25, 0.5, 0.25), Vec3::Z * 0.5, Vec3::X * 0.5, radiance)
                .with_sides(Sides::Double),
        )
        .build()
        .unwrap();
    let maps = SingleMap.partition(scene.clone()).unwrap().assignment().clone();
    let n = 50_000u32;
    let traced = trace_photons(
        &scene,
        &maps,
        &TraceOptions {
            photons: n,
            seed: 4,
            ..TraceOptions::default()
        },
    )
    .unwrap();
    let power = 2.0 * PI * 1.5 * 0.25;
    let stored = common::stored_power(&traced, Some(PhotonKind::Direct));
    assert!((stored.x - power).abs() < 1e-4 * power, "{stored} vs {power}");
    let below = traced.photons(0).iter().filter(|p| p.position.y < 0.5).count() as f64 / n as f64;
    let se = (0.25 / n as f64).sqrt();
    assert!(
        (below - 0.5).abs() <= 4.0 * se,
        "{below} below, expected 0.5 ± 4 × {se}"
    );
}

/// Irradiance at `point` with normal `normal` from `light`, by `n` shadow-ray samples (no
/// occluders): the mean and its standard error.
fn sampled_irradiance(light: &dyn Light, point: Vec3, normal: Vec3, n: u32) -> (f64, f64) {
    let (mut sum, mut sum2) = (0.0f64, 0.0f64);
    for i in 0..n {
        let e = light
            .sample_incident(point, normal, &mut Rng::new(7, i as u64))
            .map_or(0.0, |s| {
                (s.radiance_over_pdf.x * normal.dot(s.direction).max(0.0)) as f64
            });
        sum += e;
        sum2 += e * e;
    }
    let mean = sum / n as f64;
    (mean, ((sum2 / n as f64 - mean * mean).max(0.0) / n as f64).sqrt())
}

#[test]
fn two_sided_emitter_irradiance_is_the_configuration_factor_on_both_sides() {
    // A point at distance h on the axis of the unit quad sees four 0.5 × 0.5 rectangles,
    // each with the point over a corner: E = π L · 4 F(0.5, 0.5, h).
    let h = 0.75f64;
    let radiance = 2.0f32;
    let truth = PI * radiance as f64 * 4.0 * corner_factor(0.5, 0.5, h);
    let two = quad_light(0.0, Vec3::splat(radiance)).with_sides(Sides::Double);
    let one = quad_light(0.0, Vec3::splat(radiance));
    let above = Vec3::new(0.5, h as f32, 0.5);
    let below = Vec3::new(0.5, -h as f32, 0.5);
    let n = 200_000;
    for (point, normal) in [(above, Vec3::NEG_Y), (below, Vec3::Y)] {
        let (e, se) = sampled_irradiance(&two, point, normal, n);
        assert!(
            (e - truth).abs() <= 4.0 * se && se < 0.01 * truth,
            "two-sided at {point}: {e} ± {se}, closed form {truth}"
        );
    }
    let (e, se) = sampled_irradiance(&one, above, Vec3::NEG_Y, n);
    assert!(
        (e - truth).abs() <= 4.0 * se,
        "one-sided above: {e} ± {se} vs {truth}"
    );
    assert_eq!(sampled_irradiance(&one, below, Vec3::Y, 1000).0, 0.0);
}

/// Two parallel quads across the z axis: the near one at z = 1 with `near`, its front facing
/// +z (away from the origin), and a grey one at z = 2.
fn two_quads(near: Surface) -> Scene {
    // Counter-clockwise seen from +z: the front faces +z.
    let quad = |z: f32| {
        [
            Vec3::new(-1.0, -1.0, z),
            Vec3::new(1.0, -1.0, z),
            Vec3::new(1.0, 1.0, z),
            Vec3::new(-1.0, 1.0, z),
        ]
    };
    Scene::builder()
        .mesh(&quad(1.0), &[[0u32, 1, 2, 3]], near)
        .mesh(&quad(2.0), &[[0u32, 1, 2, 3]], Surface::diffuse(Vec3::splat(0.5)))
        .light(PointLight::new(Vec3::new(0.0, 0.0, -1.0), Vec3::ONE))
        .build()
        .unwrap()
}

/// From the origin along +z: the near quad's back at t = 1.
const TOWARDS_BACK: Ray = Ray {
    origin: Vec3::new(0.1, 0.2, 0.0),
    direction: Vec3::Z,
};
/// From z = 1.5 along −z: the near quad's front at t = 0.5.
const TOWARDS_FRONT: Ray = Ray {
    origin: Vec3::new(0.1, 0.2, 1.5),
    direction: Vec3::NEG_Z,
};

#[test]
fn back_face_of_a_single_sided_face_is_transparent_to_camera_rays_only() {
    let scene = two_quads(Surface::diffuse(Vec3::ONE).with_sides(Sides::Single));
    let other = scene
        .intersect(&TOWARDS_BACK, f32::INFINITY, RayKind::Other)
        .unwrap();
    assert!(
        !other.front_face && (other.t - 1.0).abs() < 1e-5,
        "photon/path rays stop at its back"
    );
    let camera = scene
        .intersect(&TOWARDS_BACK, f32::INFINITY, RayKind::Camera)
        .unwrap();
    assert!(
        (camera.t - 2.0).abs() < 1e-5,
        "camera rays see through its back: t {}",
        camera.t
    );
    // The grey quad is front-emitting (not culled): its back is seen.
    assert!(!camera.front_face);
    // Seen from the front, camera rays stop at it.
    let front = scene
        .intersect(&TOWARDS_FRONT, f32::INFINITY, RayKind::Camera)
        .unwrap();
    assert!(front.front_face && (front.t - 0.5).abs() < 1e-5);
    // Shadow rays are blocked by it from either side.
    assert!(scene.occluded(TOWARDS_BACK.origin, TOWARDS_FRONT.origin));
    // Front-emitting (the default) and double-sided faces are seen from both sides.
    for sides in [Sides::Front, Sides::Double] {
        let scene = two_quads(Surface::diffuse(Vec3::ONE).with_sides(sides));
        let hit = scene
            .intersect(&TOWARDS_BACK, f32::INFINITY, RayKind::Camera)
            .unwrap();
        assert!(
            !hit.front_face && (hit.t - 1.0).abs() < 1e-5,
            "{sides:?}: t {}",
            hit.t
        );
    }
}

#[test]
fn hits_see_emission_on_the_sides_that_emit() {
    let emitter = |sides: Sides| Surface {
        material: Material::Lambertian { albedo: Vec3::ZERO },
        emission: Vec3::splat(3.0),
        camera_visible: true,
        sides,
    };
    for (sides, back) in [(Sides::Front, 0.0), (Sides::Single, 0.0), (Sides::Double, 3.0)] {
        let scene = two_quads(emitter(sides));
        let hit = scene
            .intersect(&TOWARDS_FRONT, f32::INFINITY, RayKind::Other)
            .unwrap();
        assert!(hit.front_face);
        assert_eq!(scene.emission(&hit), Vec3::splat(3.0), "{sides:?} front");
        let hit = scene
            .intersect(&TOWARDS_BACK, f32::INFINITY, RayKind::Other)
            .unwrap();
        assert!(!hit.front_face && (hit.t - 1.0).abs() < 1e-5);
        assert_eq!(scene.emission(&hit), Vec3::splat(back), "{sides:?} back");
    }
}
