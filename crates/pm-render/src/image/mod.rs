//! Linear RGB images (the film), with metrics, a 2×2 grid, EXR and PNG files.

pub(crate) mod atomic;
#[cfg(feature = "exr")]
pub(crate) mod exr_file;
pub(crate) mod input;
pub(crate) mod metrics;
#[cfg(feature = "png")]
pub(crate) mod png_file;
pub(crate) mod srgb;

pub use atomic::{check_output_path, output_target, write_atomically};
pub use input::{check_input_file, read_text_file};
pub use srgb::linear_to_srgb8;

use crate::error::RenderError;
use glam::Vec3;

/// A linear-light RGB image (Rec. 709 primaries), f32 per channel, rows top to bottom.
#[derive(Clone, Debug, PartialEq)]
pub struct Image {
    width: u32,
    height: u32,
    pixels: Vec<Vec3>,
}

impl Image {
    /// A black image. Errors when a side is 0.
    pub fn new(width: u32, height: u32) -> Result<Self, RenderError> {
        Self::from_fn(width, height, |_, _| Vec3::ZERO)
    }

    /// An image whose pixel `(x, y)` is `f(x, y)`. Errors when a side is 0.
    pub fn from_fn(
        width: u32,
        height: u32,
        mut f: impl FnMut(u32, u32) -> Vec3,
    ) -> Result<Self, RenderError> {
        check_image_size(width, height)?;
        let mut pixels = Vec::with_capacity(width as usize * height as usize);
        for y in 0..height {
            for x in 0..width {
                pixels.push(f(x, y));
            }
        }
        Ok(Image {
            width,
            height,
            pixels,
        })
    }

    /// An image from its pixels in row order. Errors when a side is 0 or the count is wrong.
    pub fn from_pixels(width: u32, height: u32, pixels: Vec<Vec3>) -> Result<Self, RenderError> {
        if width == 0 || height == 0 {
            return Err(RenderError::EmptyImage { width, height });
        }
        if pixels.len() != width as usize * height as usize {
            return Err(RenderError::SizeMismatch {
                a_width: width,
                a_height: height,
                b_width: pixels.len() as u32,
                b_height: 1,
            });
        }
        Ok(Image {
            width,
            height,
            pixels,
        })
    }

    /// Width in pixels.
    pub fn width(&self) -> u32 {
        self.width
    }

    /// Height in pixels.
    pub fn height(&self) -> u32 {
        self.height
    }

    /// All pixels, row by row from the top.
    pub fn pixels(&self) -> &[Vec3] {
        &self.pixels
    }

    /// All pixels, mutable.
    pub fn pixels_mut(&mut self) -> &mut [Vec3] {
        &mut self.pixels
    }

    /// Pixel `(x, y)`, or `None` outside the image.
    pub fn get(&self, x: u32, y: u32) -> Option<Vec3> {
        (x < self.width && y < self.height).then(|| self.pixels[(y * self.width + x) as usize])
    }

    /// Sets pixel `(x, y)`; ignored outside the image.
    pub fn set(&mut self, x: u32, y: u32, value: Vec3) {
        if x < self.width && y < self.height {
            self.pixels[(y * self.width + x) as usize] = value;
        }
    }

    /// The four images side by side in a 2×2 grid: `[top left, top right, bottom left,
    /// bottom right]`. All must have the same size.
    pub fn grid_2x2(images: [&Image; 4]) -> Result<Image, RenderError> {
        let (w, h) = (images[0].width, images[0].height);
        for im in &images[1..] {
            check_same_size(images[0], im)?;
        }
        check_image_size(2 * w, 2 * h)?;
        Image::from_fn(2 * w, 2 * h, |x, y| {
            let cell = (y / h) * 2 + x / w;
            images[cell as usize].pixels[((y % h) * w + x % w) as usize]
        })
    }
}

pub(crate) fn check_same_size(a: &Image, b: &Image) -> Result<(), RenderError> {
    if a.width != b.width || a.height != b.height {
        return Err(RenderError::SizeMismatch {
            a_width: a.width,
            a_height: a.height,
            b_width: b.width,
            b_height: b.height,
        });
    }
    Ok(())
}

pub use crate::limits::{MAX_PIXEL_STATE_BYTES, MAX_PIXELS};

/// Checks that `bytes_per_pixel` of state for a `width × height` image fit
/// [`MAX_PIXEL_STATE_BYTES`] (and the size itself, as [`check_image_size`]).
pub fn check_pixel_state(width: u32, height: u32, bytes_per_pixel: u64) -> Result<(), RenderError> {
    check_image_size(width, height)?;
    let bytes = u64::from(width) * u64::from(height) * bytes_per_pixel;
    if bytes > MAX_PIXEL_STATE_BYTES {
        return Err(RenderError::PixelStateTooLarge { width, height, bytes });
    }
    Ok(())
}

/// Checks an image size: both sides at least 1 ([`RenderError::EmptyImage`]) and at most
/// [`MAX_PIXELS`] pixels in all ([`RenderError::ImageTooLarge`]). Call it before allocating
/// for an image made of others (a grid of `2w × 2h`).
pub fn check_image_size(width: u32, height: u32) -> Result<(), RenderError> {
    if width == 0 || height == 0 {
        return Err(RenderError::EmptyImage { width, height });
    }
    if width as u64 * height as u64 > MAX_PIXELS {
        return Err(RenderError::ImageTooLarge {
            width: width as u64,
            height: height as u64,
        });
    }
    Ok(())
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
