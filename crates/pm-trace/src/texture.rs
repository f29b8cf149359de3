//! Textures and their sampling: 8-bit texels (sRGB-encoded colour or linear data) decoded to
//! linear values, wrap modes, bilinear filtering and a box-filtered mip chain for textures
//! seen from afar, as glTF's base-colour and metallic-roughness textures need.

use std::sync::LazyLock;

use glam::Vec3;

/// An RGB image stored as 8-bit texels (3 bytes a texel, sRGB-encoded or linear: its
/// [`TexelEncoding`]), sampled as linear values, with its mip chain: each level half the size
/// of the one before (rounded up), each texel the mean in linear values of the 2×2 texels
/// below it (of those that exist: along the last row or
/// column of an odd size those texels weigh a little more), down to 1×1. The chain takes a
/// third more memory than the image.
#[derive(Clone, PartialEq)]
pub struct Texture {
    width: u32,
    height: u32,
    /// Row-major, top row first, `[r, g, b]` encoded by `encoding`.
    texels: Vec<[u8; 3]>,
    /// How the bytes encode values.
    encoding: TexelEncoding,
    /// Levels 1, 2, … of the mip chain.
    mips: Vec<Level>,
}

/// How a texture's 8-bit codes encode values.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
pub enum TexelEncoding {
    /// The sRGB transfer function (colour: glTF's base-colour and emissive textures).
    #[default]
    Srgb,
    /// Linear, `code / 255` (data: glTF's metallic-roughness texture).
    Linear,
}

impl TexelEncoding {
    /// The value of each 8-bit code.
    #[inline]
    fn table(self) -> &'static [f32; 256] {
        match self {
            TexelEncoding::Srgb => &SRGB_TO_LINEAR,
            TexelEncoding::Linear => &LINEAR,
        }
    }

    /// The code whose value is nearest `value` (clamped to `[0, 1]`).
    fn encode(self, value: f32) -> u8 {
        match self {
            TexelEncoding::Srgb => linear_to_srgb(value),
            TexelEncoding::Linear => (value.clamp(0.0, 1.0) * 255.0).round() as u8,
        }
    }
}

/// One level of a mip chain.
#[derive(Clone, PartialEq)]
struct Level {
    width: u32,
    height: u32,
    texels: Vec<[u8; 3]>,
}

/// The image of one mip level, borrowed.
#[derive(Clone, Copy)]
pub(crate) struct LevelRef<'a> {
    pub(crate) width: u32,
    pub(crate) height: u32,
    texels: &'a [[u8; 3]],
    encoding: TexelEncoding,
}

impl LevelRef<'_> {
    #[inline]
    pub(crate) fn texel(&self, x: u32, y: u32) -> Vec3 {
        let [r, g, b] = self.texels[(y as usize) * self.width as usize + x as usize];
        let table = self.encoding.table();
        Vec3::new(table[r as usize], table[g as usize], table[b as usize])
    }

    /// The level below this one: 2×2 blocks averaged in linear values, re-encoded.
    fn halved(&self) -> Level {
        let (width, height) = (self.width.div_ceil(2), self.height.div_ceil(2));
        let mut texels = Vec::with_capacity(width as usize * height as usize);
        for y in 0..height {
            for x in 0..width {
                let mut sum = Vec3::ZERO;
                let mut n = 0.0;
                for (sx, sy) in [
                    (2 * x, 2 * y),
                    (2 * x + 1, 2 * y),
                    (2 * x, 2 * y + 1),
                    (2 * x + 1, 2 * y + 1),
                ] {
                    if sx < self.width && sy < self.height {
                        sum += self.texel(sx, sy);
                        n += 1.0;
                    }
                }
                texels.push((sum / n).to_array().map(|v| self.encoding.encode(v)));
            }
        }
        Level {
            width,
            height,
            texels,
        }
    }
}

impl std::fmt::Debug for Texture {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(f, "Texture({}×{})", self.width, self.height)
    }
}

/// The sRGB transfer function inverted, for every 8-bit code.
static SRGB_TO_LINEAR: LazyLock<[f32; 256]> = LazyLock::new(|| {
    std::array::from_fn(|i| {
        let c = i as f32 / 255.0;
        if c <= 0.04045 {
            c / 12.92
        } else {
            ((c + 0.055) / 1.055).powf(2.4)
        }
    })
});

