//! Colour textures and their sampling: 8-bit sRGB texels decoded to linear RGB, wrap modes
//! and bilinear filtering, as glTF's base-colour textures need.

use std::sync::LazyLock;

use glam::{Vec2, Vec3};

/// An RGB image stored as 8-bit sRGB texels (3 bytes a texel), sampled in linear RGB.
#[derive(Clone, PartialEq)]
pub struct Texture {
    width: u32,
    height: u32,
    /// Row-major, top row first, `[r, g, b]` sRGB-encoded.
    texels: Vec<[u8; 3]>,
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

/// The linear value of an 8-bit sRGB code.
pub fn srgb_to_linear(code: u8) -> f32 {
    SRGB_TO_LINEAR[code as usize]
}

impl Texture {
    /// A texture from `width × height` sRGB texels, row-major with the top row first; `None`
    /// when the sizes disagree or either is zero.
    pub fn from_srgb8(width: u32, height: u32, texels: Vec<[u8; 3]>) -> Option<Self> {
        let count = (width as u64).checked_mul(height as u64)?;
        (count > 0 && count == texels.len() as u64).then_some(Self {
            width,
            height,
            texels,
        })
    }

    /// Width in texels.
    pub fn width(&self) -> u32 {
        self.width
    }

    /// Height in texels.
    pub fn height(&self) -> u32 {
        self.height
    }

    /// Bytes held on the heap.
    pub fn heap_bytes(&self) -> usize {
        self.texels.capacity() * 3
    }

    /// Linear RGB of texel `(x, y)` (column, row from the top); both must be in range.
    #[inline]
    pub fn texel(&self, x: u32, y: u32) -> Vec3 {
        let [r, g, b] = self.texels[(y as usize) * self.width as usize + x as usize];
        Vec3::new(srgb_to_linear(r), srgb_to_linear(g), srgb_to_linear(b))
    }

    /// The mean linear colour over all texels (what a uniform surface of the same total
    /// reflectance would have).
    pub fn mean(&self) -> Vec3 {
        let sum = self.texels.iter().fold(glam::DVec3::ZERO, |acc, &[r, g, b]| {
            acc + Vec3::new(srgb_to_linear(r), srgb_to_linear(g), srgb_to_linear(b)).as_dvec3()
        });
        (sum / self.texels.len() as f64).as_vec3()
    }
}

/// How texture coordinates outside `[0, 1]` map into the image (glTF's sampler wrap modes).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum Wrap {
    /// The image tiles (glTF's default).
    #[default]
    Repeat,
    /// Every other tile is mirrored.
    MirroredRepeat,
    /// Coordinates clamp to the edge texels.
    ClampToEdge,
}

impl Wrap {
    /// The texel index for integer texel coordinate `i` on an axis of `n` texels.
    #[inline]
    fn index(self, i: i64, n: u32) -> u32 {
        let n = n as i64;
        let r = match self {
            Wrap::Repeat => i.rem_euclid(n),
            Wrap::ClampToEdge => i.clamp(0, n - 1),
            Wrap::MirroredRepeat => {
                let m = i.rem_euclid(2 * n);
                if m < n { m } else { 2 * n - 1 - m }
            }
        };
        r as u32
    }
}

/// How a texture is read: wrap modes per axis and the filter.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct Sampler {
    /// Wrap along u (glTF `wrapS`).
    pub wrap_u: Wrap,
    /// Wrap along v (glTF `wrapT`).
    pub wrap_v: Wrap,
    /// Nearest-texel lookup instead of bilinear filtering (glTF `magFilter` NEAREST).
    pub nearest: bool,
}

impl Sampler {
    /// The linear colour at texture coordinate `uv` (glTF convention: `(0, 0)` is the image's
    /// top-left corner, v grows downwards). Non-finite coordinates read texel (0, 0).
    #[inline]
    pub fn sample(&self, texture: &Texture, uv: Vec2) -> Vec3 {
        let uv = if uv.is_finite() { uv } else { Vec2::ZERO };
        // Texel centres sit at half-integers; keep the integer parts in a safe range.
        let x = (uv.x as f64 * texture.width as f64 - 0.5).clamp(-1e15, 1e15);
        let y = (uv.y as f64 * texture.height as f64 - 0.5).clamp(-1e15, 1e15);
        if self.nearest {
            let ix = self.wrap_u.index(x.round() as i64, texture.width);
            let iy = self.wrap_v.index(y.round() as i64, texture.height);
            return texture.texel(ix, iy);
        }
        let (x0, y0) = (x.floor(), y.floor());
        let (fx, fy) = ((x - x0) as f32, (y - y0) as f32);
        let (x0, y0) = (x0 as i64, y0 as i64);
        let xs = [
            self.wrap_u.index(x0, texture.width),
            self.wrap_u.index(x0 + 1, texture.width),
        ];
        let ys = [
            self.wrap_v.index(y0, texture.height),
            self.wrap_v.index(y0 + 1, texture.height),
        ];
        let top = texture.texel(xs[0], ys[0]).lerp(texture.texel(xs[1], ys[0]), fx);
        let bottom = texture.texel(xs[0], ys[1]).lerp(texture.texel(xs[1], ys[1]), fx);
        top.lerp(bottom, fy)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn srgb_decoding_matches_the_standard_at_known_codes() {
        // IEC 61966-2-1: code 0 → 0, 255 → 1, 188 (0.737) → about 0.5029.
        assert_eq!(srgb_to_linear(0), 0.0);
        assert!((srgb_to_linear(255) - 1.0).abs() < 1e-6);
        assert!((srgb_to_linear(188) - 0.5029).abs() < 1e-3);
    }

    #[test]
    fn wrap_modes_fold_indices() {
        assert_eq!(Wrap::Repeat.index(-1, 4), 3);
        assert_eq!(Wrap::Repeat.index(5, 4), 1);
        assert_eq!(Wrap::ClampToEdge.index(-3, 4), 0);
        assert_eq!(Wrap::ClampToEdge.index(9, 4), 3);
        assert_eq!(Wrap::MirroredRepeat.index(4, 4), 3);
        assert_eq!(Wrap::MirroredRepeat.index(-1, 4), 0);
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
}
