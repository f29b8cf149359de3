//! The GGX distribution and glTF's metallic-roughness BSDF against independent truth: `D` and
//! the visible-normal density integrate to one by quadrature, Smith's `G1`/`G2`/`V` equal
//! their closed forms, `eval` equals a straight-line f64 transcription of Appendix B, the
//! parameters are checked and dispatched, and `f` is reciprocal. Sampling, albedo and the
//! mirror limit are in `ggx_sampling.rs`.

use pm_trace::bsdf::{Bsdf, Lobes, MetallicRoughness, ShadingPoint, TrowbridgeReitz};
use pm_trace::glam::{DVec3, Vec3};
use pm_trace::{Material, MaterialError, Rng};
use std::f64::consts::PI;

mod ggx_support;
use ggx_support::*;

/// `∫ D(ωm) cos θm dωm = 1` (the projected microfacet area is the macro-surface's).
#[test]
fn ggx_normal_density_projects_to_unit_area() {
    for alpha in ALPHAS {
        let d = TrowbridgeReitz::new(alpha);
        let integral = hemisphere_integral(alpha as f64, 4000, 16, |wm| d.d(wm) as f64 * wm.z as f64);
        assert!((integral - 1.0).abs() < 1e-3, "α {alpha}: ∫ D cos = {integral}");
    }
}

/// The visible-normal density `D_ω` integrates to one for each `ω`, which is Smith's `G1`
/// being the ratio of projected areas `cos θ / ∫ max(0, ω·ωm) D dωm`; and `G1`, `Λ`, `G2`
/// and `V` equal their closed forms (Heitz 2014; glTF Appendix B's visibility) in f64.
#[test]
fn visible_normals_integrate_to_one_and_smith_terms_match_closed_forms() {
    for alpha in ALPHAS {
        let d = TrowbridgeReitz::new(alpha);
        let a = alpha as f64;
        for cos_o in [1.0, 0.8, 0.4, 0.1] {
            let wo = local(cos_o, 0.7);
            let integral = hemisphere_integral(a, 2000, 256, |wm| d.visible_normal_pdf(wo, wm) as f64);
            assert!(
                (integral - 1.0).abs() < 2e-3,
                "α {alpha}, cos θo {cos_o}: ∫ D_ω = {integral}"
            );
            let tan2 = (1.0 - cos_o * cos_o) / (cos_o * cos_o);
            let lambda = ((1.0 + a * a * tan2).sqrt() - 1.0) / 2.0;
            assert!((d.lambda(wo) as f64 - lambda).abs() < 1e-5 * (1.0 + lambda));
            assert!((d.g1(wo) as f64 - 1.0 / (1.0 + lambda)).abs() < 1e-5);
            for cos_i in [0.9, 0.5, 0.05] {
                let wi = local(cos_i, 2.1);
                let tan2_i = (1.0 - cos_i * cos_i) / (cos_i * cos_i);
                let lambda_i = ((1.0 + a * a * tan2_i).sqrt() - 1.0) / 2.0;
                let g2 = 1.0 / (1.0 + lambda + lambda_i);
                assert!((d.g2(wo, wi) as f64 - g2).abs() < 1e-5, "G2");
                // Appendix B: V = 1 / (2 (|N·L| √(α² + (1 − α²)(N·V)²) + |N·V| √(α² + (1 − α²)(N·L)²))).
                let v = 1.0
                    / (2.0
                        * (cos_i * (a * a + (1.0 - a * a) * cos_o * cos_o).sqrt()
                            + cos_o * (a * a + (1.0 - a * a) * cos_i * cos_i).sqrt()));
                assert!((d.visibility(wo, wi) as f64 - v).abs() < 1e-5 * v, "V");
                assert!(
                    (g2 / (4.0 * cos_o * cos_i) - v).abs() < 1e-9 * v,
                    "V = G2 / 4 cos cos"
                );
            }
        }
    }
}

