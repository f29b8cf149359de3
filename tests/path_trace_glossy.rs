//! The path tracer on a glossy surface against quadrature: a rough metal (glTF
//! metallic-roughness, Appendix B) floor under a square area light, nothing else in the scene.
//! The radiance the camera sees at one floor point is the light's radiance integrated through
//! the BSDF over the light's area, `∫ L f(wo, wi) cos θi cos θl / r² dA`, computed here by a
//! fine midpoint rule in f64. The path tracer's next-event estimation evaluates the BSDF per
//! light sample and weights it against the BSDF's own samples; reading the diffuse lobe alone
//! (zero for a metal) would leave only the down-weighted BSDF samples and read far too dark.

use photon_maps::render::glam::Vec3;
use photon_maps::render::{EstimatorKind, Mode, RenderSettings, Renderer};
use photon_maps::trace::bsdf::{Bsdf, MetallicRoughness};
use photon_maps::trace::{Camera, Partitioner, Ray, RayKind, Scene, SingleMap, Surface};

const LIGHT_CORNER: Vec3 = Vec3::new(0.1, 1.0, -0.25);
const LIGHT_SIZE: f32 = 0.5;
const RADIANCE: f32 = 3.0;
const EYE: Vec3 = Vec3::new(-1.0, 1.0, 0.0);

fn scene(roughness: f32) -> Scene {
    let metal = MetallicRoughness::new(Vec3::new(0.9, 0.7, 0.5), 1.0, roughness).unwrap();
    let floor = [
        Vec3::new(-5.0, 0.0, -5.0),
        Vec3::new(-5.0, 0.0, 5.0),
        Vec3::new(5.0, 0.0, 5.0),
        Vec3::new(5.0, 0.0, -5.0),
    ];
    Scene::builder()
        .mesh(&floor, &[[0, 1, 2, 3]], Surface::metallic_roughness(metal))
        // Edges x then z: the quad's front (its emitting side, along edge_u × edge_v) faces
        // down, onto the floor.
        .area_light_quad(
            LIGHT_CORNER,
            Vec3::new(LIGHT_SIZE, 0.0, 0.0),
            Vec3::new(0.0, 0.0, LIGHT_SIZE),
            Vec3::splat(RADIANCE),
        )
        // A narrow view of the floor's origin: the one pixel covers a few millimetres.
        .camera(Camera::new(EYE, Vec3::ZERO, Vec3::Y, 0.002))
        .build()
        .unwrap()
}

/// The radiance leaving the floor's origin towards the eye, by an n × n midpoint rule over the
/// light (f64 sums of the BSDF's f32 values).
fn quadrature(scene: &Scene, n: usize) -> Vec3 {
    let ray = Ray::new(EYE, (Vec3::ZERO - EYE).normalize());
    let hit = scene.intersect(&ray, f32::INFINITY, RayKind::Camera).unwrap();
    let at = scene.shading_point(&hit);
    let material = scene.material(&hit);
    let wo = -ray.direction;
    let cell = f64::from(LIGHT_SIZE) / n as f64;
    let mut sum = [0.0f64; 3];
    for i in 0..n {
        for j in 0..n {
            let p = LIGHT_CORNER
                + Vec3::new(
                    ((i as f64 + 0.5) * cell) as f32,
                    0.0,
                    ((j as f64 + 0.5) * cell) as f32,
                );
            let d = p - hit.position;
            let r2 = f64::from(d.length_squared());
            let wi = d.normalize();
            let (cos_i, cos_l) = (f64::from(wi.y), f64::from(wi.y));
            let f = material.eval(&at, wo, wi);
            let g = cos_i * cos_l / r2 * cell * cell * f64::from(RADIANCE);
            for c in 0..3 {
                sum[c] += f64::from(f[c]) * g;
            }
        }
    }
    Vec3::new(sum[0] as f32, sum[1] as f32, sum[2] as f32)
}

/// The path tracer's pixel, as the mean and standard error over `seeds` renders.
fn path_traced(scene: &Scene, seeds: u64, spp: u32) -> (Vec3, Vec3) {
    let partitioned = SingleMap.partition(scene.clone()).unwrap();
    let values: Vec<Vec3> = (0..seeds)
        .map(|seed| {
            let settings = RenderSettings {
                width: 1,
                height: 1,
                samples_per_pixel: spp,
                mode: Mode::PathTrace,
                seed,
                threads: 2,
                ..RenderSettings::default()
            };
            Renderer::new(EstimatorKind::Disc, settings)
                .render(&partitioned, &())
                .unwrap()
                .image
                .pixels()[0]
        })
        .collect();
    let n = values.len() as f32;
    let mean = values.iter().copied().sum::<Vec3>() / n;
    let var = values.iter().map(|v| (*v - mean) * (*v - mean)).sum::<Vec3>() / (n - 1.0);
    (mean, (var / n).powf(0.5))
}

#[test]
fn the_path_tracer_integrates_a_rough_metal_under_an_area_light() {
    for roughness in [0.3, 0.6] {
        let scene = scene(roughness);
        let exact = quadrature(&scene, 400);
        // The midpoint rule has converged: a coarser grid agrees to 0.1 %.
        let coarse = quadrature(&scene, 200);
        assert!(
            ((coarse - exact) / exact).abs().max_element() < 1e-3,
            "{coarse} against {exact}"
        );
        assert!(exact.min_element() > 0.01, "the highlight is in view: {exact}");
        let (mean, se) = path_traced(&scene, 8, 512);
        let t = (mean - exact) / se;
        eprintln!("roughness {roughness}: path traced {mean} ± {se}, quadrature {exact}, t = {t}");
        assert!(
            (se / exact).max_element() < 0.02,
            "too noisy to judge: {se} of {exact}"
        );
        assert!(
            t.abs().max_element() < 4.5,
            "roughness {roughness}: path traced {mean} ± {se} against {exact} (t = {t})"
        );
    }
}
