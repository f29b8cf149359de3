//! The renderer: photon tracing, map building, then the image in tiles on rayon workers.
//! Every pixel sample draws from its own random stream (seed, pixel, sample), so the image is
//! bit-identical for any number of threads.

use crate::{
    Estimator, EstimatorScratch, Image, Lighting, Mode, Progress, RadianceCache, RenderError, RenderSettings,
    RenderStats,
};
use glam::Vec3;
use pm_trace::{MapAssignment, Partitioned, PhotonMaps, Rng, Scene, TraceOptions, trace_photons};
use rayon::prelude::*;
use std::sync::Mutex;
use std::sync::atomic::{AtomicU64, AtomicUsize, Ordering};
use std::time::Instant;

/// Keeps the pixel streams apart from the photon-path streams of the same seed.
pub(crate) const PIXEL_SEED_SALT: u64 = 0x5DEE_CE66_D1CE_4E5B;

/// An image and the figures of the render that made it.
#[derive(Clone, Debug)]
pub struct Rendered {
    /// The linear RGB image (radiance, W/(m²·sr)).
    pub image: Image,
    /// Counts and timings.
    pub stats: RenderStats,
}

/// Renders scenes with one estimator and one set of settings.
///
/// ```no_run
/// # use pm_render::{Renderer, RenderSettings, GeometryCube};
/// # use pm_trace::Partitioner;
/// # fn f(scene: pm_trace::Scene) -> Result<(), pm_render::RenderError> {
/// let renderer = Renderer::new(GeometryCube, RenderSettings::default());
/// let out = renderer.render(&pm_trace::CreaseAngle::default().partition(scene)?, &())?;
/// println!("{:?} total", out.stats.total());
/// # Ok(()) }
/// ```
#[derive(Clone, Debug)]
pub struct Renderer<E> {
    estimator: E,
    settings: RenderSettings,
}

impl<E: Estimator> Renderer<E> {
    /// A renderer with this estimator and these settings.
    pub fn new(estimator: E, settings: RenderSettings) -> Self {
        Renderer { estimator, settings }
    }

    /// The settings.
    pub fn settings(&self) -> &RenderSettings {
        &self.settings
    }

    /// Traces photons into the maps `partitioned` assigns (skipped for path tracing), builds
    /// the maps and renders its scene, on `settings.threads` workers.
    pub fn render(
        &self,
        partitioned: &Partitioned,
        progress: &dyn Progress,
    ) -> Result<Rendered, RenderError> {
        self.settings.validate()?;
        let scene = partitioned.scene();
        let assignment = self
            .settings
            .mode
            .uses_photons()
            .then(|| partitioned.assignment());
        self.in_pool(|| {
            let mut stats = RenderStats {
                threads: rayon::current_num_threads(),
                ..RenderStats::default()
            };
            let maps = match assignment {
                Some(assignment) => Some(self.build_maps(scene, assignment, progress, &mut stats)?),
                None => None,
            };
            let cache = match (&maps, self.settings.mode) {
                (Some(maps), Mode::FinalGather) => Some(self.build_cache(scene, maps, progress, &mut stats)?),
                _ => None,
            };
            progress.phase("render");
            let start = Instant::now();
            let (image, gather_rays) = self.render_counted(scene, maps.as_ref(), cache.as_ref(), progress)?;
            stats.render = start.elapsed();
            stats.gather_rays = gather_rays;
            Ok(Rendered { image, stats })
        })?
    }

