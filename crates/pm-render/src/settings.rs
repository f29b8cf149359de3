//! Render settings: image size, samples, photons, seed, threads and estimator parameters, with
//! the report's defaults (Ball & Stejko).

use crate::emission::choice::PhotonEmission;
use crate::error::RenderError;
use crate::estimator::options::EstimatorOptions;
use crate::mode::Mode;
use crate::source::final_gather::FinalGatherOptions;
use pm_geom::Aabb;
use pm_kdtree::KindMask;

/// What to render and how; [`RenderSettings::default`] is Ball & Stejko's setup (500×500, one
/// sample per pixel, 100,000 photons, k = 100).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct RenderSettings {
    /// Image width in pixels.
    pub width: u32,
    /// Image height in pixels.
    pub height: u32,
    /// Samples per pixel, spread over the pixel by a stratified sequence that progressive
    /// passes continue ([`crate::core::pixel_samples`]).
    pub samples_per_pixel: u32,
    /// Photon paths emitted from the lights.
    pub photons: u32,
    /// Photons gathered per estimate.
    pub k: usize,
    /// Largest search distance in metres; `None` means 10 % of the scene's diagonal.
    pub max_distance: Option<f32>,
    /// Drop photons arriving from behind the viewed side (see [`EstimatorOptions`]).
    pub reject_behind: bool,
    /// The render mode.
    pub mode: Mode,
    /// Seed of every random stream (photon paths and pixel samples).
    pub seed: u64,
    /// Worker threads; 0 uses rayon's current pool, which outside any `ThreadPool::install` is
    /// the global pool: one thread per core unless `RAYON_NUM_THREADS` says otherwise. The
    /// render example's `--threads` means the same.
    pub threads: usize,
    /// Side of the square tiles handed to workers, in pixels.
    pub tile_size: u32,
    /// Gather rays, cache density and corner rule of [`Mode::FinalGather`] (checked only in
    /// that mode).
    pub final_gather: FinalGatherOptions,
    /// How photons leave the lights ([`PhotonEmission::Uniform`] by default; camera-driven
    /// emission is refused in [`Mode::PathTrace`], which traces no photons).
    pub emission: PhotonEmission,
}

impl Default for RenderSettings {
    fn default() -> Self {
        RenderSettings {
            width: 500,
            height: 500,
            samples_per_pixel: 1,
            photons: 100_000,
            k: EstimatorOptions::DEFAULT_K,
            max_distance: None,
            reject_behind: false,
            mode: Mode::PhotonMap,
            seed: 0,
            threads: 0,
            tile_size: 16,
            final_gather: FinalGatherOptions::default(),
            emission: PhotonEmission::Uniform,
        }
    }
}

impl RenderSettings {
    /// The most samples per pixel ([`crate::limits::MAX_SAMPLES_PER_PIXEL`], 2¹⁶); more are
    /// refused with [`RenderError::TooManySamples`].
    pub const MAX_SAMPLES_PER_PIXEL: u32 = crate::limits::MAX_SAMPLES_PER_PIXEL;

    /// The most worker threads ([`crate::limits::MAX_THREADS`], 512); more are refused with
    /// [`RenderError::TooManyThreads`].
    pub const MAX_THREADS: usize = crate::limits::MAX_THREADS;

    /// Checks sizes, counts and distances before anything is allocated; the error names the
    /// bad setting and the limit. The limits: [`crate::image::MAX_PIXELS`] pixels,
    /// [`Self::MAX_SAMPLES_PER_PIXEL`] samples per pixel, [`pm_trace::MAX_PHOTON_PATHS`]
    /// photon paths and [`Self::MAX_THREADS`] threads.
    pub fn validate(&self) -> Result<(), RenderError> {
        crate::image::check_image_size(self.width, self.height)?;
        if self.samples_per_pixel == 0 {
            return Err(RenderError::ZeroSamples);
        }
        if self.samples_per_pixel > Self::MAX_SAMPLES_PER_PIXEL {
            return Err(RenderError::TooManySamples(self.samples_per_pixel));
        }
        if self.photons == 0 && self.mode.uses_photons() {
            return Err(RenderError::ZeroPhotons);
        }
        if self.photons > pm_trace::MAX_PHOTON_PATHS && self.mode.uses_photons() {
            return Err(RenderError::Trace(pm_trace::TraceError::TooManyPhotons {
                photons: self.photons,
            }));
        }
        if self.threads > Self::MAX_THREADS {
            return Err(RenderError::TooManyThreads(self.threads));
        }
        if self.tile_size == 0 {
            return Err(RenderError::ZeroTileSize);
        }
        if let PhotonEmission::CameraDriven(guide) = self.emission {
            if !self.mode.uses_photons() {
                return Err(RenderError::BadEmission(format!(
                    "the {} mode traces no photons",
                    self.mode
                )));
            }
            guide.validate().map_err(RenderError::BadEmission)?;
        }
        if self.mode == Mode::FinalGather {
            self.final_gather.validate()?;
            // One cache point in more photons than are traced is, in expectation, less than
            // one point: the gather would silently lose its indirect light.
            if self.final_gather.cache_every > self.photons {
                return Err(RenderError::BadFinalGather(format!(
                    "cache points every {} photons, but only {} photons are traced: \
                     no cache point can be expected (lower it, or trace more photons)",
                    self.final_gather.cache_every, self.photons
                )));
            }
        }
        self.estimator_options(&Aabb::cube(glam::Vec3::ZERO, 1.0))
            .validate()
    }

    /// The picture's size, samples and tiles, for the render core's tile loop.
    pub fn frame(&self) -> crate::core::tiles::Frame {
        crate::core::tiles::Frame {
            width: self.width,
            height: self.height,
            samples_per_pixel: self.samples_per_pixel,
            tile_size: self.tile_size,
        }
    }

    /// The estimator options these settings give for a scene with `bounds`: photons of kind
    /// direct are left out in [`Mode::ShadowRays`], where shadow rays supply direct light.
    pub fn estimator_options(&self, bounds: &Aabb) -> EstimatorOptions {
        let mut options = match self.max_distance {
            Some(d) => EstimatorOptions::with_max_distance(d),
            None => EstimatorOptions::for_scene(bounds),
        };
        options.k = self.k;
        options.reject_behind = self.reject_behind;
        if self.mode == Mode::ShadowRays {
            options.kinds = KindMask::NOT_DIRECT;
        }
        options
    }
}
