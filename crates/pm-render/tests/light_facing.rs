//! A ceiling light turned round (its edges swapped, so it faces the ceiling it hangs under)
//! is visible in the render's statistics, not only as a dark image.

use pm_render::prelude::*;

/// A 2 m room open at the front, lit by a 0.5 m area light 0.5 mm under its ceiling, with the
/// light's edges in the given order (it emits towards `edge_u × edge_v`).
fn room(edge_u: Vec3, edge_v: Vec3) -> Scene {
    let c = [
        vec3(0.0, 0.0, 0.0),
        vec3(2.0, 0.0, 0.0),
        vec3(2.0, 0.0, 2.0),
        vec3(0.0, 0.0, 2.0),
        vec3(0.0, 2.0, 0.0),
        vec3(2.0, 2.0, 0.0),
        vec3(2.0, 2.0, 2.0),
        vec3(0.0, 2.0, 2.0),
    ];
    let walls = [
        [0u32, 1, 2, 3],
        [4, 7, 6, 5],
        [0, 3, 7, 4],
        [1, 5, 6, 2],
        [3, 2, 6, 7],
    ];
    Scene::builder()
        .mesh(&c, &walls, Surface::diffuse(Vec3::splat(0.7)))
        .area_light_quad(vec3(0.75, 1.9995, 0.75), edge_u, edge_v, Vec3::splat(10.0))
        .camera(Camera::new(
            vec3(1.0, 1.0, -1.5),
            vec3(1.0, 0.8, 1.0),
            Vec3::Y,
            1.0,
        ))
        .build()
        .unwrap()
}

#[test]
fn a_light_facing_its_ceiling_shows_in_the_render_stats() {
    let (x, z) = (vec3(0.5, 0.0, 0.0), vec3(0.0, 0.0, 0.5));
    let settings = RenderSettings {
        width: 24,
        height: 24,
        photons: 20_000,
        ..Default::default()
    };
    let render = |scene: &Scene| {
        Renderer::new(GeometryCube, settings)
            .render(&CreaseAngle::default().partition(scene.clone()).unwrap(), &())
            .unwrap()
    };
    let down = render(&room(x, z));
    let up = render(&room(z, x));
    // Facing down, no photon's first hit lies within 1 mm of the light; facing up, all do
    // (the ceiling is 0.5 mm away).
    assert_eq!(down.stats.near_light_fraction, 0.0);
    assert!(
        up.stats.near_light_fraction > 0.99,
        "{}",
        up.stats.near_light_fraction
    );
    // And the image is much darker: the ceiling's reflection mostly lands on the light's
    // black back.
    let (bright, dark) = (down.image.mean().element_sum(), up.image.mean().element_sum());
    assert!(dark < 0.25 * bright, "facing up {dark}, facing down {bright}");
    // A path-traced render traces no photons and reports none.
    let traced = Renderer::new(
        GeometryCube,
        RenderSettings {
            mode: Mode::PathTrace,
            ..settings
        },
    )
    .render(
        &CreaseAngle::default().partition(room(z, x).clone()).unwrap(),
        &(),
    )
    .unwrap();
    assert_eq!(traced.stats.near_light_fraction, 0.0);
}

#[test]
fn a_light_facing_its_ceiling_shows_in_the_progressive_and_sppm_stats() {
    let (x, z) = (vec3(0.5, 0.0, 0.0), vec3(0.0, 0.0, 0.5));
    let render = RenderSettings {
        width: 16,
        height: 16,
        photons: 5_000,
        ..Default::default()
    };
    let progressive = |scene: &Scene| {
        ProgressiveRenderer::new(GeometryCube, ProgressiveSettings::new(render, 3))
            .render(&CreaseAngle::default().partition(scene.clone()).unwrap(), &())
            .unwrap()
            .stats
    };
    let sppm = |scene: &Scene| {
        pm_render::progressive::SppmRenderer::new(pm_render::progressive::SppmSettings::new(render, 3))
            .render(scene, &())
            .unwrap()
            .stats
    };
    let (down, up) = (room(x, z), room(z, x));
    assert_eq!(progressive(&down).near_light_fraction, 0.0);
    assert_eq!(sppm(&down).near_light_fraction, 0.0);
    for stats in [progressive(&up), sppm(&up)] {
        assert_eq!(stats.passes, 3);
        assert!(stats.near_light_fraction > 0.99, "{}", stats.near_light_fraction);
    }
}