/// The glTF 2.0 metallic-roughness BRDF, Appendix B with `KHR_materials_ior` and
/// `KHR_materials_specular`, transcribed in f64 from the specification's formulas.
#[allow(clippy::too_many_arguments)]
fn appendix_b(
    n: DVec3,
    v: DVec3,
    l: DVec3,
    base: DVec3,
    metallic: f64,
    roughness: f64,
    ior: f64,
    specular: f64,
    specular_color: DVec3,
) -> DVec3 {
    let alpha = roughness * roughness;
    let a2 = alpha * alpha;
    let h = (v + l).normalize();
    let (nh, nl, nv, vh, hl) = (n.dot(h), n.dot(l), n.dot(v), v.dot(h), h.dot(l));
    let chi = |x: f64| if x > 0.0 { 1.0 } else { 0.0 };
    if nl <= 0.0 || nv <= 0.0 {
        return DVec3::ZERO;
    }
    let d = a2 * chi(nh) / (PI * (nh * nh * (a2 - 1.0) + 1.0).powi(2));
    let vis = chi(hl) * chi(vh)
        / (2.0
            * (nl.abs() * (a2 + (1.0 - a2) * nv * nv).sqrt()
                + nv.abs() * (a2 + (1.0 - a2) * nl * nl).sqrt()));
    let specular_brdf = vis * d;
    let diffuse_brdf = base / PI;
    let fw = (1.0 - vh.abs()).powi(5);
    let f0 = (((ior - 1.0) / (ior + 1.0)).powi(2) * specular_color).min(DVec3::ONE) * specular;
    let fresnel = f0 + (DVec3::splat(specular) - f0) * fw;
    let dielectric = fresnel * specular_brdf + (1.0 - fresnel.max_element()) * diffuse_brdf;
    let metal = specular_brdf * (base + (DVec3::ONE - base) * fw);
    dielectric * (1.0 - metallic) + metal * metallic
}

/// `eval` against [`appendix_b`] over random directions, parameters and normals (relative
/// error below 1e-3, or an absolute one below 1e-5 of the peak).
#[test]
fn eval_matches_an_independent_transcription_of_appendix_b() {
    let mut rng = Rng::new(35, 2);
    let mut u = || rng.next_f32();
    for k in 0..4000 {
        let n = direction(Vec3::Y, 2.0 * u() as f64 - 1.0, 6.3 * u() as f64);
        let base = Vec3::new(u(), u(), u());
        let metallic = [0.0, 1.0, u()][k % 3];
        let roughness = [0.05, 0.1, 0.3, 0.6, 1.0, u().max(0.05)][k % 6];
        let (ior, specular, specular_color) = match k % 4 {
            0 => (1.5, 1.0, Vec3::ONE),
            1 => (1.0 + 2.0 * u(), u(), Vec3::new(u(), 2.0 * u(), 30.0 * u())),
            2 => (0.0, 1.0, Vec3::ONE),
            _ => (1.5, 0.0, Vec3::ONE),
        };
        let m = material(base, metallic, roughness)
            .with_ior(ior)
            .unwrap()
            .with_specular(specular, specular_color)
            .unwrap();
        let at = ShadingPoint::facing(n);
        let wo = direction(n, u() as f64, 6.3 * u() as f64);
        let wi = direction(n, 2.0 * u() as f64 - 0.2, 6.3 * u() as f64);
        let truth = appendix_b(
            n.as_dvec3(),
            wo.as_dvec3(),
            wi.as_dvec3(),
            base.as_dvec3(),
            metallic as f64,
            roughness as f64,
            ior as f64,
            specular as f64,
            specular_color.as_dvec3(),
        );
        let f = m.eval(&at, wo, wi).as_dvec3();
        let peak = 1.0 / (PI * (roughness as f64).powi(4));
        let err = (f - truth).abs().max_element();
        assert!(
            err < 1e-3 * truth.max_element() || err < 1e-5 * peak,
            "case {k} {m:?} wo {wo} wi {wi}: eval {f}, Appendix B {truth}"
        );
    }
}

