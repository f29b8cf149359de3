//! The textured area light against closed forms: its power is π A × factor × the texture's
//! mean, its photons' weights average 1, its shadow-ray irradiance on the axis of a quad with
//! four coloured quadrants is the sum of the quadrants' configuration factors, and the
//! scene's emission at a hit reads the same texture.

use pm_trace::glam::{Vec2, Vec3};
use pm_trace::{
    EmissionTexture, Light, PointLight, Ray, RayKind, Rng, Sampler, Scene, SceneError, Sides, Surface,
    Texture, TexturedAreaLight, VertexAttributes, Wrap,
};
use std::f64::consts::PI;
use std::sync::Arc;

/// 2 × 2 texels, nearest: each quadrant of the unit uv square one colour.
const CODES: [[u8; 3]; 4] = [[255, 40, 0], [0, 255, 90], [128, 128, 128], [30, 0, 255]];

fn quadrants() -> (Arc<Texture>, Sampler) {
    let texture = Texture::from_srgb8(2, 2, CODES.to_vec()).unwrap();
    let sampler = Sampler {
        wrap_u: Wrap::ClampToEdge,
        wrap_v: Wrap::ClampToEdge,
        nearest: true,
    };
    (Arc::new(texture), sampler)
}

fn linear(code: [u8; 3]) -> Vec3 {
    // The IEC 61966-2-1 decoding, written out here rather than taken from the crate.
    let f = |c: u8| {
        let c = c as f64 / 255.0;
        (if c <= 0.04045 {
            c / 12.92
        } else {
            ((c + 0.055) / 1.055).powf(2.4)
        }) as f32
    };
    Vec3::new(f(code[0]), f(code[1]), f(code[2]))
}

/// The unit quad at height 0 in x, z ∈ [0, 1] facing +y, with u = x and v = z.
fn quad() -> (Vec<Vec3>, Vec<[u32; 3]>, Vec<Vec2>) {
    let positions = vec![
        Vec3::new(0.0, 0.0, 0.0),
        Vec3::new(0.0, 0.0, 1.0),
        Vec3::new(1.0, 0.0, 1.0),
        Vec3::new(1.0, 0.0, 0.0),
    ];
    let uvs = positions.iter().map(|p| Vec2::new(p.x, p.z)).collect();
    (positions, vec![[0, 1, 2], [0, 2, 3]], uvs)
}

fn light(factor: Vec3, sides: Sides) -> TexturedAreaLight {
    let (positions, triangles, uvs) = quad();
    let corners: Vec<[Vec3; 3]> = triangles
        .iter()
        .map(|t| t.map(|i| positions[i as usize]))
        .collect();
    let corner_uvs: Vec<[Vec2; 3]> = triangles.iter().map(|t| t.map(|i| uvs[i as usize])).collect();
    let (texture, sampler) = quadrants();
    TexturedAreaLight::new(&corners, &corner_uvs, factor, texture, sampler, sides)
}

fn texel_mean() -> Vec3 {
    CODES.iter().map(|&c| linear(c)).sum::<Vec3>() / 4.0
}

#[test]
fn power_is_pi_area_factor_times_the_texture_mean() {
    let factor = Vec3::new(2.0, 3.0, 0.5);
    for (sides, count) in [(Sides::Single, 1.0), (Sides::Double, 2.0)] {
        let power = light(factor, sides).power();
        // A = 1 m²; nearest texels on a quad mapped once: the mean of the four texels.
        let truth = factor * texel_mean() * (std::f32::consts::PI * count);
        assert!(
            ((power - truth) / truth).abs().max_element() < 1e-5,
            "{sides:?}: {power} vs {truth}"
        );
    }
}

#[test]
fn photon_weights_average_one_per_channel() {
    let light = light(Vec3::new(1.0, 0.5, 2.0), Sides::Single);
    let n = 200_000u32;
    let (mut sum, mut sum2) = (Vec3::ZERO.as_dvec3(), Vec3::ZERO.as_dvec3());
    for i in 0..n {
        let w = light.emit(&mut Rng::new(11, i as u64)).weight.as_dvec3();
        sum += w;
        sum2 += w * w;
    }
    let mean = sum / n as f64;
    let se = ((sum2 / n as f64 - mean * mean) / n as f64).map(f64::sqrt);
    for c in 0..3 {
        assert!(
            (mean[c] - 1.0).abs() <= 4.0 * se[c],
            "channel {c}: mean weight {} ± {}",
            mean[c],
            se[c]
        );
    }
}

#[test]
fn photons_carry_each_texel_region_its_own_power() {
    // Each quadrant of the quad emits π · ¼ · factor ⊙ its texel; the triangles cut the
    // quadrants on (0,0) and (1,1) in half, so per-triangle means alone would not give this.
    let factor = Vec3::new(1.0, 0.5, 2.0);
    let light = light(factor, Sides::Single);
    let n = 400_000u32;
    let share = light.power().as_dvec3() / n as f64;
    let (mut sum, mut sum2) = ([Vec3::ZERO.as_dvec3(); 4], [Vec3::ZERO.as_dvec3(); 4]);
    for i in 0..n {
        let e = light.emit(&mut Rng::new(13, i as u64));
        let k = (e.ray.origin.x >= 0.5) as usize + 2 * (e.ray.origin.z >= 0.5) as usize;
        let p = e.weight.as_dvec3() * share;
        sum[k] += p;
        sum2[k] += p * p;
    }
    for k in 0..4 {
        let truth = (factor * linear(CODES[k])).as_dvec3() * (PI * 0.25);
        // The per-quadrant total is a sum over all n paths of (p if in k else 0).
        let mean = sum[k] / n as f64;
        let se = ((sum2[k] / n as f64 - mean * mean) * n as f64).map(f64::sqrt);
        for c in 0..3 {
            let off = (sum[k][c] - truth[c]).abs();
            assert!(
                off <= 4.0 * se[c] + 1e-9,
                "quadrant {k} channel {c}: {} ± {} vs {}",
                sum[k][c],
                se[c],
                truth[c]
            );
        }
    }
}

