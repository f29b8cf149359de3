//! How a glTF material scatters light: glTF 2.0's metallic-roughness model (Appendix B, with
//! `KHR_materials_ior` and `KHR_materials_specular`) as the renderer's [`Material`], smooth
//! glass for transmission, and Lambertian where the file asks for a pure diffuse surface.

use glam::Vec3;
use gltf::json;

use crate::bsdf::metallic_roughness::MetallicRoughness;
use crate::error::MaterialError;
use crate::material::Material;

/// `KHR_materials_ior`'s default.
pub(super) const DEFAULT_IOR: f32 = 1.5;

/// The transmitted share of the dielectric, `(1 − metallic) · transmissionFactor`, from which a
/// material becomes smooth [`Material::Glass`] (the renderer has no partly transmitting or
/// rough dielectric yet; see the module docs of [`crate::gltf`]).
pub(super) const GLASS_MIN_TRANSMISSION: f32 = 0.5;

/// `x` when finite, else `default`.
pub(super) fn finite_or(x: f32, default: f32) -> f32 {
    if x.is_finite() { x } else { default }
}

/// `x` clamped to `[0, 1]` (a NaN reads as `default`).
fn unit_or(x: f32, default: f32) -> f32 {
    finite_or(x, default).clamp(0.0, 1.0)
}

/// Each channel clamped to `[0, 1]`; a non-finite channel reads as 0.
pub(super) fn clamp01(v: Vec3) -> Vec3 {
    Vec3::new(finite_or(v.x, 0.0), finite_or(v.y, 0.0), finite_or(v.z, 0.0)).clamp(Vec3::ZERO, Vec3::ONE)
}

/// The scattering of glTF's default material (no `material` on a primitive): white,
/// metallic 1, roughness 1 — under Appendix B a rough white metal.
pub(super) fn default_scattering() -> Material {
    Material::MetallicRoughness(
        MetallicRoughness::new(Vec3::ONE, 1.0, 1.0).expect("glTF's default factors are in range"),
    )
}

/// The renderer's material for `m`'s factors (its textures are read per hit elsewhere):
///
/// - `(1 − metallic) · transmissionFactor ≥` [`GLASS_MIN_TRANSMISSION`] → [`Material::Glass`]
///   with `KHR_materials_ior` (1.5 without it or when it is below 1, 0 included);
/// - else metallic 0 and `KHR_materials_specular`'s `specularFactor` 0 → [`Material::Lambertian`]
///   of the base colour (Appendix B's BRDF is then exactly `baseColor/π`);
/// - else [`Material::MetallicRoughness`] with the base colour, metallic, roughness, ior (0
///   allowed, as the extension says) and specular factor and colour.
///
/// Out-of-range factors are clamped as glTF viewers clamp them: colours and metallic,
/// roughness, transmission and specular to `[0, 1]`, the specular colour to non-negative;
/// non-finite ones read as their defaults (a base colour channel as 0).
pub(super) fn scattering(m: &json::Material) -> Result<Material, MaterialError> {
    let pbr = &m.pbr_metallic_roughness;
    let [r, g, b, _] = pbr.base_color_factor.0;
    let base = clamp01(Vec3::new(r, g, b));
    let metallic = unit_or(pbr.metallic_factor.0, 1.0);
    let roughness = unit_or(pbr.roughness_factor.0, 1.0);
    let ext = m.extensions.as_ref();
    let transmission = ext
        .and_then(|e| e.transmission.as_ref())
        .map_or(0.0, |t| unit_or(t.transmission_factor.0, 0.0));
    let ior = ext.and_then(|e| e.ior.as_ref()).map_or(DEFAULT_IOR, |i| i.ior.0);
    if (1.0 - metallic) * transmission >= GLASS_MIN_TRANSMISSION {
        let ior = if ior.is_finite() && ior >= 1.0 {
            ior
        } else {
            DEFAULT_IOR
        };
        return Ok(Material::Glass { ior });
    }
    let (specular, specular_color) = ext
        .and_then(|e| e.specular.as_ref())
        .map_or((1.0, Vec3::ONE), |s| {
            let [r, g, b] = s.specular_color_factor.0.map(|c| finite_or(c, 1.0).max(0.0));
            (unit_or(s.specular_factor.0, 1.0), Vec3::new(r, g, b))
        });
    if metallic == 0.0 && specular == 0.0 {
        return Ok(Material::Lambertian { albedo: base });
    }
    let ior = if ior == 0.0 || (ior.is_finite() && ior >= 1.0) {
        ior
    } else {
        DEFAULT_IOR
    };
    Ok(Material::MetallicRoughness(
        MetallicRoughness::new(base, metallic, roughness)?
            .with_ior(ior)?
            .with_specular(specular, specular_color)?,
    ))
}

#[cfg(test)]
mod tests {
    use super::*;

    fn kind_of(text: &str) -> Material {
        let m: json::Material = json::deserialize::from_str(text).expect("test material parses");
        scattering(&m).unwrap()
    }

