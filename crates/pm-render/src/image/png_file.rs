//! The 8-bit sRGB PNG preview through the `png` crate.

use super::{Image, srgb8_of_image};
use crate::error::RenderError;
use std::path::Path;

impl Image {
    /// Writes an 8-bit sRGB PNG preview, each value scaled by `2^exposure` (stops), clamped,
    /// atomically (see [`super::write_atomically`]). A non-finite exposure is refused.
    pub fn write_png(&self, path: impl AsRef<Path>, exposure: f32) -> Result<(), RenderError> {
        let path = path.as_ref();
        let err = |e: &dyn std::fmt::Display| RenderError::ImageIo {
            path: path.to_path_buf(),
            message: e.to_string(),
        };
        if !exposure.is_finite() {
            return Err(RenderError::BadExposure(exposure));
        }
        let rgb8 = srgb8_of_image(self, exposure);
        let png_error = |e: png::EncodingError| std::io::Error::other(e.to_string());
        crate::image::atomic::write_atomically(path, |file| {
            let mut encoder = png::Encoder::new(file, self.width, self.height);
            encoder.set_color(png::ColorType::Rgb);
            encoder.set_depth(png::BitDepth::Eight);
            encoder.set_source_srgb(png::SrgbRenderingIntent::Perceptual);
            let mut writer = encoder.write_header().map_err(png_error)?;
            writer.write_image_data(&rgb8).map_err(png_error)?;
            writer.finish().map_err(png_error)
        })
        .map_err(|e| err(&e))
    }
}
