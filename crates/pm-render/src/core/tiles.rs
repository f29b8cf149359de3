//! The one tile loop: the image in square tiles on rayon workers, every (pass, pixel, sample)
//! from its own random stream, so the pixels are the same for any number of threads. One-shot
//! renders copy each tile into an image; progressive passes add it to their sums.

use super::pixel_samples::{PixelSequence, sample_number};
use super::{RadianceSource, camera_radiance};
use crate::estimator::scratch::EstimatorScratch;
use crate::progress::Progress;
use glam::Vec3;
use pm_trace::Rng;
use rayon::prelude::*;
use std::sync::Mutex;
use std::sync::atomic::{AtomicU64, AtomicUsize, Ordering};

/// Keeps the pixel streams apart from the photon-path streams of the same seed.
pub(crate) const PIXEL_SEED_SALT: u64 = 0x5DEE_CE66_D1CE_4E5B;

/// The picture's size, samples and tiles.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Frame {
    /// Width in pixels.
    pub width: u32,
    /// Height in pixels.
    pub height: u32,
    /// Camera samples per pixel, averaged (their positions: [`super::pixel_samples`]).
    pub samples_per_pixel: u32,
    /// Side of the square tiles handed to workers (at least 1).
    pub tile_size: u32,
}

/// Which random streams the pixel samples draw from: stream `pixel · spp + sample` of
/// [`Rng::for_pass`]`(seed ^ salt, pass, ·)`; and where they land in their pixel: sample
/// number `pass · spp + sample` of the pixel's sequence ([`super::pixel_samples`]). A
/// one-shot render is pass 0.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct SampleStreams {
    /// The render's seed.
    pub seed: u64,
    /// The progressive pass (0 for a one-shot render).
    pub pass: u64,
}

/// A rectangle of pixels rendered by one worker.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Tile {
    /// Left column.
    pub x: u32,
    /// Top row.
    pub y: u32,
    /// Width in pixels.
    pub width: u32,
    /// Height in pixels.
    pub height: u32,
}

impl Frame {
    /// The tiles covering the frame, row by row.
    pub fn tiles(&self) -> Vec<Tile> {
        let size = self.tile_size.max(1);
        let mut out = Vec::new();
        for y in (0..self.height).step_by(size as usize) {
            for x in (0..self.width).step_by(size as usize) {
                out.push(Tile {
                    x,
                    y,
                    width: size.min(self.width - x),
                    height: size.min(self.height - y),
                });
            }
        }
        out
    }
}

/// Renders every tile of `frame` with `source` through the current rayon pool and hands each
/// finished tile's pixels (row by row, the mean of the samples) to `write`, one tile at a time
/// (under a lock: tiles are disjoint, so the order of the writes does not change the result).
/// A non-finite sample (a degenerate light sample) is dropped, not averaged in. Returns the
/// gather rays cast.
pub fn render_tiles<S: RadianceSource + ?Sized>(
    source: &S,
    frame: &Frame,
    streams: SampleStreams,
    progress: &dyn Progress,
    write: impl FnMut(&Tile, &[Vec3]) + Send,
) -> u64 {
    let tiles = frame.tiles();
    let camera = source.scene().camera();
    let aspect = frame.width as f32 / frame.height as f32;
    let spp = u64::from(frame.samples_per_pixel.max(1));
    let seed = streams.seed ^ PIXEL_SEED_SALT;
    let done = AtomicUsize::new(0);
    let gather_rays = AtomicU64::new(0);
    let write = Mutex::new(write);
    tiles.par_iter().for_each_init(
        || (EstimatorScratch::new(), Vec::new()),
        |(scratch, pixels): &mut (EstimatorScratch, Vec<Vec3>), tile| {
            pixels.clear();
            for y in tile.y..tile.y + tile.height {
                for x in tile.x..tile.x + tile.width {
                    let pixel = u64::from(y) * u64::from(frame.width) + u64::from(x);
                    let mut sum = Vec3::ZERO;
                    let sequence = PixelSequence::new(streams.seed, pixel);
                    for sample in 0..spp {
                        let mut rng = Rng::for_pass(seed, streams.pass, pixel * spp + sample);
                        let at = sequence.position(sample_number(streams.pass, spp, sample));
                        let u = (x as f32 + at.x) / frame.width as f32;
                        let v = (y as f32 + at.y) / frame.height as f32;
                        let l = camera_radiance(source, camera.ray(u, v, aspect), &mut rng, scratch);
                        if l.is_finite() {
                            sum += l;
                        }
                    }
                    pixels.push(sum / spp as f32);
                }
            }
            gather_rays.fetch_add(std::mem::take(&mut scratch.gather_rays), Ordering::Relaxed);
            {
                // A poisoned lock only means another tile's write panicked; the pixels
                // themselves are plain data.
                let mut write = write.lock().unwrap_or_else(|poisoned| poisoned.into_inner());
                (*write)(tile, pixels);
            }
            progress.tiles_done(done.fetch_add(1, Ordering::Relaxed) + 1, tiles.len());
        },
    );
    gather_rays.into_inner()
}
