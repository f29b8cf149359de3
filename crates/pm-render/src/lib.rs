//! Radiance estimators, render modes, a deterministic tiled renderer, and images.
//!
//! (Crate docs completed below once the renderer lands.)

pub mod error;
pub mod estimator;
pub mod image;

pub use error::RenderError;
pub use estimator::{
    Disc, Estimator, EstimatorKind, EstimatorOptions, EstimatorScratch, GatheredPhoton, GeometryBall,
    GeometryCube, MapView, SurfacePoint, VolumeMetric, irradiance_in_volume,
};
pub use image::Image;
