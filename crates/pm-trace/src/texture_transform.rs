//! An affine map of texture coordinates (glTF's `KHR_texture_transform`): offset, rotation
//! and scale, applied before a texture is sampled.

use glam::{Mat2, Vec2};

/// `uv ↦ offset + R(rotation) · (scale ⊙ uv)` as `KHR_texture_transform` defines it: the
/// matrix `T · R · S` with `R · (x, y) = (cos x + sin y, −sin x + cos y)`, a counter-clockwise
/// turn of the coordinates as seen on the image (v grows downwards), which turns the image
/// clockwise. This is the reading under which the specification's example (offset (0, 1),
/// rotation π/2, scale 0.5) selects the image's lower-left quadrant.
/// [`TextureTransform::IDENTITY`] (the default) leaves coordinates unchanged.
///
/// Being affine, it commutes with interpolation across a triangle, so applying it to each
/// vertex's coordinates gives exactly the transformed coordinate at every point.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct TextureTransform {
    /// Added after rotating and scaling, in texture units.
    pub offset: Vec2,
    /// Radians.
    pub rotation: f32,
    /// Multiplies u and v first.
    pub scale: Vec2,
}

impl Default for TextureTransform {
    fn default() -> Self {
        Self::IDENTITY
    }
}

impl TextureTransform {
    /// No change: offset 0, rotation 0, scale 1.
    pub const IDENTITY: Self = Self {
        offset: Vec2::ZERO,
        rotation: 0.0,
        scale: Vec2::ONE,
    };

    /// The transform with every non-finite component replaced by its identity value.
    pub fn finite_or_identity(self) -> Self {
        let pick = |x: f32, default: f32| if x.is_finite() { x } else { default };
        Self {
            offset: Vec2::new(pick(self.offset.x, 0.0), pick(self.offset.y, 0.0)),
            rotation: pick(self.rotation, 0.0),
            scale: Vec2::new(pick(self.scale.x, 1.0), pick(self.scale.y, 1.0)),
        }
    }

    /// True when applying it changes nothing.
    pub fn is_identity(&self) -> bool {
        *self == Self::IDENTITY
    }

    /// The transformed coordinate.
    #[inline]
    pub fn apply(&self, uv: Vec2) -> Vec2 {
        let (sin, cos) = self.rotation.sin_cos();
        // Columns of R: R · (x, y) = (cos x + sin y, −sin x + cos y).
        let rotate = Mat2::from_cols(Vec2::new(cos, -sin), Vec2::new(sin, cos));
        self.offset + rotate * (self.scale * uv)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn quarter_turn_maps_u_to_minus_v() {
        // The extension's own example: rotation π/2 maps (1, 0) to (0, −1).
        let t = TextureTransform {
            rotation: std::f32::consts::FRAC_PI_2,
            ..TextureTransform::IDENTITY
        };
        assert!((t.apply(Vec2::X) - Vec2::NEG_Y).length() < 1e-6);
        assert!((t.apply(Vec2::Y) - Vec2::X).length() < 1e-6);
    }

    #[test]
    fn specification_example_selects_the_lower_left_quadrant() {
        let t = TextureTransform {
            offset: Vec2::new(0.0, 1.0),
            rotation: std::f32::consts::FRAC_PI_2,
            scale: Vec2::splat(0.5),
        };
        for (uv, want) in [
            (Vec2::ZERO, Vec2::new(0.0, 1.0)),
            (Vec2::X, Vec2::new(0.0, 0.5)),
            (Vec2::Y, Vec2::new(0.5, 1.0)),
            (Vec2::ONE, Vec2::new(0.5, 0.5)),
        ] {
            assert!((t.apply(uv) - want).length() < 1e-6, "{uv} → {}", t.apply(uv));
        }
    }

    #[test]
    fn scale_applies_before_offset() {
        let t = TextureTransform {
            offset: Vec2::new(0.5, -1.0),
            rotation: 0.0,
            scale: Vec2::new(2.0, 3.0),
        };
        assert_eq!(t.apply(Vec2::new(1.0, 1.0)), Vec2::new(2.5, 2.0));
        assert!(TextureTransform::default().is_identity());
        let bad = TextureTransform {
            offset: Vec2::NAN,
            rotation: f32::INFINITY,
            scale: Vec2::new(f32::NAN, 2.0),
        };
        assert_eq!(
            bad.finite_or_identity(),
            TextureTransform {
                scale: Vec2::new(1.0, 2.0),
                ..TextureTransform::IDENTITY
            }
        );
    }
}