/// `code / 255` for every 8-bit code.
static LINEAR: LazyLock<[f32; 256]> = LazyLock::new(|| std::array::from_fn(|i| i as f32 / 255.0));

/// The linear value of an 8-bit sRGB code.
pub fn srgb_to_linear(code: u8) -> f32 {
    SRGB_TO_LINEAR[code as usize]
}

/// The 8-bit sRGB code whose linear value is nearest `value` (clamped to `[0, 1]`).
pub fn linear_to_srgb(value: f32) -> u8 {
    let table = &*SRGB_TO_LINEAR;
    let above = table.partition_point(|&v| v < value).min(255);
    if above > 0 && value - table[above - 1] <= table[above] - value {
        (above - 1) as u8
    } else {
        above as u8
    }
}

impl Texture {
    /// A texture from `width × height` sRGB texels, row-major with the top row first; `None`
    /// when the sizes disagree or either is zero.
    pub fn from_srgb8(width: u32, height: u32, texels: Vec<[u8; 3]>) -> Option<Self> {
        Self::from_texels(width, height, texels, TexelEncoding::Srgb)
    }

    /// A texture from `width × height` texels encoded by `encoding`, row-major with the top
    /// row first; `None` when the sizes disagree or either is zero.
    pub fn from_texels(
        width: u32,
        height: u32,
        texels: Vec<[u8; 3]>,
        encoding: TexelEncoding,
    ) -> Option<Self> {
        let count = (width as u64).checked_mul(height as u64)?;
        if count == 0 || count != texels.len() as u64 {
            return None;
        }
        let mut texture = Self {
            width,
            height,
            texels,
            encoding,
            mips: Vec::new(),
        };
        let mut level = texture.level(0);
        while level.width > 1 || level.height > 1 {
            let next = level.halved();
            texture.mips.push(next);
            level = texture.level(texture.mips.len());
        }
        Some(texture)
    }

