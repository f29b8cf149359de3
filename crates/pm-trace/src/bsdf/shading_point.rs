//! The surface point a BSDF is evaluated at: its position, geometric and shading normals, side,
//! texture tint and textured material factors, all a world-space BSDF needs from the hit
//! (`Scene::shading_point` makes it).

use glam::Vec3;

/// Where a [`super::Bsdf`] is evaluated: a hit's local geometry and texture tint.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ShadingPoint {
    /// The hit point.
    pub position: Vec3,
    /// Unit geometric normal, on the side `wo` leaves to (the side the ray came from).
    pub geometric: Vec3,
    /// Unit shading normal (interpolated vertex normals, else the geometric normal), on the
    /// geometric normal's side. Lobes are shaped about it.
    pub shading: Vec3,
    /// True when the side the surface's own normal points to was hit (the outside of glass).
    pub front_face: bool,
    /// The base-colour texture and vertex colours at the point (one where the mesh has none):
    /// the built-ins multiply their reflectance by it.
    pub tint: Vec3,
    /// The material's parameter textures at the point (all one where the mesh has none):
    /// [`crate::bsdf::MetallicRoughness`] multiplies its factors by them.
    pub factors: TextureFactors,
}

/// What a material's parameter textures say at a point, as factors of the material's own
/// parameters (glTF's `metallicRoughnessTexture`: blue channel × `metallicFactor`, green ×
/// `roughnessFactor`; `KHR_materials_specular`'s `specularTexture`: alpha × `specularFactor`,
/// and `specularColorTexture`: RGB × `specularColorFactor`). Each in `[0, 1]`;
/// [`TextureFactors::ONE`] leaves the material as it is.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct TextureFactors {
    /// Multiplies the metalness.
    pub metallic: f32,
    /// Multiplies the perceptual roughness.
    pub roughness: f32,
    /// Multiplies the dielectric's specular strength.
    pub specular: f32,
    /// Multiplies the dielectric's specular colour, per channel.
    pub specular_color: Vec3,
}

impl TextureFactors {
    /// No texture: every factor one.
    pub const ONE: TextureFactors = TextureFactors {
        metallic: 1.0,
        roughness: 1.0,
        specular: 1.0,
        specular_color: Vec3::ONE,
    };
}

impl ShadingPoint {
    /// An untextured front-face point at the origin whose geometric and shading normal is the
    /// unit `normal` (for tests and for evaluating a BSDF away from a scene).
    #[inline]
    pub fn facing(normal: Vec3) -> Self {
        ShadingPoint {
            position: Vec3::ZERO,
            geometric: normal,
            shading: normal,
            front_face: true,
            tint: Vec3::ONE,
            factors: TextureFactors::ONE,
        }
    }
}
