//! The built-in BSDFs against independent truth: the Lambertian's samples against its `pdf` by
//! a chi-square test and its `pdf` against the cosine law; its directional albedo by a uniform
//! sphere Monte Carlo integral of `eval`; the mirror's direction against the reflection law;
//! glass's reflected fraction against Fresnel's equations in their angle form and its refraction
//! against Snell's law; each one draws from the stream exactly the numbers it documents.

use pm_trace::bsdf::{Bsdf, Glass, Lambertian, Lobes, Mirror, ShadingPoint};
use pm_trace::glam::{Vec2, Vec3};
use pm_trace::{Material, Rng};
use std::f64::consts::PI;

/// A shading point whose geometric and shading normal is `n`, tinted by `tint`.
fn point(n: Vec3, tint: Vec3) -> ShadingPoint {
    ShadingPoint {
        tint,
        ..ShadingPoint::facing(n)
    }
}

/// A unit direction at polar angle `acos(cos_theta)` from `n`, turned by `phi` about it (a
/// frame by Gram–Schmidt, independent of the crate's).
fn direction(n: Vec3, cos_theta: f32, phi: f32) -> Vec3 {
    let (t, b) = frame(n);
    let s = (1.0 - cos_theta * cos_theta).max(0.0).sqrt();
    (t * (s * phi.cos()) + b * (s * phi.sin()) + n * cos_theta).normalize()
}

fn frame(n: Vec3) -> (Vec3, Vec3) {
    let helper = if n.x.abs() < 0.9 { Vec3::X } else { Vec3::Y };
    let t = (helper - n * helper.dot(n)).normalize();
    (t, n.cross(t))
}

const NORMALS: [Vec3; 3] = [Vec3::Y, Vec3::new(0.48, -0.6, 0.64), Vec3::new(0.0, 0.0, -1.0)];

/// Chi-square of the Lambertian's sampled directions, binned by `cos² θ` (10 bins) and `φ`
/// (16 bins) about the normal, against the bins' probabilities integrated from its `pdf` (a
/// 12 × 12 midpoint rule per bin in `(cos θ, φ)`); 159 degrees of freedom, refused above 260
/// (p ≈ 1e-6).
#[test]
fn lambertian_samples_follow_its_pdf_by_chi_square() {
    let bsdf = Lambertian {
        albedo: Vec3::new(0.8, 0.5, 0.2),
    };
    let (nc, np, n) = (10usize, 16usize, 160_000usize);
    for (k, normal) in NORMALS.into_iter().enumerate() {
        let at = point(normal, Vec3::ONE);
        let wo = direction(normal, 0.3, 1.0);
        let (t, b) = frame(normal);
        let mut counts = vec![0u32; nc * np];
        let mut rng = Rng::new(11, k as u64);
        for _ in 0..n {
            let s = bsdf
                .sample_from(&at, wo, &mut rng)
                .expect("a Lambertian always samples");
            let c = s.wi.dot(normal).clamp(0.0, 1.0);
            let phi = s.wi.dot(b).atan2(s.wi.dot(t)).rem_euclid(std::f32::consts::TAU);
            let i = ((c * c * nc as f32) as usize).min(nc - 1);
            let j = ((phi / std::f32::consts::TAU * np as f32) as usize).min(np - 1);
            counts[i * np + j] += 1;
        }
        let mut chi2 = 0.0;
        for i in 0..nc {
            // Bin i holds cos θ in [sqrt(i/nc), sqrt((i+1)/nc)].
            let (c0, c1) = (
                ((i as f64) / nc as f64).sqrt(),
                ((i + 1) as f64 / nc as f64).sqrt(),
            );
            for j in 0..np {
                let (p0, p1) = (
                    j as f64 / np as f64 * 2.0 * PI,
                    (j + 1) as f64 / np as f64 * 2.0 * PI,
                );
                let mut prob = 0.0;
                let m = 12;
                for a in 0..m {
                    let c = c0 + (c1 - c0) * (a as f64 + 0.5) / m as f64;
                    for q in 0..m {
                        let phi = p0 + (p1 - p0) * (q as f64 + 0.5) / m as f64;
                        let wi = direction(normal, c as f32, phi as f32);
                        prob += bsdf.pdf(&at, wo, wi) as f64;
                    }
                }
                // dω = d(cos θ) dφ.
                prob *= (c1 - c0) * (p1 - p0) / (m * m) as f64;
                let expected = prob * n as f64;
                let observed = counts[i * np + j] as f64;
                chi2 += (observed - expected).powi(2) / expected;
            }
        }
        assert!(
            chi2 < 260.0,
            "normal {normal}: chi-square {chi2:.1} over 159 degrees of freedom"
        );
    }
}

