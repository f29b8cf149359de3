//! The 8-bit sRGB preview: exposure, clamp to [0, 1], sRGB transfer curve.

/// One linear value to an 8-bit sRGB code value (clamped; NaN maps to 0).
pub fn linear_to_srgb8(linear: f32) -> u8 {
    let c = if linear.is_nan() {
        0.0
    } else {
        linear.clamp(0.0, 1.0)
    };
    let s = if c <= 0.003_130_8 {
        12.92 * c
    } else {
        1.055 * c.powf(1.0 / 2.4) - 0.055
    };
    (s * 255.0 + 0.5) as u8
}
