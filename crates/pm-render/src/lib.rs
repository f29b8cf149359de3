//! Radiance estimators, render modes, a deterministic tiled renderer, and images.
//!
//! The crate turns a [`pm_trace::Scene`] and its photon maps into a picture:
//!
//! - [`estimator`]: irradiance from the photons of one map, by Jensen's [`Disc`], Hey &
//!   Purgathofer's geometry-based [`GeometryCube`], or the [`GeometryBall`] variant; all
//!   generic in the hot loop and allocation-free once their [`EstimatorScratch`] is warm.
//! - [`core`]: the one path from a camera ray to radiance. A ray follows mirror and glass
//!   bounces to its first diffuse vertex ([`PathVertex`]), where a [`RadianceSource`] reads
//!   the radiance; one tile loop renders any source. Bring your own source to render with
//!   the same core ([`Renderer::render_source`]). Camera samples spread over each pixel by
//!   a scrambled Sobol' sequence that progressive passes continue
//!   ([`core::pixel_samples`]).
//! - [`Mode`]: `PhotonMap` (the photon maps read at the first diffuse hit), `ShadowRays`
//!   (direct light by shadow rays), `PathTrace` (the unbiased reference) and `FinalGather`
//!   (one gathered bounce into the [`RadianceCache`], precomputed irradiance in each map);
//!   each is a choice of [`source`].
//! - [`Renderer`]: photon tracing, map building and the image in tiles on rayon workers; the
//!   image is bit-identical for any thread count. [`Progress`] observes it; [`RenderStats`]
//!   times each phase.
//! - [`progressive`]: a consistent progressive renderer (Knaus & Zwicker passes with
//!   fixed-volume estimates, [`FixedVolumeEstimator`]) that stays leak-free and edge-true at
//!   every pass, shards of passes that merge into the bits of one run, and the SPPM baseline.
//! - [`prelude`]: the scene, tracing, map and estimator names most programs need, in one
//!   `use pm_render::prelude::*`.
//! - [`Image`]: linear RGB film, metrics, EXR (feature `exr`) and sRGB PNG (feature `png`),
//!   each written atomically ([`image::write_atomically`]: a failed write keeps the old file).
//!
//! Limits, checked by [`RenderSettings::validate`] before anything is allocated: at most
//! [`image::MAX_PIXELS`] pixels, [`RenderSettings::MAX_SAMPLES_PER_PIXEL`] samples per pixel,
//! [`RenderSettings::MAX_THREADS`] threads and [`pm_trace::MAX_PHOTON_PATHS`] photon paths;
//! past one, a [`RenderError`] naming it.
//!
//! Conventions: metres, watts, f32; right-handed with +y up; colour is linear RGB with
//! Rec. 709 primaries. Irradiance is in W/m², radiance in W/(m²·sr); a Lambertian surface of
//! albedo ρ under irradiance E has radiance ρE/π.
//!
//! ```
//! use pm_render::glam::Vec3;
//! use pm_render::{EstimatorKind, Mode, RenderSettings, Renderer};
//! use pm_trace::{Camera, CreaseAngle, Partitioner, PointLight, Scene, Surface};
//! use std::f32::consts::PI;
//!
//! // pbrt's analytic scene: a point light of intensity π at the centre of a closed diffuse
//! // sphere of albedo 0.5 gives radiance 1 everywhere inside.
//! let scene = Scene::builder()
//!     .sphere(Vec3::ZERO, 1.0, Surface::diffuse(Vec3::splat(0.5)))
//!     .light(PointLight::new(Vec3::ZERO, Vec3::splat(4.0 * PI * PI)))
//!     .camera(Camera::new(Vec3::new(0.0, 0.0, 0.5), Vec3::NEG_Z, Vec3::Y, 1.2))
//!     .build()?;
//! let settings = RenderSettings { width: 32, height: 32, photons: 20_000, mode: Mode::PhotonMap, ..Default::default() };
//! let partitioned = CreaseAngle::default().partition(scene)?;
//! let out = Renderer::new(EstimatorKind::GeometryCube, settings).render(&partitioned, &())?;
//! assert!((out.image.mean().x - 1.0).abs() < 0.05);
//! println!("{:.3} s in total", out.stats.total().as_secs_f64());
//! # Ok::<(), Box<dyn std::error::Error>>(())
//! ```
//!
//! # References
//!
//! - H. W. Jensen, *Global Illumination using Photon Maps*, Rendering Techniques '96
//!   (Eurographics Workshop on Rendering), 1996: photon maps and the disc estimate
//!   `E = Σ Φ / (π r²)` over the k nearest photons.
//! - R. D. Larsen and N. J. Christensen, *Optimizing Photon Mapping Using Multiple Photon Maps
//!   for Irradiance Estimates*, WSCG 2003: one photon map per group of faces joined across
//!   edges with a small crease angle, so that no estimate gathers through a wall.
//! - H. Hey and W. Purgathofer, *Advanced Radiance Estimation for Photon Map Global
//!   Illumination*, Computer Graphics Forum 21(3), 2002: gather in a cube and divide by the
//!   surface area actually inside it, so that edges are not darkened.
//! - Ball and Stejko's project report, which combines the three and whose scenes (the Cornell
//!   box, the lit and unlit rooms, the coloured rooms, the accordion), four variants (basic,
//!   multiple maps, geometry area, both) and timing table this workspace reproduces; "the
//!   report" in these docs is that report. The reproduction is in the repository's
//!   `docs/results.md`.
//! - I. M. Sobol', *On the distribution of points in a cube and the approximate evaluation of
//!   integrals*, USSR Computational Mathematics and Mathematical Physics 7(4), 1967: the
//!   low-discrepancy sequence the camera samples follow. Each pixel's is randomised by a
//!   digital shift, which keeps its stratification and makes every sample uniform (P.
//!   L'Ecuyer and C. Lemieux, *Recent Advances in Randomized Quasi-Monte Carlo Methods*,
//!   2002).

pub mod auto_photons;
pub mod cache;
pub mod cache_file;
pub mod core;
pub mod emission;
pub mod error;
pub mod estimator;
pub mod image;
pub mod limits;
pub mod mode;
pub mod prelude;
pub mod progress;
pub mod progressive;
pub mod renderer;
pub mod settings;
pub mod source;
pub mod stats;

pub use auto_photons::{AutoBatch, AutoPhotons, AutoPhotonsReport};
pub use cache::{CachePoint, CacheQuery, CachedRadiance, QueryMap, RadianceCache};
pub use core::{PathVertex, RadianceSource};
pub use error::RenderError;
pub use estimator::{
    BsdfWeight, Disc, Estimator, EstimatorKind, EstimatorOptions, EstimatorScratch, FixedVolumeEstimator,
    GatheredPhoton, GeometryBall, GeometryCube, Irradiance, MapView, PhotonWeight, SurfacePoint,
    VolumeMetric, find_nearest, gather_found, gather_within, irradiance_in_volume,
};
/// The glam version this crate's API uses (`Vec3`), so users need not pin it by hand.
pub use glam;
pub use image::Image;
pub use mode::Mode;
pub use progress::Progress;
pub use renderer::{PhotonCache, Rendered, Renderer};
pub use settings::RenderSettings;
pub use source::FinalGatherOptions;
pub use stats::RenderStats;
