//! glTF materials to the renderer's materials plus emission and texture references; the
//! mapping is documented on [`GltfMaterial`] and in the module docs of [`crate::gltf`].

use glam::Vec3;
use gltf::json;

use super::options::GltfOptions;
use super::scattering::{default_scattering, scattering};
use super::texture_ref::TextureRef;
use crate::material::Material;

/// A glTF material as this loader reads it.
///
/// `kind` follows glTF 2.0's Appendix B (see the module docs of [`crate::gltf`] for the table):
///
/// - `(1 − metallicFactor) · KHR_materials_transmission`'s `transmissionFactor ≥ 0.5` →
///   [`Material::Glass`] with `KHR_materials_ior` (default 1.5; values below 1 also give 1.5):
///   smooth, colourless, whatever its roughness (an approximation);
/// - else `metallicFactor` 0 and `KHR_materials_specular`'s `specularFactor` 0 (how a file says
///   "pure Lambertian") → [`Material::Lambertian`] with the base colour factor as albedo;
/// - else [`Material::MetallicRoughness`] with the base colour, metallic and roughness factors,
///   `KHR_materials_ior` and `KHR_materials_specular`'s factor and colour — at every roughness
///   (0 is GGX at [`MIN_ALPHA`](crate::bsdf::MIN_ALPHA), not a mirror) and metalness. glTF's
///   default material (none named) is white, metallic 1, roughness 1: a rough white metal.
///
/// The base-colour, metallic-roughness, specular, specular-colour, normal and emissive textures
/// are read (with `KHR_texture_transform`). `emission` is `emissiveFactor × emissiveStrength ×`
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
    /// material has one; its texels multiply the base colour factor (of every kind but glass).
    pub base_color_texture: Option<TextureRef>,
    /// The metallic-roughness texture, if the material has one and `kind` is
    /// [`Material::MetallicRoughness`] (for the other kinds it would change nothing); its
    /// blue channel multiplies the metallic factor and its green channel the roughness factor
    /// at each point, read as linear values.
    pub metallic_roughness_texture: Option<TextureRef>,
    /// `KHR_materials_specular`'s `specularTexture` (its alpha channel, linear, multiplies
    /// the specular factor), kept as the metallic-roughness texture is.
    pub specular_texture: Option<TextureRef>,
    /// `KHR_materials_specular`'s `specularColorTexture` (sRGB colour multiplying the
    /// specular colour factor), kept as the metallic-roughness texture is.
    pub specular_color_texture: Option<TextureRef>,
    /// The normal map and its `scale`, for every kind (a bent shading normal changes glass
    /// and Lambertian surfaces too).
    pub normal_texture: Option<(TextureRef, f32)>,
    /// The emissive texture, its `TEXCOORD` set and `KHR_texture_transform`, if the material
    /// has one; its texels multiply `emission`.
    pub emissive_texture: Option<TextureRef>,
    /// The glTF `doubleSided` flag: when set, an emissive surface emits from both sides
    /// ([`crate::Sides::Double`]); when clear, camera rays pass through its back
    /// ([`crate::Sides::Single`]).
    pub double_sided: bool,
}

/// Maps a glTF material (or the spec's default material for `None`), whose normal texture's
/// `KHR_texture_transform` is `normal_transform` (read apart: see `normal_transform.rs`).
pub(super) fn map_material(
    material: Option<&json::Material>,
    normal_transform: Option<&json::extensions::texture::TextureTransform>,
    options: &GltfOptions,
) -> Result<GltfMaterial, String> {
    let Some(m) = material else {
        // The glTF default material: white base colour, metallic 1, roughness 1.
        return Ok(GltfMaterial {
            kind: default_scattering(),
            emission: Vec3::ZERO,
            base_color_texture: None,
            metallic_roughness_texture: None,
            specular_texture: None,
            specular_color_texture: None,
            normal_texture: None,
            emissive_texture: None,
            double_sided: false,
        });
    };
    let pbr = &m.pbr_metallic_roughness;
    let ext = m.extensions.as_ref();
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
    let kind = scattering(m).map_err(|e| e.to_string())?;
    // Parameter textures change only the metallic-roughness kind.
    let parameter = |info: Option<&json::texture::Info>| match kind {
        Material::MetallicRoughness(_) => info.map(TextureRef::from_info),
        _ => None,
    };
    let specular = ext.and_then(|e| e.specular.as_ref());
    Ok(GltfMaterial {
        kind,
        emission,
        metallic_roughness_texture: parameter(pbr.metallic_roughness_texture.as_ref()),
        specular_texture: parameter(specular.and_then(|s| s.specular_texture.as_ref())),
        specular_color_texture: parameter(specular.and_then(|s| s.specular_color_texture.as_ref())),
        normal_texture: m
            .normal_texture
            .as_ref()
            .map(|n| TextureRef::from_normal(n, normal_transform)),
        base_color_texture: pbr.base_color_texture.as_ref().map(TextureRef::from_info),
        emissive_texture: m.emissive_texture.as_ref().map(TextureRef::from_info),
        double_sided: m.double_sided,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    fn material_from(text: &str) -> json::Material {
        json::deserialize::from_str(text).expect("test material parses")
    }

    #[test]
    fn metallic_roughness_texture_is_kept_only_where_it_changes_something() {
        let texture = r#""metallicRoughnessTexture":{"index":3,"texCoord":1}"#;
        let mapped = |extra: &str| {
            let m = material_from(&format!(
                r#"{{"pbrMetallicRoughness":{{"metallicFactor":0,{texture}}}{extra}}}"#
            ));
            map_material(Some(&m), None, &GltfOptions::default()).unwrap()
        };
        let reference = mapped("").metallic_roughness_texture.unwrap();
        assert_eq!((reference.index, reference.tex_coord), (3, 1));
        assert!(matches!(mapped("").kind, Material::MetallicRoughness(_)));
        // Metallic 0 and specular 0: Lambertian whatever the texture says (factor × texel = 0).
        let lambertian = mapped(r#","extensions":{"KHR_materials_specular":{"specularFactor":0}}"#);
        assert_eq!(lambertian.kind, Material::Lambertian { albedo: Vec3::ONE });
        assert_eq!(lambertian.metallic_roughness_texture, None);
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
            map_material(Some(&m), None, &options).unwrap().emission,
            Vec3::new(2.0, 1.0, 0.0)
        );
        // Without the extension the strength is 1; colours above 1 are clamped.
        let m = material_from(
            r#"{"emissiveFactor":[0.25,0.25,0.25],"pbrMetallicRoughness":{"baseColorFactor":[2,0.5,-1,1],"metallicFactor":0}}"#,
        );
        let mapped = map_material(Some(&m), None, &GltfOptions::default()).unwrap();
        assert_eq!(mapped.emission, Vec3::splat(0.25));
        assert_eq!(
            mapped.kind,
            Material::MetallicRoughness(
                crate::bsdf::metallic_roughness::MetallicRoughness::new(Vec3::new(1.0, 0.5, 0.0), 0.0, 1.0)
                    .unwrap()
            )
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
            let err = map_material(Some(&m), None, &GltfOptions::default()).unwrap_err();
            assert!(err.contains(needle), "{err}");
        }
        assert!(map_material(Some(&strength("1e30")), None, &GltfOptions::default()).is_ok());
    }
}