    fn pbr(metallic: f32, roughness: f32) -> String {
        format!(r#"{{"pbrMetallicRoughness":{{"metallicFactor":{metallic},"roughnessFactor":{roughness}}}}}"#)
    }

    fn mr(base: Vec3, metallic: f32, roughness: f32) -> MetallicRoughness {
        MetallicRoughness::new(base, metallic, roughness).unwrap()
    }

    #[test]
    fn defaults_are_a_rough_white_metal_not_lambertian() {
        // glTF 2.0: baseColorFactor [1,1,1,1], metallicFactor 1, roughnessFactor 1.
        let want = Material::MetallicRoughness(mr(Vec3::ONE, 1.0, 1.0));
        assert_eq!(kind_of("{}"), want);
        assert_eq!(kind_of(r#"{"pbrMetallicRoughness":{}}"#), want);
        assert_eq!(default_scattering(), want);
    }

    #[test]
    fn factors_map_one_to_one_without_thresholds() {
        let text = r#"{"pbrMetallicRoughness":{"baseColorFactor":[0.8,0.4,0.2,1],"metallicFactor":0.9,"roughnessFactor":0.1}}"#;
        assert_eq!(
            kind_of(text),
            Material::MetallicRoughness(mr(Vec3::new(0.8, 0.4, 0.2), 0.9, 0.1))
        );
        // A rough metal stays a metal; a smooth one stays GGX (at MIN_ALPHA), not a mirror.
        for (m, r) in [(1.0, 0.8), (1.0, 0.0), (0.5, 0.5), (0.0, 1.0), (0.0, 0.0)] {
            assert_eq!(
                kind_of(&pbr(m, r)),
                Material::MetallicRoughness(mr(Vec3::ONE, m, r)),
                "metallic {m} roughness {r}"
            );
        }
        // Out of range: clamped as viewers do.
        assert_eq!(
            kind_of(
                r#"{"pbrMetallicRoughness":{"baseColorFactor":[2,0.5,-1,1],"metallicFactor":1.5,"roughnessFactor":-0.5}}"#
            ),
            Material::MetallicRoughness(mr(Vec3::new(1.0, 0.5, 0.0), 1.0, 0.0))
        );
    }

    #[test]
    fn ior_and_specular_extensions_reach_the_bsdf() {
        let text = r#"{"pbrMetallicRoughness":{"metallicFactor":0.25,"roughnessFactor":0.5},
            "extensions":{"KHR_materials_ior":{"ior":1.8},
            "KHR_materials_specular":{"specularFactor":0.7,"specularColorFactor":[1,0.5,2]}}}"#;
        let want = mr(Vec3::ONE, 0.25, 0.5)
            .with_ior(1.8)
            .unwrap()
            .with_specular(0.7, Vec3::new(1.0, 0.5, 2.0))
            .unwrap();
        assert_eq!(kind_of(text), Material::MetallicRoughness(want));
        // f0 = ((1.8 − 1)/(1.8 + 1))² · colour, clamped to 1, · 0.7.
        let r = (0.8f32 / 2.8).powi(2);
        let f0 = (r * Vec3::new(1.0, 0.5, 2.0)).min(Vec3::ONE) * 0.7;
        assert!((want.dielectric_f0() - f0).abs().max_element() < 1e-6, "{f0}");
        // ior 0 is the extension's own value (f0 = 1); other values below 1 read as 1.5.
        let ior = |v: &str| {
            kind_of(&format!(
                r#"{{"pbrMetallicRoughness":{{"metallicFactor":0}},"extensions":{{"KHR_materials_ior":{{"ior":{v}}}}}}}"#
            ))
        };
        assert_eq!(
            ior("0"),
            Material::MetallicRoughness(mr(Vec3::ONE, 0.0, 1.0).with_ior(0.0).unwrap())
        );
        assert_eq!(ior("0.5"), Material::MetallicRoughness(mr(Vec3::ONE, 0.0, 1.0)));
    }

    #[test]
    fn specular_zero_dielectric_is_lambertian_of_the_base_colour() {
        let text = r#"{"pbrMetallicRoughness":{"baseColorFactor":[0.7,0.12,0.08,1],"metallicFactor":0,"roughnessFactor":0.3},
            "extensions":{"KHR_materials_specular":{"specularFactor":0}}}"#;
        assert_eq!(
            kind_of(text),
            Material::Lambertian {
                albedo: Vec3::new(0.7, 0.12, 0.08)
            }
        );
        // Any metal keeps its specular lobe (metals ignore the dielectric's specular factor).
        let metal = r#"{"pbrMetallicRoughness":{"metallicFactor":0.01},
            "extensions":{"KHR_materials_specular":{"specularFactor":0}}}"#;
        assert_eq!(
            kind_of(metal),
            Material::MetallicRoughness(mr(Vec3::ONE, 0.01, 1.0).with_specular(0.0, Vec3::ONE).unwrap())
        );
    }

    #[test]
    fn transmission_of_the_dielectric_share_is_smooth_glass() {
        let glass = |metallic: f32, t: f32, ior: &str| {
            kind_of(&format!(
                r#"{{"pbrMetallicRoughness":{{"metallicFactor":{metallic},"roughnessFactor":0.4}},"extensions":{{"KHR_materials_transmission":{{"transmissionFactor":{t}}}{ior}}}}}"#
            ))
        };
        assert_eq!(glass(0.0, 0.5, ""), Material::Glass { ior: 1.5 });
        assert_eq!(
            glass(0.0, 1.0, r#","KHR_materials_ior":{"ior":2.4}"#),
            Material::Glass { ior: 2.4 }
        );
        assert_eq!(
            glass(0.0, 1.0, r#","KHR_materials_ior":{"ior":0}"#),
            Material::Glass { ior: 1.5 }
        );
        assert_eq!(
            glass(0.0, 0.49, ""),
            Material::MetallicRoughness(mr(Vec3::ONE, 0.0, 0.4))
        );
        // A metal does not transmit: mix(dielectric, metal, metallic) leaves (1 − m) · t.
        assert_eq!(
            glass(1.0, 1.0, ""),
            Material::MetallicRoughness(mr(Vec3::ONE, 1.0, 0.4))
        );
        assert_eq!(glass(0.4, 1.0, ""), Material::Glass { ior: 1.5 });
        assert_eq!(
            glass(0.6, 1.0, ""),
            Material::MetallicRoughness(mr(Vec3::ONE, 0.6, 0.4))
        );
    }
}