/// The Lambertian's `pdf` is the cosine law `cos θ / π` above the shading normal and zero
/// below; `eval` is `ρ · tint / π` there; each sample's `pdf` and `weight` agree with them.
#[test]
fn lambertian_pdf_is_the_cosine_law_and_samples_report_it() {
    let albedo = Vec3::new(0.9, 0.4, 0.1);
    let tint = Vec3::new(0.5, 1.0, 0.25);
    let bsdf = Lambertian { albedo };
    let mut rng = Rng::new(3, 0);
    for normal in NORMALS {
        let at = point(normal, tint);
        let wo = direction(normal, 0.7, 2.0);
        for _ in 0..1_000 {
            let cos = 2.0 * rng.next_f32() - 1.0;
            let wi = direction(normal, cos, 6.0 * rng.next_f32());
            let truth = (cos.max(0.0) as f64 / PI) as f32;
            assert!((bsdf.pdf(&at, wo, wi) - truth).abs() < 1e-5, "cos {cos}");
            let f = bsdf.eval(&at, wo, wi);
            let f_truth = if wi.dot(normal) > 0.0 {
                albedo * tint / PI as f32
            } else {
                Vec3::ZERO
            };
            assert!((f - f_truth).abs().max_element() < 1e-6, "cos {cos}: {f}");
            let s = bsdf
                .sample(&at, wo, Vec2::new(rng.next_f32(), rng.next_f32()), 0.5)
                .unwrap();
            assert_eq!(s.lobe, Lobes::DIFFUSE_REFLECTION);
            assert!((s.wi.length() - 1.0).abs() < 1e-5);
            assert!((s.pdf - bsdf.pdf(&at, wo, s.wi)).abs() < 1e-6);
            if s.pdf > 1e-3 {
                let weight = bsdf.eval(&at, wo, s.wi) * s.wi.dot(normal) / s.pdf;
                assert!(
                    (weight - s.weight).abs().max_element() < 1e-4,
                    "{weight} vs {}",
                    s.weight
                );
            }
        }
    }
}

/// The directional albedo `∫ f |cos| dω`, by a Monte Carlo integral over uniform directions on
/// the sphere (not the BSDF's own sampling), equals `albedo()` within four standard errors.
#[test]
fn lambertian_directional_albedo_by_monte_carlo_is_its_albedo() {
    let bsdf = Lambertian {
        albedo: Vec3::new(0.75, 0.3, 1.0),
    };
    let tint = Vec3::new(1.0, 0.5, 0.9);
    let n = 400_000;
    for (k, normal) in NORMALS.into_iter().enumerate() {
        let at = point(normal, tint);
        for cos_o in [1.0, 0.5, 0.05] {
            let wo = direction(normal, cos_o, 0.4);
            let mut rng = Rng::new(5, k as u64);
            let (mut sum, mut sum2) = ([0.0f64; 3], [0.0f64; 3]);
            for _ in 0..n {
                // A uniform direction: z = 1 − 2u, density 1/4π.
                let z = 1.0 - 2.0 * rng.next_f32();
                let wi = direction(normal, z, std::f32::consts::TAU * rng.next_f32());
                let x = bsdf.eval(&at, wo, wi) * wi.dot(normal).abs() * (4.0 * std::f32::consts::PI);
                for c in 0..3 {
                    sum[c] += x[c] as f64;
                    sum2[c] += (x[c] as f64).powi(2);
                }
            }
            let albedo = bsdf.albedo(&at, wo);
            for c in 0..3 {
                let mean = sum[c] / n as f64;
                let se = ((sum2[c] / n as f64 - mean * mean) / n as f64).sqrt();
                assert!(
                    (mean - albedo[c] as f64).abs() < 4.0 * se + 1e-6,
                    "channel {c}, cos θo {cos_o}: Monte Carlo {mean:.5} ± {se:.5}, albedo() {}",
                    albedo[c]
                );
            }
            assert!((albedo - bsdf.albedo * tint).abs().max_element() < 1e-7);
        }
    }
}

/// The mirror reflects `wo` to `2 (n·wo) n − wo` with weight (and albedo) the tinted
/// reflectance, reports no density, and draws no random number.
#[test]
fn mirror_reflects_by_the_law_of_reflection_and_draws_nothing() {
    let bsdf = Mirror {
        reflectance: Vec3::new(0.9, 0.8, 0.3),
    };
    let tint = Vec3::new(0.5, 1.0, 1.0);
    let mut rng = Rng::new(9, 1);
    for normal in NORMALS {
        let at = point(normal, tint);
        for cos_o in [1.0, 0.6, 0.02] {
            let wo = direction(normal, cos_o, 1.3);
            let before = rng.clone();
            let s = bsdf.sample_from(&at, wo, &mut rng).unwrap();
            assert_eq!(rng, before, "the mirror drew a number");
            let truth = 2.0 * normal.dot(wo) * normal - wo;
            assert!((s.wi - truth).length() < 1e-5, "{} vs {truth}", s.wi);
            assert_eq!((s.lobe, s.pdf), (Lobes::DELTA_REFLECTION, 1.0));
            assert!((s.weight - bsdf.reflectance * tint).abs().max_element() < 1e-7);
            assert_eq!(bsdf.albedo(&at, wo), s.weight);
            assert_eq!(
                (bsdf.eval(&at, wo, s.wi), bsdf.pdf(&at, wo, s.wi)),
                (Vec3::ZERO, 0.0)
            );
        }
    }
}

