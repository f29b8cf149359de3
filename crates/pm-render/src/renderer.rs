//! The one-shot renderer: photon tracing, map building (and a final gather's cache), then the
//! mode's radiance source rendered by the core's tile loop. Every pixel sample draws from its
//! own random stream (seed, pixel, sample), so the image is bit-identical for any number of
//! threads.

use crate::cache::RadianceCache;
use crate::core::RadianceSource;
use crate::core::tiles::SampleStreams;
use crate::core::tiles::render_tiles;
use crate::emission::emitter::Emitter;
use crate::error::RenderError;
use crate::estimator::Estimator;
use crate::image::Image;
use crate::mode::Mode;
use crate::progress::Progress;
use crate::settings::RenderSettings;
use crate::source::final_gather::CacheReads;
use crate::source::final_gather::FinalGatherSource;
use crate::source::path_traced::PathTraced;
use crate::source::photon_map::PhotonMapSource;
use crate::source::photon_read::DirectLight;
use crate::stats::RenderStats;
use pm_trace::{Camera, MapAssignment, Partitioned, PhotonMaps, Scene};
use std::time::Instant;

/// An image and the figures of the render that made it.
#[derive(Clone, Debug)]
pub struct Rendered {
    /// The linear RGB image (radiance, W/(m²·sr)).
    pub image: Image,
    /// Counts and timings.
    pub stats: RenderStats,
}

/// What a render reads from photons, built once and reusable for any camera: the photon maps,
/// for the final gather its irradiance cache, and the figures of the trace that made them
/// ([`Renderer::build_photon_cache`]; saved and loaded by [`crate::cache_file`]).
#[derive(Clone, Debug)]
pub struct PhotonCache {
    /// The photon maps.
    pub maps: PhotonMaps,
    /// The final gather's irradiance cache (without its estimating photons), `None` in the
    /// other modes.
    pub radiance: Option<RadianceCache>,
    /// Photon paths emitted ([`pm_trace::TraceStats::emitted`]).
    pub photons_emitted: u64,
    /// [`pm_trace::TraceStats::near_light_fraction`] of the trace.
    pub near_light_fraction: f64,
}

impl PhotonCache {
    /// Puts the cache's figures into `stats`: photon counts, maps, their occupancy against
    /// `k`, and the irradiance cache's points and bytes (no timings).
    pub fn record_figures(&self, k: usize, stats: &mut RenderStats) {
        stats.photons_emitted = self.photons_emitted;
        stats.photons_stored = self.maps.iter().map(|m| m.tree().len() as u64).sum();
        stats.near_light_fraction = self.near_light_fraction;
        stats.map_count = self.maps.len() as u32;
        stats.photon_channels_below_range = self.maps.channels_below_range();
        stats.occupancy = self.maps.occupancy(k);
        if let Some(cache) = &self.radiance {
            stats.cache_points = cache.len() as u64;
            stats.cache_bytes = cache.memory_bytes() as u64;
        }
    }
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

    /// The estimator.
    pub fn estimator(&self) -> &E {
        &self.estimator
    }

