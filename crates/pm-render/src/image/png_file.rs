//! The 8-bit sRGB PNG preview through the `png` crate.

use super::{Image, srgb8_of_image};
use crate::RenderError;
use std::fs::File;
use std::io::BufWriter;
use std::path::Path;

impl Image {
    /// Writes an 8-bit sRGB PNG preview, each value scaled by `2^exposure` (stops), clamped.
    pub fn write_png(&self, path: impl AsRef<Path>, exposure: f32) -> Result<(), RenderError> {
        let path = path.as_ref();
        let err = |e: &dyn std::fmt::Display| RenderError::ImageIo {
            path: path.to_path_buf(),
            message: e.to_string(),
        };
        let file = File::create(path).map_err(|e| err(&e))?;
        let mut encoder = png::Encoder::new(BufWriter::new(file), self.width, self.height);
        encoder.set_color(png::ColorType::Rgb);
        encoder.set_depth(png::BitDepth::Eight);
        encoder.set_source_srgb(png::SrgbRenderingIntent::Perceptual);
        let mut writer = encoder.write_header().map_err(|e| err(&e))?;
        writer
            .write_image_data(&srgb8_of_image(self, exposure))
            .map_err(|e| err(&e))?;
        writer.finish().map_err(|e| err(&e))
    }
}
