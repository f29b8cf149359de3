//! Emission textures: a texture that multiplies a mesh's emitted radiance, and the fixed
//! quadrature that gives each emitting triangle its mean emission (for light power and
//! light selection).

use std::sync::Arc;

use glam::{DVec3, Vec2, Vec3};

use crate::sampler::Sampler;
use crate::texture::Texture;

/// A texture multiplying a mesh's emission ([`crate::Surface::emission`]) at each point,
/// read at per-vertex texture coordinates with `sampler` (glTF's `emissiveTexture`; the
/// texels are sRGB-encoded and read as linear values, as base-colour textures are).
#[derive(Clone, Debug, PartialEq)]
pub struct EmissionTexture {
    /// Texture coordinates per vertex of the mesh (glTF convention: v grows down the image).
    pub uvs: Vec<Vec2>,
    /// The image, shared with every other mesh or material that uses it.
    pub texture: Arc<Texture>,
    /// Wrap modes and filter.
    pub sampler: Sampler,
}

impl EmissionTexture {
    /// The texture's linear value at barycentric weights `w` of a triangle whose corners have
    /// texture coordinates `uvs`.
    #[inline]
    pub fn at(&self, uvs: [Vec2; 3], w: Vec3) -> Vec3 {
        self.sampler
            .sample(&self.texture, uvs[0] * w.x + uvs[1] * w.y + uvs[2] * w.z)
    }
}

/// Most texture lookups spent on the per-triangle means of one light (2²², a few tens of
/// milliseconds): a light of many triangles gets fewer points per triangle, at least one.
pub const MEAN_LOOKUP_BUDGET: u64 = 1 << 22;

/// Most subdivisions per triangle edge (256² = 65,536 lookups for one triangle).
pub const MAX_SUBDIVISIONS: u32 = 256;

/// The subdivision `m` (per edge, `m²` equal sub-triangles) for a triangle with corner
/// coordinates `uvs` on `texture`: about two sub-triangles per texel along each edge, at most
/// `limit`.
pub fn subdivisions(texture: &Texture, uvs: [Vec2; 3], limit: u32) -> u32 {
    let size = Vec2::new(texture.width() as f32, texture.height() as f32);
    let longest = (0..3)
        .map(|i| ((uvs[(i + 1) % 3] - uvs[i]) * size).abs().max_element())
        .fold(0.0f32, f32::max);
    let m = (2.0 * longest).ceil();
    if m.is_finite() {
        (m as u32).clamp(1, limit.max(1))
    } else {
        limit.max(1)
    }
}

/// The mean of `texture` over a triangle with corner coordinates `uvs`, by the centroid rule on
/// its regular subdivision into `m²` sub-triangles of equal area (exact for a texture that is
/// linear over each sub-triangle; bilinear filtering is piecewise bilinear, so the error
/// falls as `1/m²` and [`subdivisions`] puts about two sub-triangles on a texel).
pub fn triangle_mean(texture: &EmissionTexture, uvs: [Vec2; 3], m: u32) -> Vec3 {
    let m = m.max(1);
    let inv = 1.0 / m as f32;
    let mut sum = DVec3::ZERO;
    let mut add = |s: f32, t: f32| {
        sum += texture.at(uvs, Vec3::new(1.0 - s - t, s, t)).as_dvec3();
    };
    for i in 0..m {
        for j in 0..m - i {
            let (i, j) = (i as f32, j as f32);
            // The sub-triangle pointing like the whole one, then (where it exists) the
            // inverted one sharing its long edge.
            add((i + 1.0 / 3.0) * inv, (j + 1.0 / 3.0) * inv);
            if i + j + 1.0 < m as f32 {
                add((i + 2.0 / 3.0) * inv, (j + 2.0 / 3.0) * inv);
            }
        }
    }
    (sum / (m as f64 * m as f64)).as_vec3()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::sampler::Wrap;

    fn gradient() -> EmissionTexture {
        // Linear values 0, 1/3, 2/3, 1 are not 8-bit sRGB codes; use the codes' own values.
        let texels = [0u8, 90, 170, 255].iter().map(|&c| [c; 3]).collect();
        EmissionTexture {
            uvs: Vec::new(),
            texture: Arc::new(Texture::from_srgb8(4, 1, texels).unwrap()),
            sampler: Sampler {
                wrap_u: Wrap::ClampToEdge,
                wrap_v: Wrap::ClampToEdge,
                nearest: true,
            },
        }
    }

    #[test]
    fn subdivision_counts_are_m_squared_and_cover_the_triangle_evenly() {
        // A constant texture integrates to itself at every m.
        let mut t = gradient();
        t.texture = Arc::new(Texture::from_srgb8(1, 1, vec![[255; 3]]).unwrap());
        for m in [1, 2, 3, 7] {
            let mean = triangle_mean(&t, [Vec2::ZERO, Vec2::X, Vec2::Y], m);
            assert!((mean - Vec3::ONE).abs().max_element() < 1e-6, "m {m}: {mean}");
        }
    }

    #[test]
    fn nearest_stripes_mean_matches_the_area_fractions() {
        // Triangle (0,0) (1,0) (0,1) over 4 vertical stripes of width 1/4: stripe k covers
        // the area between u = k/4 and (k+1)/4 under the line v = 1 − u, a fraction
        // ((1 − k/4)² − (1 − (k+1)/4)²) of the triangle.
        let t = gradient();
        let values: Vec<f32> = (0..4).map(|x| t.texture.texel(x, 0).x).collect();
        let truth: f32 = (0..4)
            .map(|k| {
                let (a, b) = (1.0 - k as f32 / 4.0, 1.0 - (k + 1) as f32 / 4.0);
                (a * a - b * b) * values[k]
            })
            .sum();
        let uvs = [Vec2::ZERO, Vec2::X, Vec2::Y];
        let m = subdivisions(&t.texture, uvs, MAX_SUBDIVISIONS);
        assert_eq!(m, 8);
        // The centroid rule on a step function errs only in sub-triangles a step crosses.
        let fine = triangle_mean(&t, uvs, 256).x;
        assert!((fine - truth).abs() < 2e-3, "{fine} vs {truth}");
        let coarse = triangle_mean(&t, uvs, m).x;
        assert!((coarse - truth).abs() < 0.05, "{coarse} vs {truth}");
    }
}