    /// Traces photons into the maps `partitioned` assigns (skipped for path tracing), builds
    /// the maps (and for the final gather its cache) and renders its scene, on
    /// `settings.threads` workers.
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
            let image = self.render_mode(scene, maps.as_ref(), None, progress, &mut stats)?;
            Ok(Rendered { image, stats })
        })?
    }

    /// What a render of `partitioned` in this renderer's mode reads from photons: the maps
    /// ([`Renderer::build_maps`]) and, for [`Mode::FinalGather`], the irradiance cache
    /// ([`Renderer::build_cache`]), timed into `stats`, on `settings.threads` workers. The
    /// path tracer, which reads no photons, is refused ([`RenderError::UnreadMaps`]).
    pub fn build_photon_cache(
        &self,
        partitioned: &Partitioned,
        progress: &dyn Progress,
        stats: &mut RenderStats,
    ) -> Result<PhotonCache, RenderError> {
        let camera = *partitioned.scene().camera();
        self.build_photon_cache_seen_from(partitioned, &[camera], progress, stats)
    }

    /// [`Renderer::build_photon_cache`] for a cache that `cameras` will render from (a
    /// fly-through's frames): camera-driven emission ([`crate::emission`]) learns what all of
    /// them see; uniform emission ignores them. With one camera, the scene's own, it is
    /// `build_photon_cache`.
    pub fn build_photon_cache_seen_from(
        &self,
        partitioned: &Partitioned,
        cameras: &[Camera],
        progress: &dyn Progress,
        stats: &mut RenderStats,
    ) -> Result<PhotonCache, RenderError> {
        self.settings.validate()?;
        let mode = self.settings.mode;
        if !mode.uses_photons() {
            return Err(RenderError::UnreadMaps(mode));
        }
        let scene = partitioned.scene();
        self.in_pool(|| {
            let maps =
                self.build_maps_seen_from(scene, partitioned.assignment(), cameras, progress, stats)?;
            let radiance = match mode {
                Mode::FinalGather => Some(self.build_cache(scene, &maps, progress, stats)?),
                _ => None,
            };
            Ok(PhotonCache {
                maps,
                radiance,
                photons_emitted: stats.photons_emitted,
                near_light_fraction: stats.near_light_fraction,
            })
        })?
    }

    /// Renders the image of this renderer's mode from a [`PhotonCache`] built before (by
    /// [`Renderer::build_photon_cache`], or loaded from a file), timing the render into
    /// `stats`, on `settings.threads` workers: no photon is traced and, when the cache holds
    /// an irradiance cache, none is built; the image is the bits a render that built them
    /// gives. A final gather from a cache without an irradiance cache builds one; an
    /// irradiance cache given to another mode is refused ([`RenderError::UnreadCache`]).
    pub fn render_from_cache(
        &self,
        scene: &Scene,
        cache: &PhotonCache,
        progress: &dyn Progress,
        stats: &mut RenderStats,
    ) -> Result<Image, RenderError> {
        self.in_pool(|| self.render_mode(scene, Some(&cache.maps), cache.radiance.as_ref(), progress, stats))?
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
        self.build_maps_seen_from(scene, assignment, &[*scene.camera()], progress, stats)
    }

    /// [`Renderer::build_maps`] with camera-driven emission learning what `cameras` see
    /// (uniform emission ignores them).
    pub fn build_maps_seen_from(
        &self,
        scene: &Scene,
        assignment: &MapAssignment,
        cameras: &[Camera],
        progress: &dyn Progress,
        stats: &mut RenderStats,
    ) -> Result<PhotonMaps, RenderError> {
        progress.phase("guide");
        let emitter = Emitter::new(scene, assignment, &self.settings, cameras)?;
        stats.emission = emitter.report().copied();
        progress.phase("trace");
        let start = Instant::now();
        let traced = emitter.trace(scene, assignment, &self.settings, 0)?;
        stats.photons_emitted = traced.stats().emitted;
        stats.photons_traced = traced.stats().traced;
        stats.photons_stored = traced.stats().total_stored();
        stats.near_light_fraction = traced.stats().near_light_fraction;
        stats.map_count = assignment.map_count();
        stats.trace = start.elapsed();
        progress.phase("build");
        let start = Instant::now();
        let maps = PhotonMaps::build(scene, assignment, traced)?;
        stats.build = start.elapsed();
        stats.photon_channels_below_range = maps.channels_below_range();
        stats.occupancy = maps.occupancy(self.settings.k);
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
        // The one-shot gather reads nothing else: with no point (every photon stored was
        // set aside as an estimate's), its image would silently lose the indirect light.
        let stored: usize = maps.iter().map(|m| m.tree().len()).sum();
        if cache.is_empty() && stored > 0 {
            return Err(RenderError::BadFinalGather(format!(
                "no cache point among the {stored} photons stored (one in {} was asked for): \
                 lower cache_every or trace more photons",
                self.settings.final_gather.cache_every
            )));
        }
        stats.precompute = start.elapsed();
        stats.cache_points = cache.len() as u64;
        stats.cache_bytes = cache.memory_bytes() as u64;
        Ok(cache)
    }

    /// Renders the image of this renderer's mode from maps already built (none for path
    /// tracing, which reads none) in the current rayon pool; for [`Mode::FinalGather`] this
    /// builds the irradiance cache first ([`Renderer::build_cache`]). Maps built for another
    /// scene, missing maps for a mode that reads them and maps given to the path tracer are
    /// errors.
    pub fn render_image(
        &self,
        scene: &Scene,
        maps: Option<&PhotonMaps>,
        progress: &dyn Progress,
    ) -> Result<Image, RenderError> {
        self.render_mode(scene, maps, None, progress, &mut RenderStats::default())
    }

    /// The image of the mode: the mode chooses the radiance source, the core renders it; the
    /// final gather reads `cache` or, when none is given, builds one. Timings of the
    /// precompute and render phases go into `stats`.
    fn render_mode(
        &self,
        scene: &Scene,
        maps: Option<&PhotonMaps>,
        cache: Option<&RadianceCache>,
        progress: &dyn Progress,
        stats: &mut RenderStats,
    ) -> Result<Image, RenderError> {
        self.settings.validate()?;
        let mode = self.settings.mode;
        if cache.is_some() && mode != Mode::FinalGather {
            return Err(RenderError::UnreadCache(mode));
        }
        let maps = match (maps, mode.uses_photons()) {
            (Some(maps), true) => {
                let (maps_parts, scene_parts) = (maps.assignment().part_count(), scene.part_count());
                if maps_parts != scene_parts {
                    return Err(RenderError::MapsForAnotherScene {
                        maps: maps_parts,
                        scene: scene_parts,
                    });
                }
                Some(maps)
            }
            (None, false) => None,
            (None, true) => return Err(RenderError::MissingMaps(mode)),
            (Some(_), false) => return Err(RenderError::UnreadMaps(mode)),
        };
        let options = self.settings.estimator_options(&scene.bounds());
        options.validate()?;
        let direct = match mode {
            Mode::ShadowRays => DirectLight::ShadowRays,
            _ => DirectLight::Photons,
        };
        match (mode, maps) {
            // Path tracing, the one mode that reads no maps (so `None` here).
            (Mode::PathTrace, _) | (_, None) => self.render_counted(&PathTraced { scene }, progress, stats),
            (Mode::PhotonMap | Mode::ShadowRays, Some(maps)) => {
                let source = PhotonMapSource {
                    scene,
                    maps,
                    estimator: &self.estimator,
                    options: &options,
                    pixel_angle: scene.camera().pixel_angle(self.settings.height),
                    direct,
                };
                self.render_counted(&source, progress, stats)
            }
            (Mode::FinalGather, Some(maps)) => {
                let built;
                let cache = match cache {
                    Some(cache) if cache.map_count() == maps.len() => cache,
                    Some(cache) => {
                        return Err(RenderError::BadFinalGather(format!(
                            "an irradiance cache of {} maps for photon maps of {}",
                            cache.map_count(),
                            maps.len()
                        )));
                    }
                    None => {
                        built = self.build_cache(scene, maps, progress, stats)?;
                        &built
                    }
                };
                let source = FinalGatherSource {
                    reads: CacheReads {
                        scene,
                        maps,
                        estimator: &self.estimator,
                        options: &options,
                        cache,
                        gather: self.settings.final_gather,
                    },
                };
                self.render_counted(&source, progress, stats)
            }
        }
    }

    /// Renders `source` (any [`RadianceSource`]: a renderer author's own too) with this
    /// renderer's size, samples, seed and tiles, in the current rayon pool. The mode in the
    /// settings is not read: the source is what renders.
    pub fn render_source<S: RadianceSource + ?Sized>(
        &self,
        source: &S,
        progress: &dyn Progress,
    ) -> Result<Image, RenderError> {
        self.settings.validate()?;
        self.render_counted(source, progress, &mut RenderStats::default())
    }

    /// The image of `source`, timing the render phase and counting gather rays into `stats`.
    fn render_counted<S: RadianceSource + ?Sized>(
        &self,
        source: &S,
        progress: &dyn Progress,
        stats: &mut RenderStats,
    ) -> Result<Image, RenderError> {
        let s = &self.settings;
        progress.phase("render");
        let start = Instant::now();
        // Each finished tile is copied into the image at once, so the pixels are held once
        // (plus one tile per worker), not twice.
        let mut image = Image::new(s.width, s.height)?;
        let width = s.width as usize;
        let streams = SampleStreams {
            seed: s.seed,
            pass: 0,
        };
        let gather_rays = render_tiles(source, &s.frame(), streams, progress, |tile, pixels| {
            for (row, chunk) in pixels.chunks_exact(tile.width as usize).enumerate() {
                let start = (tile.y as usize + row) * width + tile.x as usize;
                image.pixels_mut()[start..start + chunk.len()].copy_from_slice(chunk);
            }
        });
        stats.render = start.elapsed();
        stats.gather_rays = gather_rays;
        Ok(image)
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
