//! The area light's density for multiple importance sampling: `incident_pdf` towards a point
//! the light's own `sample_incident` chose gives that sample's distance and density
//! (radiance over `radiance_over_pdf`), on one- and two-sided lights; rays that miss, or meet
//! the back of a one-sided light, get none; delta lights get none and allow MIS.

use pm_trace::glam::{Vec3, vec3};
use pm_trace::{AreaLight, Light, PointLight, Rng, Sides};

#[test]
fn incident_pdf_is_the_density_of_sample_incident() {
    let radiance = Vec3::new(3.0, 2.0, 1.0);
    // A 0.5 × 0.25 m ceiling light facing down (+x × +z = −y), and a triangle pair tilted.
    let one_sided = AreaLight::quad(
        vec3(0.0, 1.0, 0.0),
        vec3(0.5, 0.0, 0.0),
        vec3(0.0, 0.0, 0.25),
        radiance,
    );
    let two_sided = one_sided.clone().with_sides(Sides::Double);
    let mut rng = Rng::new(3, 0);
    let mut checked = 0;
    for light in [&one_sided, &two_sided] {
        assert!(light.supports_mis());
        for _ in 0..2000 {
            let point = vec3(
                rng.next_f32() * 2.0 - 0.75,
                rng.next_f32() * 1.8,
                rng.next_f32() * 2.0 - 0.9,
            );
            let Some(sample) = light.sample_incident(point, Vec3::Y, &mut rng) else {
                continue;
            };
            let pdf = radiance.x / sample.radiance_over_pdf.x;
            let found = light
                .incident_pdf(point, sample.direction)
                .expect("the ray towards a sampled point meets the light");
            assert!(
                (found.distance / sample.distance - 1.0).abs() < 1e-3,
                "{found:?} vs {sample:?}"
            );
            assert!((found.pdf / pdf - 1.0).abs() < 2e-3, "{} vs {pdf}", found.pdf);
            checked += 1;
        }
    }
    assert!(checked > 2500, "{checked}");
    // Below the one-sided light, looking away from it, or above it looking down at its back.
    assert!(
        one_sided
            .incident_pdf(vec3(0.25, 0.5, 0.1), Vec3::NEG_Y)
            .is_none()
    );
    assert!(
        one_sided
            .incident_pdf(vec3(0.25, 1.5, 0.1), Vec3::NEG_Y)
            .is_none()
    );
    assert!(
        two_sided
            .incident_pdf(vec3(0.25, 1.5, 0.1), Vec3::NEG_Y)
            .is_some()
    );
    // Beside it.
    assert!(one_sided.incident_pdf(vec3(2.0, 0.5, 0.1), Vec3::Y).is_none());
    // Straight below its centre at 1 m: d² / (A cos) = 1 / 0.125.
    let below = one_sided.incident_pdf(vec3(0.25, 0.0, 0.125), Vec3::Y).unwrap();
    assert!(
        (below.distance - 1.0).abs() < 1e-5 && (below.pdf - 8.0).abs() < 1e-3,
        "{below:?}"
    );
    let point = PointLight::new(Vec3::ZERO, Vec3::ONE);
    assert!(point.supports_mis() && point.incident_pdf(Vec3::Y, Vec3::NEG_Y).is_none());
}

#[test]
fn large_emitting_meshes_keep_shadow_rays_alone() {
    // incident_pdf scans every triangle: past the limit the light opts out of MIS.
    let strip = |n: usize| -> Vec<[Vec3; 3]> {
        (0..n)
            .map(|i| {
                let x = i as f32 * 0.01;
                [vec3(x, 1.0, 0.0), vec3(x, 1.0, 0.1), vec3(x + 0.01, 1.0, 0.0)]
            })
            .collect()
    };
    let small = AreaLight::from_triangles(&strip(AreaLight::MIS_MAX_TRIANGLES), Vec3::ONE);
    let large = AreaLight::from_triangles(&strip(AreaLight::MIS_MAX_TRIANGLES + 1), Vec3::ONE);
    assert!(small.supports_mis());
    assert!(!large.supports_mis());
}
