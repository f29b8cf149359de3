//! Lossless OpenEXR files (32-bit float RGB, ZIP compression) through the `exr` crate.

use super::Image;
use crate::error::RenderError;
use exr::prelude::{Encoding, SpecificChannels, Vec2, WritableImage};
use glam::Vec3;
use std::path::Path;

fn io_error(path: &Path, e: impl std::fmt::Display) -> RenderError {
    RenderError::ImageIo {
        path: path.to_path_buf(),
        message: e.to_string(),
    }
}

impl Image {
    /// Writes the image as a lossless 32-bit float RGB EXR file, atomically (see
    /// [`super::write_atomically`]): on any error the file named, or the link naming it, is
    /// left as it was.
    pub fn write_exr(&self, path: impl AsRef<Path>) -> Result<(), RenderError> {
        let path = path.as_ref();
        let w = self.width as usize;
        let channels = SpecificChannels::rgb(|Vec2(x, y): Vec2<usize>| {
            let p = self.pixels[y * w + x];
            (p.x, p.y, p.z)
        });
        crate::image::atomic::write_atomically(path, |writer| {
            exr::prelude::Image::from_encoded_channels(
                (w, self.height as usize),
                Encoding::SMALL_LOSSLESS,
                channels,
            )
            .write()
            .to_buffered(writer)
            .map_err(|e| std::io::Error::other(e.to_string()))
        })
        .map_err(|e| io_error(path, e))
    }

    /// Reads the first RGB(A) layer of an EXR file (alpha is dropped).
    pub fn read_exr(path: impl AsRef<Path>) -> Result<Image, RenderError> {
        let path = path.as_ref();
        // A regular file only: a FIFO would block the reader for ever.
        super::input::check_input_file(path, u64::MAX)?;
        // Check the declared size before the reader allocates for it: a tiny file can claim a
        // billion pixels on a side.
        let meta = exr::meta::MetaData::read_from_file(path, false).map_err(|e| io_error(path, e))?;
        for header in meta.headers.iter() {
            let size = header.layer_size;
            let (w, h) = (u32::try_from(size.width()), u32::try_from(size.height()));
            match (w, h) {
                (Ok(w), Ok(h)) => super::check_image_size(w, h)?,
                _ => {
                    return Err(RenderError::ImageTooLarge {
                        width: size.width() as u64,
                        height: size.height() as u64,
                    });
                }
            }
        }
        let img = exr::prelude::read_first_rgba_layer_from_file(
            path,
            |res, _| (res.width(), vec![Vec3::ZERO; res.width() * res.height()]),
            |(w, buf): &mut (usize, Vec<Vec3>), pos, (r, g, b, _a): (f32, f32, f32, f32)| {
                buf[pos.y() * *w + pos.x()] = Vec3::new(r, g, b)
            },
        )
        .map_err(|e| io_error(path, e))?;
        let size = img.layer_data.size;
        let (_, pixels) = img.layer_data.channel_data.pixels;
        Image::from_pixels(size.width() as u32, size.height() as u32, pixels)
    }
}
