//! The limits every render is checked against before anything is allocated, in one leaf
//! module (re-exported where they apply: [`crate::image::MAX_PIXELS`],
//! [`crate::RenderSettings::MAX_SAMPLES_PER_PIXEL`], [`crate::progressive::MAX_PASS`], …) so
//! that the errors naming them depend on nothing else.

/// The most pixels an image may have: 2²⁶ (67,108,864, e.g. 8192×8192). The film holds 12 bytes
/// a pixel (768 MiB at the limit) and writing it takes about as much again (the PNG's 3 bytes a
/// pixel, the EXR encoder's blocks); larger sizes are refused with
/// [`crate::RenderError::ImageTooLarge`] before anything is allocated. A 2×2 grid
/// ([`crate::Image::grid_2x2`]) counts its four cells.
pub const MAX_PIXELS: u64 = 1 << 26;

/// The most bytes the per-pixel state of a render may hold: 2 GiB. The progressive
/// renderer's exact sums ([`crate::progressive::PassSums`], 48 bytes a pixel, also the running
/// sum of a merge) and SPPM's pixel state (48 bytes a pixel) count against it, so those modes
/// stop at about 44.7 million pixels (6688×6688) where the single-pass film (12 bytes a pixel)
/// fits [`MAX_PIXELS`]; past it the run is refused with
/// [`crate::RenderError::PixelStateTooLarge`] before anything is allocated.
pub const MAX_PIXEL_STATE_BYTES: u64 = 1 << 31;

/// The most samples per pixel (2¹⁶): render time grows with pixels × samples, and more than
/// this is refused with [`crate::RenderError::TooManySamples`].
pub const MAX_SAMPLES_PER_PIXEL: u32 = 1 << 16;

/// The most worker threads (512): each is an OS thread with its own stack, and the standard
/// library aborts the process when it cannot make one, so more are refused with
/// [`crate::RenderError::TooManyThreads`].
pub const MAX_THREADS: usize = 512;

/// The largest pass index a progressive render may use: every index below
/// [`crate::progressive::PILOT_PASS`] (`u64::MAX`, whose streams trace the pilot map), so a
/// run's passes end at most at `u64::MAX`.
pub const MAX_PASS: u64 = u64::MAX - 1;