    /// Mip level `i` (0 is the image itself); `i` must be at most [`Self::mip_levels`].
    #[inline]
    pub(crate) fn level(&self, i: usize) -> LevelRef<'_> {
        match i.checked_sub(1) {
            None => LevelRef {
                width: self.width,
                height: self.height,
                texels: &self.texels,
                encoding: self.encoding,
            },
            Some(m) => {
                let l = &self.mips[m];
                LevelRef {
                    width: l.width,
                    height: l.height,
                    texels: &l.texels,
                    encoding: self.encoding,
                }
            }
        }
    }

    /// How the texels encode values.
    pub fn encoding(&self) -> TexelEncoding {
        self.encoding
    }

    /// The same image with its codes read by `encoding` (its mip chain rebuilt); a copy of
    /// this one when the encoding is already `encoding`.
    pub fn with_encoding(&self, encoding: TexelEncoding) -> Self {
        if encoding == self.encoding {
            return self.clone();
        }
        Self::from_texels(self.width, self.height, self.texels.clone(), encoding)
            .unwrap_or_else(|| self.clone())
    }

    /// Levels of the mip chain below the image (0 for a 1×1 texture).
    pub fn mip_levels(&self) -> usize {
        self.mips.len()
    }

    /// The texels of the full-resolution level, row-major with the top row first, as
    /// [`Texture::encoding`] encodes them.
    pub fn texels(&self) -> &[[u8; 3]] {
        &self.texels
    }

    /// Width in texels.
    pub fn width(&self) -> u32 {
        self.width
    }

    /// Height in texels.
    pub fn height(&self) -> u32 {
        self.height
    }

    /// Bytes held on the heap (the image and its mip chain).
    pub fn heap_bytes(&self) -> usize {
        self.texels.capacity() * 3
            + self.mips.capacity() * size_of::<Level>()
            + self.mips.iter().map(|l| l.texels.capacity() * 3).sum::<usize>()
    }

    /// Linear RGB of texel `(x, y)` (column, row from the top); both must be in range.
    #[inline]
    pub fn texel(&self, x: u32, y: u32) -> Vec3 {
        self.level(0).texel(x, y)
    }

    /// The mean linear colour over all texels (what a uniform surface of the same total
    /// reflectance would have).
    pub fn mean(&self) -> Vec3 {
        let table = self.encoding.table();
        let sum = self.texels.iter().fold(glam::DVec3::ZERO, |acc, &[r, g, b]| {
            acc + Vec3::new(table[r as usize], table[g as usize], table[b as usize]).as_dvec3()
        });
        (sum / self.texels.len() as f64).as_vec3()
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::sampler::{Sampler, Wrap};
    use glam::Vec2;

    #[test]
    fn srgb_decoding_matches_the_standard_at_known_codes() {
        // IEC 61966-2-1: code 0 → 0, 255 → 1, 188 (0.737) → about 0.5029.
        assert_eq!(srgb_to_linear(0), 0.0);
        assert!((srgb_to_linear(255) - 1.0).abs() < 1e-6);
        assert!((srgb_to_linear(188) - 0.5029).abs() < 1e-3);
    }

    #[test]
    fn linear_to_srgb_inverts_the_decoding() {
        for code in 0..=255u8 {
            assert_eq!(linear_to_srgb(srgb_to_linear(code)), code);
        }
        assert_eq!(linear_to_srgb(-1.0), 0);
        assert_eq!(linear_to_srgb(2.0), 255);
    }

    #[test]
    fn mip_chain_of_a_checkerboard_is_its_mean() {
        // 8×4 texels: levels 4×2, 2×1, 1×1, each texel 0.5 (to 8-bit rounding).
        let checker = |w: u32, h: u32| {
            (0..w * h)
                .map(|i| {
                    if (i % w + i / w).is_multiple_of(2) {
                        [255; 3]
                    } else {
                        [0; 3]
                    }
                })
                .collect::<Vec<_>>()
        };
        let t = Texture::from_srgb8(8, 4, checker(8, 4)).unwrap();
        assert_eq!(t.mip_levels(), 3);
        let s = Sampler::default();
        for footprint in [2.0, 3.0, 8.0, 1e6] {
            let far = s.sample_footprint(&t, Vec2::new(0.3, 0.6), footprint);
            assert!((far - Vec3::splat(0.5)).abs().max_element() < 0.003, "{far}");
        }
        // One texel or less is the plain lookup.
        assert_eq!(
            s.sample_footprint(&t, Vec2::new(0.3, 0.5), 1.0),
            s.sample(&t, Vec2::new(0.3, 0.5))
        );
        // Odd sizes round up (5×3: 3×2, 2×1, 1×1).
        assert_eq!(Texture::from_srgb8(5, 3, checker(5, 3)).unwrap().mip_levels(), 3);
    }

    #[test]
    fn bilinear_halfway_between_texel_centres_is_the_mean() {
        let t = Texture::from_srgb8(2, 1, vec![[0, 0, 0], [255, 255, 255]]).unwrap();
        let s = Sampler {
            wrap_u: Wrap::ClampToEdge,
            ..Sampler::default()
        };
        assert!(
            (s.sample(&t, Vec2::new(0.5, 0.5)) - Vec3::splat(0.5))
                .abs()
                .max_element()
                < 1e-6
        );
        assert_eq!(s.sample(&t, Vec2::new(0.25, 0.5)), Vec3::ZERO);
        assert_eq!(s.sample(&t, Vec2::new(0.75, 0.5)), Vec3::ONE);
        assert!(Texture::from_srgb8(2, 2, vec![[0, 0, 0]]).is_none());
    }

    #[test]
    fn linear_texels_read_code_over_255_and_average_linearly() {
        let texels = vec![[0, 51, 254], [254, 102, 0]];
        let t = Texture::from_texels(2, 1, texels.clone(), TexelEncoding::Linear).unwrap();
        assert_eq!(t.texel(0, 0), Vec3::new(0.0, 0.2, 254.0 / 255.0));
        assert_eq!(t.texel(1, 0), Vec3::new(254.0 / 255.0, 0.4, 0.0));
        // The 1×1 mip: the mean of the values, re-encoded linearly.
        let far = Sampler::default().sample_footprint(&t, Vec2::new(0.5, 0.5), 4.0);
        assert!((far - Vec3::new(127.0, 76.5, 127.0) / 255.0).abs().max_element() <= 0.5 / 255.0);
        // The same bytes as sRGB read differently; re-reading them linearly is `t`.
        let srgb = Texture::from_srgb8(2, 1, texels).unwrap();
        assert_eq!(srgb.texel(0, 0).y, srgb_to_linear(51));
        assert!(srgb.with_encoding(TexelEncoding::Linear) == t);
    }
}