/// Configuration factor from a point to a parallel rectangle `a × b` at distance `h`, the
/// point on the normal through one of its corners (Howell's catalogue, C-11).
fn corner_factor(a: f64, b: f64, h: f64) -> f64 {
    let (x, y) = (a / h, b / h);
    let (sx, sy) = ((1.0 + x * x).sqrt(), (1.0 + y * y).sqrt());
    (x / sx * (y / sx).atan() + y / sy * (x / sy).atan()) / (2.0 * PI)
}

#[test]
fn shadow_ray_irradiance_on_the_axis_is_the_quadrants_sum() {
    // Above the quad's centre, each 0.5 × 0.5 quadrant has the point over a corner:
    // E = π · factor · Σ_k c_k · F(0.5, 0.5, h), on both sides for a two-sided light.
    let h = 0.6f64;
    let factor = Vec3::new(1.0, 2.0, 0.5);
    let truth = (factor * texel_mean() * 4.0).as_dvec3() * PI * corner_factor(0.5, 0.5, h);
    let two = light(factor, Sides::Double);
    let n = 200_000u32;
    for (point, normal) in [
        (Vec3::new(0.5, h as f32, 0.5), Vec3::NEG_Y),
        (Vec3::new(0.5, -h as f32, 0.5), Vec3::Y),
    ] {
        let (mut sum, mut sum2) = (Vec3::ZERO.as_dvec3(), Vec3::ZERO.as_dvec3());
        for i in 0..n {
            let e = two
                .sample_incident(point, normal, &mut Rng::new(5, i as u64))
                .map_or(Vec3::ZERO, |s| {
                    s.radiance_over_pdf * normal.dot(s.direction).max(0.0)
                })
                .as_dvec3();
            sum += e;
            sum2 += e * e;
        }
        let mean = sum / n as f64;
        let se = ((sum2 / n as f64 - mean * mean) / n as f64).map(f64::sqrt);
        for c in 0..3 {
            assert!(
                (mean[c] - truth[c]).abs() <= 4.0 * se[c] && se[c] < 0.02 * truth[c],
                "{point} channel {c}: {} ± {} vs {}",
                mean[c],
                se[c],
                truth[c]
            );
        }
    }
}

#[test]
fn scene_emission_at_a_hit_reads_the_texture() {
    let (positions, triangles, uvs) = quad();
    let (texture, sampler) = quadrants();
    let factor = Vec3::new(2.0, 1.0, 4.0);
    let surface = Surface {
        emission: factor,
        ..Surface::diffuse(Vec3::ZERO)
    };
    let scene = Scene::builder()
        .attributed_mesh(
            &positions,
            &triangles,
            surface,
            VertexAttributes {
                emission_texture: Some(EmissionTexture {
                    uvs,
                    texture,
                    sampler,
                }),
                ..VertexAttributes::default()
            },
        )
        .light(PointLight::new(Vec3::Y, Vec3::ONE))
        .build()
        .unwrap();
    // Texel (x, y) covers u ∈ [x/2, (x+1)/2], v ∈ [y/2, (y+1)/2]; u = x, v = z here.
    for (k, code) in CODES.iter().enumerate() {
        let (x, z) = ((k % 2) as f32 * 0.5 + 0.2, (k / 2) as f32 * 0.5 + 0.3);
        let ray = Ray {
            origin: Vec3::new(x, 1.0, z),
            direction: Vec3::NEG_Y,
        };
        let hit = scene.intersect(&ray, f32::INFINITY, RayKind::Camera).unwrap();
        let e = scene.emission(&hit);
        assert!(
            (e - factor * linear(*code)).abs().max_element() < 1e-5,
            "texel {k}: {e}"
        );
    }
}

#[test]
fn mismatched_or_black_textured_lights_are_refused() {
    let (texture, sampler) = quadrants();
    let triangle = [[Vec3::ZERO, Vec3::X, Vec3::Z]];
    let uv = [[Vec2::ZERO, Vec2::X, Vec2::Y]];
    let mismatched =
        TexturedAreaLight::new(&triangle, &[], Vec3::ONE, texture.clone(), sampler, Sides::Single);
    assert!(mismatched.validate().is_err());
    let black = TexturedAreaLight::new(
        &triangle,
        &uv,
        Vec3::ZERO,
        texture.clone(),
        sampler,
        Sides::Single,
    );
    assert!(black.validate().is_err());
    assert_eq!(black.power(), Vec3::ZERO);
    let nan = TexturedAreaLight::new(&triangle, &uv, Vec3::NAN, texture, sampler, Sides::Single);
    let floor = [Vec3::ZERO, Vec3::X, Vec3::Z];
    let built = Scene::builder()
        .mesh(&floor, &[[0u32, 1, 2]], Surface::diffuse(Vec3::ONE))
        .light(nan)
        .build();
    assert!(matches!(built, Err(SceneError::InvalidLight { .. })), "{built:?}");
}
