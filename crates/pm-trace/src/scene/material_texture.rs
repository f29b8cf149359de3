//! One texture of a material on a mesh, read at its own per-vertex texture coordinates (at a
//! point or averaged over a footprint).

use std::sync::Arc;

use glam::{Vec2, Vec3};

use crate::sampler::Sampler;
use crate::texture::Texture;

/// One texture of a material's parameters, with its own texture coordinates per vertex of the
/// mesh (glTF convention: v grows down the image).
#[derive(Clone, Debug, PartialEq)]
pub struct MaterialTexture {
    /// Texture coordinates per vertex of the mesh.
    pub uvs: Vec<Vec2>,
    /// The image, shared with every other mesh or material that uses it.
    pub texture: Arc<Texture>,
    /// Wrap modes and filter.
    pub sampler: Sampler,
}

impl MaterialTexture {
    /// The texel at barycentric weights `w` of a triangle with corners `corners` (indices of
    /// this texture's `uvs`) and positions `positions`, averaged over a footprint `footprint`
    /// metres across (0: a point lookup).
    #[inline]
    pub(crate) fn texel_at(&self, corners: [u32; 3], positions: [Vec3; 3], w: Vec3, footprint: f32) -> Vec3 {
        let [ta, tb, tc] = corners.map(|i| self.uvs[i as usize]);
        let uv = ta * w.x + tb * w.y + tc * w.z;
        if footprint > 0.0 {
            let texels = texels_across(&self.texture, positions, [ta, tb, tc], footprint);
            self.sampler.sample_footprint(&self.texture, uv, texels)
        } else {
            self.sampler.sample(&self.texture, uv)
        }
    }
}

/// How many texels of `texture` a footprint `footprint` metres across covers on a triangle
/// with corners `positions` and texture coordinates `uvs`: texture units per metre (the square
/// root of the ratio of its areas in texture and in space) times texels per texture unit.
#[inline]
pub(crate) fn texels_across(texture: &Texture, positions: [Vec3; 3], uvs: [Vec2; 3], footprint: f32) -> f32 {
    let [a, b, c] = positions;
    let [ta, tb, tc] = uvs;
    let uv_area = (tb - ta).perp_dot(tc - ta).abs();
    let area = (b - a).cross(c - a).length();
    let per_metre = (uv_area / area).sqrt() * (texture.width() as f32 * texture.height() as f32).sqrt();
    footprint * per_metre
}
