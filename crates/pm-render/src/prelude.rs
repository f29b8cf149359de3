//! The names a renderer author reaches for first, in one `use`: scenes and lights, map
//! partitions, photon tracing and maps, rays and hits, the estimators with their building
//! blocks, the render core's source trait, and the renderers.

pub use crate::progressive::{ProgressiveRenderer, ProgressiveSettings};
pub use crate::{
    BsdfWeight, Disc, Estimator, EstimatorKind, EstimatorOptions, EstimatorScratch, FixedVolumeEstimator,
    GatheredPhoton, GeometryBall, GeometryCube, Image, Irradiance, MapView, Mode, PathVertex, PhotonWeight,
    RadianceCache, RadianceSource, RenderSettings, RenderStats, Renderer, SurfacePoint, find_nearest,
    gather_found, gather_within,
};
pub use glam::{Vec3, vec3};
pub use pm_geom::{Aabb, Ball, HalfEdgeMesh, PolygonSet};
pub use pm_kdtree::{Chebyshev, Euclidean, KindMask, Photon, PhotonKind, PhotonTree};
pub use pm_trace::{
    AreaLight, Camera, Contact, CreaseAngle, DirectionalLight, Hit, Light, MapAssignment, Material,
    Partitioned, Partitioner, PhotonMaps, PointLight, Ray, RayKind, Rng, Scene, SingleMap, SpotLight,
    Surface, TraceOptions, scenes, trace_photons,
};
