//! glTF materials to the renderer's three materials plus emission; the mapping is documented
//! on [`GltfMaterial`] and in the module docs of [`crate::gltf`].

use glam::Vec3;
use gltf::json;

use super::options::GltfOptions;
use super::texture_ref::TextureRef;
use crate::material::Material;

/// A glTF material as this loader reads it.
///
/// - `KHR_materials_transmission` with `transmissionFactor ≥ 0.5` → [`Material::Glass`]
///   with `KHR_materials_ior` (default 1.5; values below 1 also give 1.5);
/// - else `metallicFactor ≥ 0.9` and `roughnessFactor ≤ 0.1` → [`Material::Mirror`] with
///   the base colour as reflectance;
/// - else [`Material::Lambertian`] with the base colour factor as albedo.
///
/// The base-colour and emissive textures are read (with `KHR_texture_transform`). `emission`
/// is `emissiveFactor × emissiveStrength ×`
/// [`LightUnits::emission_factor`](super::LightUnits::emission_factor) `×`
/// [`GltfOptions::emission_scale`], a radiance in W/(m²·sr), which the emissive texture (if
/// any) multiplies at each point.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct GltfMaterial {
    /// How the surface scatters light.
    pub kind: Material,
    /// Emitted radiance in W/(m²·sr); zero for a surface that does not glow.
    pub emission: Vec3,
    /// The base-colour texture, its `TEXCOORD` set and `KHR_texture_transform`, if the
    /// material has one; its texels multiply the base colour factor.
    pub base_color_texture: Option<TextureRef>,
    /// The emissive texture, its `TEXCOORD` set and `KHR_texture_transform`, if the material
    /// has one; its texels multiply `emission`.
    pub emissive_texture: Option<TextureRef>,
    /// The glTF `doubleSided` flag: when set, an emissive surface emits from both sides
    /// ([`crate::Sides::Double`]); when clear, camera rays pass through its back
    /// ([`crate::Sides::Single`]).
    pub double_sided: bool,
}

/// Mirror threshold on `metallicFactor`.
const MIRROR_MIN_METALLIC: f32 = 0.9;
/// Mirror threshold on `roughnessFactor`.
const MIRROR_MAX_ROUGHNESS: f32 = 0.1;
/// Glass threshold on `transmissionFactor`.
const GLASS_MIN_TRANSMISSION: f32 = 0.5;
/// `KHR_materials_ior`'s default.
const DEFAULT_IOR: f32 = 1.5;

fn finite_or(x: f32, default: f32) -> f32 {
    if x.is_finite() { x } else { default }
}

fn clamp01(v: Vec3) -> Vec3 {
    Vec3::new(finite_or(v.x, 0.0), finite_or(v.y, 0.0), finite_or(v.z, 0.0)).clamp(Vec3::ZERO, Vec3::ONE)
}

