//! A renderer author's own BSDF, from outside the crates with public items only: a Lambertian
//! written against the `Bsdf` trait renders in every mode (and SPPM) exactly as the built-in
//! Lambertian of the same albedo when it draws its numbers as the built-in does, and within
//! the noise of the built-in's seed-to-seed spread when it draws them by the trait's default.

use photon_maps::render::glam::{Vec2, Vec3};
use photon_maps::render::progressive::{SppmRenderer, SppmSettings};
use photon_maps::render::{EstimatorKind, Image, Mode, RenderSettings, Renderer};
use photon_maps::trace::bsdf::{Bsdf, BsdfSample, Lobes, ShadingPoint};
use photon_maps::trace::sampling::cosine_hemisphere;
use photon_maps::trace::{Camera, CreaseAngle, Partitioner, PointLight, Rng, Scene, Surface};
use std::f32::consts::FRAC_1_PI;

const ALBEDO: Vec3 = Vec3::new(0.7, 0.45, 0.2);

/// The author's Lambertian; `Drawing` says how `sample_from` draws its numbers.
#[derive(Debug)]
struct Matte {
    albedo: Vec3,
    drawing: Drawing,
}

/// How [`Matte`] draws from the stream.
#[derive(Debug, Clone, Copy)]
enum Drawing {
    /// Two numbers, as the built-in Lambertian.
    AsBuiltIn,
    /// The trait's default (three numbers).
    Default,
}

impl Bsdf for Matte {
    fn lobes(&self) -> Lobes {
        Lobes::DIFFUSE_REFLECTION
    }

    fn eval(&self, at: &ShadingPoint, _wo: Vec3, wi: Vec3) -> Vec3 {
        if at.shading.dot(wi) > 0.0 {
            self.albedo * at.tint * FRAC_1_PI
        } else {
            Vec3::ZERO
        }
    }

    fn pdf(&self, at: &ShadingPoint, _wo: Vec3, wi: Vec3) -> f32 {
        at.shading.dot(wi).max(0.0) * FRAC_1_PI
    }

    fn sample(&self, at: &ShadingPoint, _wo: Vec3, u: Vec2, _u_lobe: f32) -> Option<BsdfSample> {
        let wi = cosine_hemisphere(at.shading, u);
        Some(BsdfSample {
            wi,
            weight: self.albedo * at.tint,
            pdf: at.shading.dot(wi).max(0.0) * FRAC_1_PI,
            lobe: Lobes::DIFFUSE_REFLECTION,
        })
    }

    fn sample_from(&self, at: &ShadingPoint, wo: Vec3, rng: &mut Rng) -> Option<BsdfSample> {
        match self.drawing {
            Drawing::AsBuiltIn => {
                let u = Vec2::new(rng.next_f32(), rng.next_f32());
                self.sample(at, wo, u, 0.0)
            }
            Drawing::Default => {
                let (u, u_lobe) = (Vec2::new(rng.next_f32(), rng.next_f32()), rng.next_f32());
                self.sample(at, wo, u, u_lobe)
            }
        }
    }

    fn albedo(&self, at: &ShadingPoint, _wo: Vec3) -> Vec3 {
        self.albedo * at.tint
    }

    fn diffuse_albedo(&self, at: &ShadingPoint) -> Vec3 {
        self.albedo * at.tint
    }
}

static MATTE_AS_BUILT_IN: Matte = Matte {
    albedo: ALBEDO,
    drawing: Drawing::AsBuiltIn,
};
static MATTE_DEFAULT: Matte = Matte {
    albedo: ALBEDO,
    drawing: Drawing::Default,
};

/// A closed grey sphere lit by a point light; inside it a ball of `ball` in front of the
/// camera, and a mirror ball that shows the first ball from the side.
fn scene(ball: Surface) -> Scene {
    Scene::builder()
        .sphere(Vec3::ZERO, 2.0, Surface::diffuse(Vec3::splat(0.5)))
        .sphere(Vec3::new(0.0, -0.3, -0.5), 0.45, ball)
        .sphere(Vec3::new(0.8, -0.5, -0.2), 0.3, Surface::mirror(Vec3::splat(0.9)))
        .light(PointLight::new(Vec3::new(0.3, 1.2, 0.4), Vec3::splat(40.0)))
        .camera(Camera::new(Vec3::new(0.0, 0.0, 1.5), Vec3::NEG_Z, Vec3::Y, 0.9))
        .build()
        .unwrap()
}

