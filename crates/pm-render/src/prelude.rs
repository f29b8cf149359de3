//! The names a renderer author reaches for first, in one `use`: scenes and lights, map
//! partitions, photon tracing and maps, the estimators with their building blocks, and the renderers.

pub use crate::progressive::{ProgressiveRenderer, ProgressiveSettings};
pub use crate::{
    Disc, Estimator, EstimatorKind, EstimatorOptions, EstimatorScratch, FixedVolumeEstimator, GatheredPhoton,
    GeometryBall, GeometryCube, Image, MapView, Mode, RenderSettings, RenderStats, Renderer, SurfacePoint,
    find_nearest, gather_found,
};
pub use glam::{Vec3, vec3};
pub use pm_geom::{Aabb, Ball, HalfEdgeMesh, PolygonSet};
pub use pm_kdtree::{Chebyshev, Euclidean, KindMask, Photon, PhotonKind, PhotonTree};
pub use pm_trace::{
    AreaLight, Camera, Contact, CreaseAngle, DirectionalLight, Light, MapAssignment, Material, Partitioned,
    Partitioner, PhotonMaps, PointLight, Scene, SingleMap, SpotLight, Surface, TraceOptions, scenes,
    trace_photons,
};
