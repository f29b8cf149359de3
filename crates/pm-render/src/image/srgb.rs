//! The 8-bit sRGB preview: exposure, clamp to [0, 1], sRGB transfer curve.

use super::Image;

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

/// The image as interleaved 8-bit sRGB bytes (RGBRGB…, rows from the top), each linear
/// value scaled by `2^exposure` (exposure in stops) first.
pub fn srgb8_of_image(image: &Image, exposure: f32) -> Vec<u8> {
    let scale = exposure.exp2();
    image
        .pixels()
        .iter()
        .flat_map(|p| (*p * scale).to_array().map(linear_to_srgb8))
        .collect()
}