    /// The photon maps for `scene` under `assignment` (the "trace" and "build" phases),
    /// timing them into `stats`; runs in the current rayon pool.
    pub fn build_maps(
        &self,
        scene: &Scene,
        assignment: &MapAssignment,
        progress: &dyn Progress,
        stats: &mut RenderStats,
    ) -> Result<PhotonMaps, RenderError> {
        progress.phase("trace");
        let start = Instant::now();
        let options = TraceOptions {
            photons: self.settings.photons,
            seed: self.settings.seed,
            ..TraceOptions::default()
        };
        let traced = trace_photons(scene, assignment, &options)?;
        stats.photons_emitted = traced.stats().emitted;
        stats.photons_stored = traced.stats().total_stored();
        stats.near_light_fraction = traced.stats().near_light_fraction;
        stats.map_count = assignment.map_count();
        stats.trace = start.elapsed();
        progress.phase("build");
        let start = Instant::now();
        let maps = PhotonMaps::build(scene, assignment, traced)?;
        stats.build = start.elapsed();
        stats.photon_channels_below_range = maps.channels_below_range();
        Ok(maps)
    }

    /// The final gather's irradiance cache for `maps` (the "precompute" phase, timed into
    /// `stats`), with this renderer's estimator and options; runs in the current rayon pool.
    pub fn build_cache(
        &self,
        scene: &Scene,
        maps: &PhotonMaps,
        progress: &dyn Progress,
        stats: &mut RenderStats,
    ) -> Result<RadianceCache, RenderError> {
        progress.phase("precompute");
        let start = Instant::now();
        let options = self.settings.estimator_options(&scene.bounds());
        let cache = RadianceCache::build(
            scene,
            maps,
            &self.estimator,
            &options,
            self.settings.final_gather.cache_every,
        )?
        // The one-shot gather reads cache points only.
        .without_photons();
        stats.precompute = start.elapsed();
        stats.cache_points = cache.len() as u64;
        stats.cache_bytes = cache.memory_bytes() as u64;
        Ok(cache)
    }

    /// Renders the image from already built maps (`None` is fine for path tracing) in the
    /// current rayon pool. Maps built for another scene are an error. For
    /// [`Mode::FinalGather`] this builds the irradiance cache first
    /// ([`Renderer::build_cache`]); [`Renderer::render_image_with`] takes one already built.
    pub fn render_image(
        &self,
        scene: &Scene,
        maps: Option<&PhotonMaps>,
        progress: &dyn Progress,
    ) -> Result<Image, RenderError> {
        let cache = match (maps, self.settings.mode) {
            (Some(maps), Mode::FinalGather) => {
                Some(self.build_cache(scene, maps, progress, &mut RenderStats::default())?)
            }
            _ => None,
        };
        self.render_image_with(scene, maps, cache.as_ref(), progress)
    }

    /// [`Renderer::render_image`] with the final gather's cache given (ignored in the other
    /// modes; without one the final gather sees no indirect light).
    pub fn render_image_with(
        &self,
        scene: &Scene,
        maps: Option<&PhotonMaps>,
        cache: Option<&RadianceCache>,
        progress: &dyn Progress,
    ) -> Result<Image, RenderError> {
        Ok(self.render_counted(scene, maps, cache, progress)?.0)
    }