/// Maps a glTF material (or the spec's default material for `None`).
pub(super) fn map_material(
    material: Option<&json::Material>,
    options: &GltfOptions,
) -> Result<GltfMaterial, String> {
    let Some(m) = material else {
        // The glTF default material: white base colour, metallic 1, roughness 1.
        return Ok(GltfMaterial {
            kind: Material::Lambertian { albedo: Vec3::ONE },
            emission: Vec3::ZERO,
            base_color_texture: None,
            emissive_texture: None,
            double_sided: false,
        });
    };
    let pbr = &m.pbr_metallic_roughness;
    let [r, g, b, _] = pbr.base_color_factor.0;
    let base = clamp01(Vec3::new(r, g, b));
    let metallic = finite_or(pbr.metallic_factor.0, 1.0);
    let roughness = finite_or(pbr.roughness_factor.0, 1.0);
    let ext = m.extensions.as_ref();
    let transmission = ext
        .and_then(|e| e.transmission.as_ref())
        .map_or(0.0, |t| finite_or(t.transmission_factor.0, 0.0));
    let ior = ext.and_then(|e| e.ior.as_ref()).map_or(DEFAULT_IOR, |i| i.ior.0);
    let ior = if ior.is_finite() && ior >= 1.0 {
        ior
    } else {
        DEFAULT_IOR
    };
    let strength = ext
        .and_then(|e| e.emissive_strength.as_ref())
        .map_or(1.0, |s| s.emissive_strength.0);
    // An infinite or negative emission is a broken file, not a black emitter: refused.
    if !(strength.is_finite() && strength >= 0.0) {
        return Err(format!(
            "emissive strength {strength} must be finite and not negative"
        ));
    }
    let factor = Vec3::from(m.emissive_factor.0);
    if !(factor.is_finite() && factor.min_element() >= 0.0) {
        return Err(format!(
            "emissive factor {factor} must be finite and not negative"
        ));
    }
    let emission = factor * strength * options.light_units.emission_factor() * options.emission_scale;
    if !(emission.is_finite() && emission.min_element() >= 0.0) {
        return Err(format!(
            "emission {emission} (emissive factor {factor} × strength {strength} × the options' scale) must be finite and not negative"
        ));
    }
    let kind = if transmission >= GLASS_MIN_TRANSMISSION {
        Material::Glass { ior }
    } else if metallic >= MIRROR_MIN_METALLIC && roughness <= MIRROR_MAX_ROUGHNESS {
        Material::Mirror { reflectance: base }
    } else {
        Material::Lambertian { albedo: base }
    };
    Ok(GltfMaterial {
        kind,
        emission,
        base_color_texture: pbr.base_color_texture.as_ref().map(TextureRef::from_info),
        emissive_texture: m.emissive_texture.as_ref().map(TextureRef::from_info),
        double_sided: m.double_sided,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    fn kind_of(json: &str) -> Material {
        let m: json::Material = material_from(json);
        map_material(Some(&m), &GltfOptions::default()).unwrap().kind
    }

    fn material_from(text: &str) -> json::Material {
        json::deserialize::from_str(text).expect("test material parses")
    }

    #[test]
    fn thresholds_split_mirror_glass_and_diffuse() {
        let pbr = |m: f32, r: f32| {
            format!(r#"{{"pbrMetallicRoughness":{{"metallicFactor":{m},"roughnessFactor":{r}}}}}"#)
        };
        assert!(matches!(kind_of(&pbr(0.9, 0.1)), Material::Mirror { .. }));
        assert!(matches!(kind_of(&pbr(0.89, 0.1)), Material::Lambertian { .. }));
        assert!(matches!(kind_of(&pbr(1.0, 0.11)), Material::Lambertian { .. }));
        // The glTF defaults are metallic 1, roughness 1: diffuse, white.
        assert_eq!(kind_of("{}"), Material::Lambertian { albedo: Vec3::ONE });
        let glass = |t: f32, ior: &str| {
            format!(r#"{{"extensions":{{"KHR_materials_transmission":{{"transmissionFactor":{t}}}{ior}}}}}"#)
        };
        assert_eq!(kind_of(&glass(0.5, "")), Material::Glass { ior: 1.5 });
        assert_eq!(
            kind_of(&glass(1.0, r#","KHR_materials_ior":{"ior":2.4}"#)),
            Material::Glass { ior: 2.4 }
        );
        assert!(matches!(kind_of(&glass(0.49, "")), Material::Lambertian { .. }));
    }

    #[test]
    fn emission_is_factor_times_strength_times_scale() {
        let m = material_from(
            r#"{"emissiveFactor":[1,0.5,0],"extensions":{"KHR_materials_emissive_strength":{"emissiveStrength":4}}}"#,
        );
        let options = GltfOptions {
            emission_scale: 0.5,
            ..GltfOptions::default()
        };
        assert_eq!(
            map_material(Some(&m), &options).unwrap().emission,
            Vec3::new(2.0, 1.0, 0.0)
        );
        // Without the extension the strength is 1; colours above 1 are clamped for albedo.
        let m = material_from(
            r#"{"emissiveFactor":[0.25,0.25,0.25],"pbrMetallicRoughness":{"baseColorFactor":[2,0.5,-1,1],"metallicFactor":0}}"#,
        );
        let mapped = map_material(Some(&m), &GltfOptions::default()).unwrap();
        assert_eq!(mapped.emission, Vec3::splat(0.25));
        assert_eq!(
            mapped.kind,
            Material::Lambertian {
                albedo: Vec3::new(1.0, 0.5, 0.0)
            }
        );
    }

    #[test]
    fn infinite_or_negative_emission_is_refused_not_black() {
        let strength = |s: &str| {
            material_from(&format!(
                r#"{{"emissiveFactor":[1,1,1],"extensions":{{"KHR_materials_emissive_strength":{{"emissiveStrength":{s}}}}}}}"#
            ))
        };
        for (m, needle) in [
            (strength("-2"), "strength"),
            (strength("1e39"), "strength"),
            (material_from(r#"{"emissiveFactor":[1e39,0,0]}"#), "factor"),
            (material_from(r#"{"emissiveFactor":[-1,0,0]}"#), "factor"),
            // Each finite, the product not.
            (
                material_from(
                    r#"{"emissiveFactor":[2,2,2],"extensions":{"KHR_materials_emissive_strength":{"emissiveStrength":3e38}}}"#,
                ),
                "emission",
            ),
        ] {
            let err = map_material(Some(&m), &GltfOptions::default()).unwrap_err();
            assert!(err.contains(needle), "{err}");
        }
        assert!(map_material(Some(&strength("1e30")), &GltfOptions::default()).is_ok());
    }
}