/// `specularFactor` 0 on a dielectric leaves the Lambertian `base/π`, and only a diffuse lobe.
#[test]
fn specular_factor_zero_is_lambertian() {
    let base = Vec3::new(0.8, 0.4, 0.1);
    let m = material(base, 0.0, 0.4).with_specular(0.0, Vec3::ONE).unwrap();
    assert_eq!(m.lobes(), Lobes::DIFFUSE_REFLECTION);
    let at = ShadingPoint::facing(TILTED);
    for (co, ci) in [(1.0, 0.3), (0.2, 0.9), (0.05, 0.05)] {
        let f = m.eval(&at, direction(TILTED, co, 0.1), direction(TILTED, ci, 2.0));
        assert!(
            (f - base / std::f32::consts::PI).abs().max_element() < 1e-7,
            "{f}"
        );
    }
    assert_eq!(m.diffuse_albedo(&at), base);
}

/// The lobes follow the parameters: a metal is glossy only, glTF's default matte (metallic
/// 0, roughness 1) keeps its Fresnel layer, and `Material` dispatches sample for sample.
#[test]
fn lobes_follow_the_parameters_and_material_dispatches() {
    let grey = Vec3::splat(0.5);
    assert_eq!(material(grey, 1.0, 0.5).lobes(), Lobes::GLOSSY_REFLECTION);
    assert_eq!(
        material(grey, 0.0, 1.0).lobes(),
        Lobes::GLOSSY_REFLECTION | Lobes::DIFFUSE_REFLECTION
    );
    assert_eq!(material(Vec3::ZERO, 0.0, 1.0).lobes(), Lobes::GLOSSY_REFLECTION);
    let m = material(Vec3::new(0.9, 0.6, 0.3), 0.4, 0.35);
    let as_material = Material::MetallicRoughness(m);
    assert!(as_material.is_diffuse());
    let at = ShadingPoint::facing(TILTED);
    let wo = direction(TILTED, 0.6, 0.3);
    for k in 0..200 {
        let (mut a, mut b) = (Rng::new(4, k), Rng::new(4, k));
        assert_eq!(
            as_material.sample_from(&at, wo, &mut a),
            m.sample_from(&at, wo, &mut b)
        );
    }
}

/// Out-of-range parameters are refused with the parameter named; `ior` 0 is allowed.
#[test]
fn out_of_range_parameters_are_refused() {
    let named = |r: Result<MetallicRoughness, MaterialError>| match r {
        Err(MaterialError::OutOfRange { parameter, .. }) => parameter,
        other => panic!("accepted: {other:?}"),
    };
    assert_eq!(
        named(MetallicRoughness::new(Vec3::new(0.5, 1.5, 0.0), 0.0, 0.5)),
        "baseColorFactor"
    );
    assert_eq!(
        named(MetallicRoughness::new(Vec3::ONE, f32::NAN, 0.5)),
        "metallicFactor"
    );
    assert_eq!(
        named(MetallicRoughness::new(Vec3::ONE, 0.0, -0.1)),
        "roughnessFactor"
    );
    let ok = material(Vec3::ONE, 0.0, 0.5);
    assert_eq!(named(ok.with_ior(0.5)), "ior");
    assert_eq!(named(ok.with_ior(f32::INFINITY)), "ior");
    assert_eq!(ok.with_ior(0.0).unwrap().dielectric_f0(), Vec3::ONE);
    assert_eq!(named(ok.with_specular(1.2, Vec3::ONE)), "specularFactor");
    assert_eq!(
        named(ok.with_specular(1.0, Vec3::new(1.0, -1.0, 1.0))),
        "specularColorFactor"
    );
}

/// `f(wo, wi) = f(wi, wo)` for directions above the shading normal.
#[test]
fn eval_is_reciprocal() {
    let mut rng = Rng::new(7, 7);
    let mut u = || rng.next_f32() as f64;
    for k in 0..3000 {
        let m = material(
            Vec3::new(u() as f32, u() as f32, u() as f32),
            [0.0, 0.5, 1.0][k % 3],
            [0.1, 0.3, 0.6, 1.0][k % 4],
        );
        let at = ShadingPoint::facing(TILTED);
        let a = direction(TILTED, u(), 6.3 * u());
        let b = direction(TILTED, u(), 6.3 * u());
        let (f, g) = (m.eval(&at, a, b), m.eval(&at, b, a));
        assert!(
            (f - g).abs().max_element() <= 2e-5 * f.max_element().max(1.0),
            "{f} vs {g}"
        );
    }
}