    /// [`Renderer::render_image_with`], and the number of gather rays cast.
    fn render_counted(
        &self,
        scene: &Scene,
        maps: Option<&PhotonMaps>,
        cache: Option<&RadianceCache>,
        progress: &dyn Progress,
    ) -> Result<(Image, u64), RenderError> {
        self.settings.validate()?;
        if let Some(maps) = maps {
            let (maps, scene) = (maps.assignment().part_count(), scene.part_count());
            if maps != scene {
                return Err(RenderError::MapsForAnotherScene { maps, scene });
            }
        }
        let s = &self.settings;
        let options = s.estimator_options(&scene.bounds());
        options.validate()?;
        let lighting = Lighting {
            scene,
            maps,
            estimator: &self.estimator,
            options: &options,
            pixel_angle: scene.camera().pixel_angle(s.height),
            cache,
            final_gather: s.final_gather,
        };
        let tiles = tiles(s.width, s.height, s.tile_size);
        let done = AtomicUsize::new(0);
        let gather_rays = AtomicU64::new(0);
        // Each finished tile is copied into the image at once, so the pixels are held once
        // (plus one tile per worker), not twice. Tiles are disjoint: the order of the copies
        // does not change the image.
        let image = Mutex::new(Image::new(s.width, s.height)?);
        let width = s.width as usize;
        tiles.par_iter().for_each_init(
            || (EstimatorScratch::new(), Vec::new()),
            |(scratch, pixels), tile| {
                render_tile(&lighting, s, tile, scratch, pixels);
                gather_rays.fetch_add(std::mem::take(&mut scratch.gather_rays), Ordering::Relaxed);
                {
                    // A poisoned lock only means another tile's copy panicked; the pixels
                    // themselves are plain data.
                    let mut image = image.lock().unwrap_or_else(|poisoned| poisoned.into_inner());
                    for (row, chunk) in pixels.chunks_exact(tile.width as usize).enumerate() {
                        let start = (tile.y as usize + row) * width + tile.x as usize;
                        image.pixels_mut()[start..start + chunk.len()].copy_from_slice(chunk);
                    }
                }
                progress.tiles_done(done.fetch_add(1, Ordering::Relaxed) + 1, tiles.len());
            },
        );
        let image = image
            .into_inner()
            .unwrap_or_else(|poisoned| poisoned.into_inner());
        Ok((image, gather_rays.into_inner()))
    }

    fn in_pool<T: Send>(&self, f: impl FnOnce() -> T + Send) -> Result<T, RenderError> {
        in_pool(self.settings.threads, f)
    }
}

/// Runs `f` on a pool of `threads` workers (0: the current pool).
pub(crate) fn in_pool<T: Send>(threads: usize, f: impl FnOnce() -> T + Send) -> Result<T, RenderError> {
    if threads == 0 {
        return Ok(f());
    }
    let pool = rayon::ThreadPoolBuilder::new()
        .num_threads(threads)
        .build()
        .map_err(|e| RenderError::Threads(e.to_string()))?;
    Ok(pool.install(f))
}

/// A rectangle of pixels rendered by one worker.
#[derive(Clone, Copy, Debug)]
pub(crate) struct Tile {
    pub(crate) x: u32,
    pub(crate) y: u32,
    pub(crate) width: u32,
    pub(crate) height: u32,
}

pub(crate) fn tiles(width: u32, height: u32, size: u32) -> Vec<Tile> {
    let mut out = Vec::new();
    for y in (0..height).step_by(size as usize) {
        for x in (0..width).step_by(size as usize) {
            out.push(Tile {
                x,
                y,
                width: size.min(width - x),
                height: size.min(height - y),
            });
        }
    }
    out
}

/// Renders `tile` into `out` (cleared first), row by row; every (pixel, sample) draws from
/// its own random stream, so a tile's pixels do not depend on which worker renders it.
fn render_tile<E: Estimator>(
    lighting: &Lighting<'_, E>,
    s: &RenderSettings,
    tile: &Tile,
    scratch: &mut EstimatorScratch,
    out: &mut Vec<Vec3>,
) {
    let camera = lighting.scene.camera();
    let aspect = s.width as f32 / s.height as f32;
    let spp = s.samples_per_pixel as u64;
    let seed = s.seed ^ PIXEL_SEED_SALT;
    out.clear();
    for y in tile.y..tile.y + tile.height {
        for x in tile.x..tile.x + tile.width {
            let pixel = y as u64 * s.width as u64 + x as u64;
            let mut sum = Vec3::ZERO;
            for sample in 0..spp {
                let mut rng = Rng::new(seed, pixel * spp + sample);
                let u = (x as f32 + rng.next_f32()) / s.width as f32;
                let v = (y as f32 + rng.next_f32()) / s.height as f32;
                let l = lighting.radiance(s.mode, camera.ray(u, v, aspect), &mut rng, scratch);
                // A non-finite sample (a degenerate light sample) must not poison the pixel.
                if l.is_finite() {
                    sum += l;
                }
            }
            out.push(sum / spp as f32);
        }
    }
}
