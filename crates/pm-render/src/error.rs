//! Errors of pm-render: bad parameters, bad images, and image I/O.

use std::path::PathBuf;
use thiserror::Error;

/// What went wrong, and where.
#[derive(Debug, Error)]
#[non_exhaustive]
pub enum RenderError {
    /// k = 0 photons to gather.
    #[error("k must be at least 1")]
    ZeroK,
    /// A maximum search distance that is not positive and finite.
    #[error("maximum search distance must be positive and finite, got {0}")]
    BadMaxDistance(f32),
    /// An image with zero width or height.
    #[error("image size {width}x{height}: both sides must be at least 1")]
    EmptyImage {
        /// Width asked for.
        width: u32,
        /// Height asked for.
        height: u32,
    },
    /// An image with more than [`crate::limits::MAX_PIXELS`] pixels.
    #[error("image size {width}x{height}: more than the limit of {max} pixels", max = crate::limits::MAX_PIXELS)]
    ImageTooLarge {
        /// Width asked for.
        width: u64,
        /// Height asked for.
        height: u64,
    },
    /// A render whose per-pixel state would pass [`crate::limits::MAX_PIXEL_STATE_BYTES`].
    #[error(
        "image size {width}x{height}: its per-pixel state takes {bytes} bytes, more than the limit of {max} (2 GiB)",
        max = crate::limits::MAX_PIXEL_STATE_BYTES
    )]
    PixelStateTooLarge {
        /// Width asked for.
        width: u32,
        /// Height asked for.
        height: u32,
        /// Bytes the state would take.
        bytes: u64,
    },
    /// Photon maps built for another scene (their part count differs from the scene's).
    #[error("photon maps cover {maps} parts but the scene has {scene}: they were built for another scene")]
    MapsForAnotherScene {
        /// Parts the maps were built for.
        maps: usize,
        /// Parts of the scene rendered.
        scene: usize,
    },
    /// A mode that reads photon maps was given none to render from.
    #[error("the {0} mode reads photon maps: build them first (Renderer::build_maps) and pass them")]
    MissingMaps(crate::mode::Mode),
    /// The path tracer, which reads no photon maps, was given some.
    #[error("the {0} mode reads no photon maps: pass None")]
    UnreadMaps(crate::mode::Mode),
    /// An irradiance cache given to a mode other than the final gather, which alone reads one.
    #[error("the {0} mode reads no irradiance cache (only final-gather does): pass none")]
    UnreadCache(crate::mode::Mode),
    /// Zero photons for a mode that reads photon maps.
    #[error("photons must be at least 1")]
    ZeroPhotons,
    /// Tiles of zero pixels.
    #[error("tile size must be at least 1")]
    ZeroTileSize,
    /// The worker pool could not be made.
    #[error("thread pool: {0}")]
    Threads(String),
    /// A PNG exposure that is NaN or infinite.
    #[error("exposure must be a finite number of stops, got {0}")]
    BadExposure(f32),
    /// More samples per pixel than [`crate::limits::MAX_SAMPLES_PER_PIXEL`].
    #[error("{0} samples per pixel: more than the limit of {max}", max = crate::limits::MAX_SAMPLES_PER_PIXEL)]
    TooManySamples(u32),
    /// More worker threads than [`crate::limits::MAX_THREADS`].
    #[error("{0} threads: more than the limit of {max}", max = crate::limits::MAX_THREADS)]
    TooManyThreads(usize),
    /// Zero samples per pixel.
    #[error("samples per pixel must be at least 1")]
    ZeroSamples,
    /// Two images that should have the same size do not.
    #[error("image sizes differ: {a_width}x{a_height} vs {b_width}x{b_height}")]
    SizeMismatch {
        /// First width.
        a_width: u32,
        /// First height.
        a_height: u32,
        /// Second width.
        b_width: u32,
        /// Second height.
        b_height: u32,
    },
    /// A pixel rectangle that is empty or reaches outside the image.
    #[error(
        "pixel rectangle at ({x}, {y}) of {width}x{height} is empty or outside the {image_width}x{image_height} image"
    )]
    BadRect {
        /// Left column.
        x: u32,
        /// Top row.
        y: u32,
        /// Width.
        width: u32,
        /// Height.
        height: u32,
        /// Image width.
        image_width: u32,
        /// Image height.
        image_height: u32,
    },
    /// An input that is not a regular file (a folder, a FIFO, a device): refused before it
    /// is opened.
    #[error("{}: not a regular file", path.display())]
    NotARegularFile {
        /// The path as given.
        path: PathBuf,
    },
    /// An input file larger than what it can hold.
    #[error("{}: {bytes} bytes, more than the {max_bytes} such a file can hold", path.display())]
    InputTooLarge {
        /// The path as given.
        path: PathBuf,
        /// Its size (or the bytes read before the bound).
        bytes: u64,
        /// The bound.
        max_bytes: u64,
    },
    /// Reading or writing an image file failed.
    #[error("{path}: {message}")]
    ImageIo {
        /// The file.
        path: PathBuf,
        /// What failed.
        message: String,
    },
    /// A progressive render in a mode other than photon-map, shadow-rays or final-gather.
    #[error("mode {0} cannot render progressively (expected photon-map, shadow-rays or final-gather)")]
    UnsupportedMode(crate::mode::Mode),
    /// A final-gather parameter is out of range (the message names it).
    #[error("final gather: {0}")]
    BadFinalGather(String),
    /// Camera-driven emission with bad options, or in a mode or run it does not apply to.
    #[error("camera-driven emission: {0}")]
    BadEmission(String),
    /// An automatic photon count's threshold outside (0, 1) (relative change between batches).
    #[error("auto photons: the threshold must lie strictly between 0 and 1, got {0}")]
    BadAutoThreshold(f64),
    /// An automatic photon count's start, maximum, batch or probe count out of range (the
    /// message names it).
    #[error("auto photons: {0}")]
    BadAutoPhotons(String),
    /// Knaus & Zwicker's α outside (0, 1).
    #[error("alpha must lie strictly between 0 and 1, got {0}")]
    BadAlpha(f32),
    /// A progressive render with zero passes, or with neither passes nor a time budget.
    #[error("a progressive render needs at least one pass or a time budget")]
    ZeroPasses,
    /// Passes that would run past the last pass index,
    /// [`crate::limits::MAX_PASS`].
    #[error(
        "passes from {first_pass} ({passes}) run past the last pass, {max}",
        passes = passes.map_or_else(|| "on a time budget".to_owned(), |n| format!("{n} of them")),
        max = crate::limits::MAX_PASS
    )]
    PassRange {
        /// The first pass.
        first_pass: u64,
        /// The passes asked for (`None`: until a time budget is spent).
        passes: Option<u64>,
    },
    /// Photon tracing refused the scene or the options (no lights, zero power, …).
    #[error("photon tracing: {0}")]
    Trace(#[from] pm_trace::TraceError),
    /// A partition failed (the contact split past its bounds, an assignment for another
    /// scene); the renderers take a partition already made, so this comes from `?` on
    /// [`pm_trace::Partitioner::partition`] in code that renders.
    #[error(transparent)]
    Partition(#[from] pm_trace::PartitionError),
    /// The photon maps could not be built from the traced photons.
    #[error("photon maps: {0}")]
    Maps(#[from] pm_trace::MapError),
}
