//! Per-pixel sums of progressive passes kept as double-double values (an f64 and its exact
//! remainder), so that the sum does not depend on how the passes were grouped: one run of
//! passes 0..n and the merge of shards of the same passes give bit-identical images.
//!
//! Every pass adds f32 radiance values. Their f64 sum rounds as soon as a pixel's values span
//! more than about 29 bits (light seen in one pass, a dark corner in the next), and rounding
//! makes `((a + b) + c) + d` and `(a + b) + (c + d)` differ. Each sum here is `hi + lo` with
//! `hi` the sum rounded to f64 and `lo` what rounding left out (Knuth's TwoSum gives it
//! exactly), so the pair holds the exact sum while it spans at most 106 significant bits: for
//! a pixel whose pass values lie within a ratio of 2⁵⁰ of each other, over up to 2³⁰ passes.
//! Within that, `hi` is the exact sum correctly rounded, whatever the grouping, and the mean
//! `hi / passes` rounded to f32 is the same bits.

use crate::core::tiles::Tile;
use crate::error::RenderError;
use crate::image::Image;
use glam::{DVec3, Vec3};

/// `a + b` as the rounded sum and its exact error: `a + b == s + e` exactly.
fn two_sum(a: f64, b: f64) -> (f64, f64) {
    let s = a + b;
    let bb = s - a;
    let e = (a - (s - bb)) + (b - bb);
    (s, e)
}

/// One channel's exact sum `hi + lo`, normalised so that `hi` is `hi + lo` rounded to f64.
fn add_exact(hi: f64, lo: f64, other_hi: f64, other_lo: f64) -> (f64, f64) {
    let (s, e) = two_sum(hi, other_hi);
    let (t, _) = two_sum(lo, other_lo);
    let (t, _) = two_sum(t, e);
    two_sum(s, t)
}

/// The per-pixel sums of a run of passes, row by row.
#[derive(Clone, Debug, PartialEq)]
pub struct PassSums {
    width: u32,
    height: u32,
    hi: Vec<DVec3>,
    lo: Vec<DVec3>,
}

impl PassSums {
    /// Bytes a pixel's sums hold (two f64 per channel).
    pub const BYTES_PER_PIXEL: u64 = 2 * size_of::<DVec3>() as u64;

    /// Zero sums for a `width × height` image, within
    /// [`crate::image::MAX_PIXEL_STATE_BYTES`].
    pub fn new(width: u32, height: u32) -> Result<Self, RenderError> {
        crate::image::check_pixel_state(width, height, Self::BYTES_PER_PIXEL)?;
        let n = width as usize * height as usize;
        Ok(PassSums {
            width,
            height,
            hi: vec![DVec3::ZERO; n],
            lo: vec![DVec3::ZERO; n],
        })
    }