/// Fresnel's reflectance of unpolarised light in its angle form (Born & Wolf), `eta = n_i/n_t`;
/// 1 beyond the critical angle.
fn fresnel_by_angles(cos_i: f64, eta: f64) -> f64 {
    let theta_i = cos_i.acos();
    let sin_t = eta * theta_i.sin();
    if sin_t >= 1.0 {
        return 1.0;
    }
    if theta_i < 1e-6 {
        return ((1.0 - eta) / (1.0 + eta)).powi(2);
    }
    let theta_t = sin_t.asin();
    let rs = (theta_i - theta_t).sin() / (theta_i + theta_t).sin();
    let rp = (theta_i - theta_t).tan() / (theta_i + theta_t).tan();
    0.5 * (rs * rs + rp * rp)
}

/// Over many samples, glass reflects the fraction Fresnel's equations give (within four
/// standard errors), each reflection by the law of reflection and each refraction by Snell's
/// law into the other side; the lobe's reported probability is that reflectance; the mean
/// weight, and `albedo()`, is one. From inside beyond the critical angle, it always reflects
/// and draws nothing.
#[test]
fn glass_reflects_the_fresnel_fraction_and_refracts_by_snell() {
    let ior = 1.5f32;
    let bsdf = Glass { ior };
    let n = 100_000;
    for normal in NORMALS {
        for front_face in [true, false] {
            let at = ShadingPoint {
                front_face,
                ..point(normal, Vec3::new(0.2, 0.3, 0.4))
            };
            let eta = if front_face { 1.0 / ior as f64 } else { ior as f64 };
            for cos_o in [1.0f32, 0.8, 0.5, 0.2] {
                let wo = direction(normal, cos_o, 0.9);
                let fresnel = fresnel_by_angles(cos_o as f64, eta);
                let mut rng = Rng::new(21, (cos_o * 100.0) as u64);
                let (mut reflected, mut weight_sum) = (0usize, Vec3::ZERO);
                for _ in 0..n {
                    let before = rng.clone();
                    let s = bsdf.sample_from(&at, wo, &mut rng).unwrap();
                    weight_sum += s.weight;
                    if s.lobe == Lobes::DELTA_REFLECTION {
                        reflected += 1;
                        assert!((s.wi - (2.0 * normal.dot(wo) * normal - wo)).length() < 1e-5);
                    } else {
                        assert_eq!(s.lobe, Lobes::DELTA_TRANSMISSION);
                        // Snell: sin θt = η sin θi, on the other side.
                        let sin_i = (1.0 - cos_o as f64 * cos_o as f64).sqrt();
                        let cos_t = -s.wi.dot(normal) as f64;
                        let sin_t = (1.0 - cos_t * cos_t).max(0.0).sqrt();
                        assert!(
                            cos_t > 0.0 && (sin_t - eta * sin_i).abs() < 1e-4,
                            "sin θt {sin_t}"
                        );
                    }
                    let p = if s.lobe == Lobes::DELTA_REFLECTION {
                        fresnel
                    } else {
                        1.0 - fresnel
                    };
                    assert!((s.pdf as f64 - p).abs() < 1e-4, "pdf {} vs {p}", s.pdf);
                    if fresnel >= 1.0 {
                        assert_eq!(rng, before, "total internal reflection drew a number");
                    }
                }
                let fraction = reflected as f64 / n as f64;
                let se = (fresnel * (1.0 - fresnel) / n as f64).sqrt();
                assert!(
                    (fraction - fresnel).abs() <= 4.0 * se + 1e-9,
                    "front {front_face}, cos θ {cos_o}: reflected {fraction:.5}, Fresnel {fresnel:.5} ± {se:.5}"
                );
                assert!((weight_sum / n as f32 - bsdf.albedo(&at, wo)).abs().max_element() < 1e-6);
            }
        }
    }
    // Past the critical angle from inside (cos 0.5 < cos θc ≈ 0.745) everything reflects.
    assert_eq!(fresnel_by_angles(0.5, 1.5), 1.0);
}

/// `Material` dispatches to the same BSDF as the built-in types, sample for sample.
#[test]
fn material_variants_sample_as_their_bsdfs() {
    let at = point(NORMALS[1], Vec3::new(0.9, 0.7, 0.5));
    let wo = direction(NORMALS[1], 0.6, 0.3);
    let albedo = Vec3::new(0.3, 0.6, 0.9);
    let pairs: [(Material, &dyn Bsdf); 3] = [
        (Material::Lambertian { albedo }, &Lambertian { albedo }),
        (
            Material::Mirror { reflectance: albedo },
            &Mirror { reflectance: albedo },
        ),
        (Material::Glass { ior: 1.33 }, &Glass { ior: 1.33 }),
    ];
    for (material, bsdf) in pairs {
        assert_eq!(material.lobes(), bsdf.lobes());
        for k in 0..100 {
            let (mut a, mut b) = (Rng::new(4, k), Rng::new(4, k));
            assert_eq!(
                material.sample_from(&at, wo, &mut a),
                bsdf.sample_from(&at, wo, &mut b)
            );
            assert_eq!(a, b);
        }
    }
}