fn settings(mode: Mode, seed: u64) -> RenderSettings {
    RenderSettings {
        width: 20,
        height: 20,
        samples_per_pixel: 2,
        photons: 8_000,
        mode,
        seed,
        threads: 2,
        ..RenderSettings::default()
    }
}

/// Each mode's image, then SPPM's (two passes).
fn renders(scene: &Scene, seed: u64) -> Vec<(String, Image)> {
    let partitioned = CreaseAngle::default().partition(scene.clone()).unwrap();
    let mut out: Vec<(String, Image)> = Mode::ALL
        .into_iter()
        .map(|mode| {
            let image = Renderer::new(EstimatorKind::Disc, settings(mode, seed))
                .render(&partitioned, &())
                .unwrap()
                .image;
            (mode.to_string(), image)
        })
        .collect();
    let sppm = SppmRenderer::new(SppmSettings::new(settings(Mode::PhotonMap, seed), 2))
        .render(scene, &())
        .unwrap()
        .image;
    out.push(("sppm".into(), sppm));
    out
}

fn bits(image: &Image) -> Vec<[u32; 3]> {
    image
        .pixels()
        .iter()
        .map(|p| p.to_array().map(f32::to_bits))
        .collect()
}

/// Pixels whose mean is lit and finite: the images are not black, so equality means something.
fn assert_lit(image: &Image, what: &str) {
    let mean = image.mean();
    assert!(
        mean.is_finite() && mean.min_element() > 1e-3,
        "{what}: mean {mean}"
    );
}

#[test]
fn an_authors_lambertian_renders_bit_for_bit_as_the_built_in_in_every_mode() {
    let built_in = renders(&scene(Surface::diffuse(ALBEDO)), 5);
    let custom = renders(&scene(Surface::with_bsdf(&MATTE_AS_BUILT_IN)), 5);
    assert_eq!(built_in.len(), Mode::ALL.len() + 1);
    for ((mode, a), (_, b)) in built_in.iter().zip(&custom) {
        assert_lit(b, mode);
        assert!(bits(a) == bits(b), "{mode}: the custom BSDF's image differs");
    }
}

/// Drawing three numbers per bounce changes the streams, so the images differ by noise only:
/// each image's mean lies within four standard deviations of the built-in's mean over four
/// seeds (the spread measured from those seeds), in every mode.
#[test]
fn an_authors_lambertian_with_the_default_draws_agrees_within_noise_in_every_mode() {
    let built_in_scene = scene(Surface::diffuse(ALBEDO));
    let seeds = [11u64, 12, 13, 14];
    let built_in: Vec<Vec<(String, Image)>> = seeds.iter().map(|&s| renders(&built_in_scene, s)).collect();
    let custom = renders(&scene(Surface::with_bsdf(&MATTE_DEFAULT)), 21);
    for (k, (mode, image)) in custom.iter().enumerate() {
        assert_lit(image, mode);
        let means: Vec<Vec3> = built_in.iter().map(|r| r[k].1.mean()).collect();
        let mean = means.iter().copied().sum::<Vec3>() / means.len() as f32;
        let var = means.iter().map(|m| (*m - mean) * (*m - mean)).sum::<Vec3>() / (means.len() - 1) as f32;
        let sd = var.max(Vec3::splat(0.0)).powf(0.5);
        let diff = (image.mean() - mean).abs();
        // 4 sd of one image against a four-seed mean: sd · sqrt(1 + 1/4); plus 0.5 % of the
        // mean for the sd's own uncertainty from four seeds.
        let limit = 4.0 * sd * 1.25f32.sqrt() + 0.005 * mean;
        assert!(
            diff.cmple(limit).all(),
            "{mode}: custom mean {}, built-in {mean} ± {sd} (limit {limit})",
            image.mean()
        );
    }
}
