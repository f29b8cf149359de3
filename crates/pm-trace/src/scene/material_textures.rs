//! A material's parameter textures on a mesh (glTF's `metallicRoughnessTexture`,
//! `KHR_materials_specular`'s `specularTexture` and `specularColorTexture`), each read at its
//! own per-vertex texture coordinates into the [`TextureFactors`] a BSDF multiplies its own
//! parameters by; and the normal map ([`NormalTexture`]), read into the shading normal.

use glam::{Vec2, Vec3};

use super::material_texture::MaterialTexture;
use super::normal_texture::NormalTexture;
use crate::bsdf::shading_point::TextureFactors;

/// The textures of a mesh's material that change its parameters or its normal, each optional.
/// Their texels should be [`crate::TexelEncoding::Linear`] (data, not colour) except the
/// specular colour's, which is sRGB-encoded colour.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct MaterialTextures {
    /// Blue multiplies a [`crate::bsdf::MetallicRoughness`]'s metalness, green its roughness
    /// (glTF's `metallicRoughnessTexture`; red, occlusion in some files, is ignored).
    pub metallic_roughness: Option<MaterialTexture>,
    /// Multiplies its specular strength (`KHR_materials_specular`'s `specularTexture`, whose
    /// value is in the image's alpha channel: the loader copies alpha into all three
    /// channels, and the first is read).
    pub specular: Option<MaterialTexture>,
    /// Multiplies its specular colour per channel (`specularColorTexture`).
    pub specular_color: Option<MaterialTexture>,
    /// Bends the shading normal (glTF's `normalTexture`).
    pub normal: Option<NormalTexture>,
}

impl MaterialTextures {
    /// No texture at all.
    pub fn is_empty(&self) -> bool {
        self.factor_textures().all(|t| t.is_none()) && self.normal.is_none()
    }

    /// The textures that give [`TextureFactors`], in a fixed order.
    fn factor_textures(&self) -> impl Iterator<Item = Option<&MaterialTexture>> {
        [&self.metallic_roughness, &self.specular, &self.specular_color]
            .into_iter()
            .map(Option::as_ref)
    }

    /// Every texture with its own texture coordinates, named (for checks and digests), the
    /// normal map's included.
    pub(crate) fn named(&self) -> [(&'static str, Option<&MaterialTexture>); 4] {
        [
            ("metallic-roughness", self.metallic_roughness.as_ref()),
            ("specular", self.specular.as_ref()),
            ("specular colour", self.specular_color.as_ref()),
            ("normal", self.normal.as_ref().map(|n| &n.map)),
        ]
    }

    /// The factors at barycentric weights `w` of a triangle with corners `corners` and
    /// positions `positions`, averaged over a footprint `footprint` metres across (0: a point
    /// lookup); [`TextureFactors::ONE`] where no texture gives one.
    #[inline]
    pub(crate) fn factors_at(
        &self,
        corners: [u32; 3],
        positions: [Vec3; 3],
        w: Vec3,
        footprint: f32,
    ) -> TextureFactors {
        let read =
            |t: &Option<MaterialTexture>| t.as_ref().map(|t| t.texel_at(corners, positions, w, footprint));
        let mut factors = TextureFactors::ONE;
        if let Some(texel) = read(&self.metallic_roughness) {
            factors.metallic = texel.z;
            factors.roughness = texel.y;
        }
        if let Some(texel) = read(&self.specular) {
            factors.specular = texel.x;
        }
        if let Some(texel) = read(&self.specular_color) {
            factors.specular_color = texel;
        }
        factors
    }

    /// True when some texture gives [`TextureFactors`].
    #[inline]
    pub(crate) fn has_factors(&self) -> bool {
        self.factor_textures().any(|t| t.is_some())
    }

    /// Heap bytes of the texture coordinates and tangents (the images are shared and counted
    /// with the scene's textures).
    pub(crate) fn heap_bytes(&self) -> usize {
        self.named()
            .iter()
            .filter_map(|(_, t)| *t)
            .map(|t| t.uvs.capacity() * size_of::<Vec2>())
            .sum::<usize>()
            + self.normal.as_ref().map_or(0, NormalTexture::tangent_heap_bytes)
    }
}