    /// Sums from their two parts (as [`PassSums::parts`] gives them). Errors when a side is 0,
    /// the counts are wrong, or a value is not finite.
    pub fn from_parts(width: u32, height: u32, hi: Vec<DVec3>, lo: Vec<DVec3>) -> Result<Self, RenderError> {
        crate::image::check_image_size(width, height)?;
        let n = width as usize * height as usize;
        if hi.len() != n || lo.len() != n {
            return Err(RenderError::SizeMismatch {
                a_width: width,
                a_height: height,
                b_width: hi.len().max(lo.len()) as u32,
                b_height: 1,
            });
        }
        Ok(PassSums {
            width,
            height,
            hi,
            lo,
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

    /// The sums rounded to f64 (`hi`) and what rounding left out (`lo`), row by row.
    pub fn parts(&self) -> (&[DVec3], &[DVec3]) {
        (&self.hi, &self.lo)
    }

    /// Heap bytes held.
    pub fn heap_bytes(&self) -> u64 {
        ((self.hi.capacity() + self.lo.capacity()) * size_of::<DVec3>()) as u64
    }

    /// Adds one pass's value to pixel `index` (row-major).
    pub fn add_value(&mut self, index: usize, value: Vec3) {
        let (hi, lo) = (&mut self.hi[index], &mut self.lo[index]);
        let v = value.as_dvec3();
        for c in 0..3 {
            (hi[c], lo[c]) = add_exact(hi[c], lo[c], v[c], 0.0);
        }
    }

    /// Adds one pass's values of the pixels of `tile` (row by row, as the render core's tile
    /// loop hands them over).
    pub(crate) fn add_tile(&mut self, tile: &Tile, pixels: &[Vec3]) {
        let width = self.width as usize;
        for (row, chunk) in pixels.chunks_exact(tile.width as usize).enumerate() {
            let start = (tile.y as usize + row) * width + tile.x as usize;
            for (i, p) in chunk.iter().enumerate() {
                self.add_value(start + i, *p);
            }
        }
    }

    /// Adds the exact sum `hi + lo` of another run to channel `channel` of pixel `index`.
    pub(crate) fn add_channel(&mut self, index: usize, channel: usize, hi: f64, lo: f64) {
        let (h, l) = (&mut self.hi[index][channel], &mut self.lo[index][channel]);
        (*h, *l) = add_exact(*h, *l, hi, lo);
    }

    /// Adds another run's sums pixel by pixel (the merge of two shards).
    pub fn add_sums(&mut self, other: &PassSums) -> Result<(), RenderError> {
        if (self.width, self.height) != (other.width, other.height) {
            return Err(RenderError::SizeMismatch {
                a_width: self.width,
                a_height: self.height,
                b_width: other.width,
                b_height: other.height,
            });
        }
        for i in 0..self.hi.len() {
            let (hi, lo) = (&mut self.hi[i], &mut self.lo[i]);
            for c in 0..3 {
                (hi[c], lo[c]) = add_exact(hi[c], lo[c], other.hi[i][c], other.lo[i][c]);
            }
        }
        Ok(())
    }

    /// The mean of `passes` passes (black for none): each sum correctly rounded to f64,
    /// divided by the pass count and rounded to f32.
    pub fn mean(&self, passes: u64) -> Image {
        let n = passes.max(1) as f64;
        let pixels = self.hi.iter().map(|s| (*s / n).as_vec3()).collect();
        // The size was checked when the sums were made.
        Image::from_pixels(self.width, self.height, pixels).unwrap_or_else(|_| unreachable!())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Sums `values` into one pixel in the given groups, each group summed from zero and the
    /// groups then added, as shards are merged.
    fn grouped(values: &[f32], groups: &[usize]) -> (f64, f64) {
        let mut total = PassSums::new(1, 1).unwrap();
        let mut at = 0;
        for &len in groups {
            let mut part = PassSums::new(1, 1).unwrap();
            for &v in &values[at..at + len] {
                part.add_value(0, Vec3::splat(v));
            }
            total.add_sums(&part).unwrap();
            at += len;
        }
        (total.hi[0].x, total.lo[0].x)
    }

    #[test]
    fn any_grouping_of_widely_spread_values_gives_the_same_bits() {
        // Values spanning 2⁴⁰: a plain f64 running sum of them depends on the grouping.
        let values: Vec<f32> = (0..64)
            .map(|i| {
                let x = ((i as u64).wrapping_mul(0x9e37_79b9_7f4a_7c15) >> 40) as f32 / 16_777_216.0;
                x * 2f32.powi((i * 7 % 41) - 20)
            })
            .collect();
        let naive = |groups: &[usize]| {
            let mut at = 0;
            let mut total = 0.0f64;
            for &len in groups {
                total += values[at..at + len].iter().map(|&v| f64::from(v)).sum::<f64>();
                at += len;
            }
            total
        };
        let one = grouped(&values, &[64]);
        let mut naive_differs = false;
        for groups in [
            &[1usize; 64][..],
            &[32, 32],
            &[1, 2, 61],
            &[63, 1],
            &[10, 20, 30, 4],
        ] {
            assert_eq!(grouped(&values, groups), one, "{groups:?}");
            naive_differs |= naive(groups) != naive(&[64]);
        }
        assert!(naive_differs, "the values do not exercise rounding");
        // hi is the exact sum rounded: check against an exact integer sum of the same values.
        let exact: i128 = values
            .iter()
            .map(|&v| (f64::from(v) * 2f64.powi(60)) as i128)
            .sum();
        assert_eq!(one.0, exact as f64 / 2f64.powi(60));
    }

    #[test]
    fn the_mean_divides_the_rounded_sum() {
        let mut s = PassSums::new(2, 1).unwrap();
        for v in [1.0f32, 2.0, 4.0] {
            s.add_value(1, Vec3::new(v, -v, 0.0));
        }
        let m = s.mean(3);
        assert_eq!(m.pixels()[0], Vec3::ZERO);
        assert_eq!(m.pixels()[1], Vec3::new(7.0 / 3.0, -7.0 / 3.0, 0.0));
        assert_eq!(PassSums::new(1, 1).unwrap().mean(0).pixels()[0], Vec3::ZERO);
    }
}
