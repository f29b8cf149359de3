//! How a texture is read: the wrap modes (glTF's sampler `wrapS`/`wrapT`) and bilinear,
//! nearest or trilinear (mip-mapped) lookups at texture coordinates.

use crate::texture::{LevelRef, Texture};
use glam::{Vec2, Vec3};

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
        self.sample_level(texture.level(0), uv)
    }

    /// The linear colour at `uv` averaged over a footprint about `texels` texels of the image
    /// across: trilinear filtering between the two mip levels whose texels bracket the
    /// footprint. A footprint of one texel or less (or not a number) is [`Self::sample`].
    #[inline]
    pub fn sample_footprint(&self, texture: &Texture, uv: Vec2, texels: f32) -> Vec3 {
        if texels.is_nan() || texels <= 1.0 {
            return self.sample(texture, uv);
        }
        let lod = texels.log2().min(texture.mip_levels() as f32);
        let below = lod.floor();
        let (i, t) = (below as usize, lod - below);
        let fine = self.sample_level(texture.level(i), uv);
        if t <= 0.0 || i >= texture.mip_levels() {
            return fine;
        }
        fine.lerp(self.sample_level(texture.level(i + 1), uv), t)
    }

    /// Bilinear (or nearest) lookup in one mip level.
    #[inline]
    fn sample_level(&self, texture: LevelRef<'_>, uv: Vec2) -> Vec3 {
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
    fn wrap_modes_fold_indices() {
        assert_eq!(Wrap::Repeat.index(-1, 4), 3);
        assert_eq!(Wrap::Repeat.index(5, 4), 1);
        assert_eq!(Wrap::ClampToEdge.index(-3, 4), 0);
        assert_eq!(Wrap::ClampToEdge.index(9, 4), 3);
        assert_eq!(Wrap::MirroredRepeat.index(4, 4), 3);
        assert_eq!(Wrap::MirroredRepeat.index(-1, 4), 0);
    }
}
