//! Image metrics: mean, RMSE and relative RMSE against a reference, mean over a rectangle.

use super::{Image, check_same_size};
use crate::error::RenderError;
use glam::{DVec3, Vec3};

impl Image {
    /// Mean pixel value per channel (accumulated in f64).
    pub fn mean(&self) -> Vec3 {
        mean_of(self.pixels.iter().copied(), self.pixels.len())
    }

    /// Mean over the `width × height` rectangle whose top-left pixel is `(x, y)`.
    pub fn mean_in_rect(&self, x: u32, y: u32, width: u32, height: u32) -> Result<Vec3, RenderError> {
        let inside = x.checked_add(width).is_some_and(|r| r <= self.width)
            && y.checked_add(height).is_some_and(|b| b <= self.height);
        if width == 0 || height == 0 || !inside {
            return Err(RenderError::BadRect {
                x,
                y,
                width,
                height,
                image_width: self.width,
                image_height: self.height,
            });
        }
        let rows = (y..y + height).flat_map(|row| {
            let start = (row * self.width + x) as usize;
            self.pixels[start..start + width as usize].iter().copied()
        });
        Ok(mean_of(rows, width as usize * height as usize))
    }

    /// Root-mean-square difference to `reference` over all pixels and channels.
    pub fn rmse(&self, reference: &Image) -> Result<f32, RenderError> {
        check_same_size(self, reference)?;
        let sum: f64 = self
            .pixels
            .iter()
            .zip(&reference.pixels)
            .map(|(a, b)| (a.as_dvec3() - b.as_dvec3()).length_squared())
            .sum();
        Ok((sum / (3 * self.pixels.len()) as f64).sqrt() as f32)
    }

    /// RMSE divided by the reference's mean value over all channels (0 when both are black,
    /// infinite when only the reference is).
    pub fn relative_rmse(&self, reference: &Image) -> Result<f32, RenderError> {
        let rmse = self.rmse(reference)?;
        let m = reference.mean();
        let mean = (m.x + m.y + m.z) / 3.0;
        Ok(if rmse == 0.0 { 0.0 } else { rmse / mean })
    }
}

fn mean_of(values: impl Iterator<Item = Vec3>, count: usize) -> Vec3 {
    let sum: DVec3 = values.map(|v| v.as_dvec3()).sum();
    (sum / count.max(1) as f64).as_vec3()
}
