//! Render modes: what radiance a camera ray carries. `PhotonMap` reads the photon maps at
//! the first diffuse hit, `ShadowRays` adds direct light by shadow rays, `PathTrace` is the
//! unbiased reference, `FinalGather` reads the maps through one gathered bounce.

mod direct;
pub(crate) mod final_gather;
mod path_trace;
pub(crate) mod scatter;
mod visualize;

pub use direct::direct_irradiance;
pub use final_gather::FinalGatherOptions;

use crate::{Estimator, EstimatorOptions, EstimatorScratch, MapView, RadianceCache, SurfacePoint};
use glam::Vec3;
use pm_trace::{Hit, PhotonMaps, Ray, Rng, Scene};
use std::fmt;

/// How a camera ray's radiance is computed.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Mode {
    /// Follow specular bounces from the eye, then at the first diffuse hit return emission +
    /// `albedo/π · E` from that surface's photon map (the main results of Ball & Stejko's report).
    /// The default. Called `Visualize` before (the deprecated [`Mode::Visualize`] is it; the
    /// render example still reads the name `visualize`).
    PhotonMap,
    /// Direct light by shadow rays to every light, plus the photon map without direct photons
    /// for the rest (Image 1 of Ball & Stejko's report).
    ShadowRays,
    /// An unbiased path tracer with next-event estimation, combined with its diffuse bounces by
    /// multiple importance sampling (power heuristic) where every light supports it
    /// ([`pm_trace::Light::supports_mis`]), and Russian roulette (the reference).
    PathTrace,
    /// Final gathering (Jensen 1996, with Christensen's precomputed irradiance): specular
    /// bounces from the eye to the first diffuse hit x; there direct light by shadow rays
    /// combined with the gather rays that hit lights by multiple importance sampling (power
    /// heuristic, where every light supports it), caustics from the photons of kind caustic
    /// in x's map, and the rest by
    /// [`FinalGatherOptions::gather_rays`] cosine-weighted rays whose diffuse hits read the
    /// [`RadianceCache`] in their own map. Clean images at a fraction of a path tracer's time;
    /// the cache's blur is hidden behind the gathered hemisphere.
    FinalGather,
}

impl Mode {
    /// All modes, in command-line order.
    pub const ALL: [Mode; 4] = [
        Mode::PhotonMap,
        Mode::ShadowRays,
        Mode::PathTrace,
        Mode::FinalGather,
    ];

    /// The old name of [`Mode::PhotonMap`].
    #[deprecated(since = "0.1.0", note = "renamed `Mode::PhotonMap`")]
    #[allow(non_upper_case_globals)]
    pub const Visualize: Mode = Mode::PhotonMap;

    /// The command-line name: `photon-map`, `shadow-rays`, `path-trace` or `final-gather`.
    pub const fn name(self) -> &'static str {
        match self {
            Mode::PhotonMap => "photon-map",
            Mode::ShadowRays => "shadow-rays",
            Mode::PathTrace => "path-trace",
            Mode::FinalGather => "final-gather",
        }
    }

    /// True when the mode reads photon maps (every mode but [`Mode::PathTrace`]).
    pub const fn uses_photons(self) -> bool {
        !matches!(self, Mode::PathTrace)
    }
}

impl fmt::Display for Mode {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.name())
    }
}

/// Everything a mode reads: the scene, the photon maps, and the estimator with its options.
#[derive(Clone, Copy, Debug)]
pub struct Lighting<'a, E> {
    /// The scene.
    pub scene: &'a Scene,
    /// The photon maps (`None` for [`Mode::PathTrace`], which needs none).
    pub maps: Option<&'a PhotonMaps>,
    /// The estimator.
    pub estimator: &'a E,
    /// Its options.
    pub options: &'a EstimatorOptions,
    /// The angle a pixel spans ([`pm_trace::Camera::pixel_angle`]): PhotonMap and ShadowRays
    /// average textures over the pixel's footprint at the diffuse hit (distance travelled
    /// from the eye times this, over the square root of the cosine there). Zero point-samples
    /// textures, as PathTrace always does (it averages them by its samples, unbiased).
    pub pixel_angle: f32,
    /// The precomputed irradiance read by [`Mode::FinalGather`]'s gather rays (`None` for the
    /// other modes; the final gather then sees no indirect light).
    pub cache: Option<&'a RadianceCache>,
    /// The final gather's parameters.
    pub final_gather: FinalGatherOptions,
}

impl<E: Estimator> Lighting<'_, E> {
    /// Irradiance at `hit` from the photon map of the part hit (zero when that map is missing).
    #[inline]
    pub fn photon_irradiance(&self, hit: &Hit, scratch: &mut EstimatorScratch) -> Vec3 {
        let Some(maps) = self.maps else { return Vec3::ZERO };
        let Some(map) = maps.maps().get(maps.map_of(hit.part) as usize) else {
            return Vec3::ZERO;
        };
        let view = MapView {
            tree: map.tree(),
            polygons: map.geometry(),
        };
        let at = SurfacePoint {
            position: hit.position,
            normal: self.scene.shading_normal_at(hit),
            front_face: hit.front_face,
        };
        self.estimator.irradiance(at, view, self.options, scratch)
    }

    /// Radiance arriving along the camera `ray` under `mode`.
    #[inline]
    pub fn radiance(&self, mode: Mode, ray: Ray, rng: &mut Rng, scratch: &mut EstimatorScratch) -> Vec3 {
        match mode {
            Mode::PhotonMap => visualize::radiance(self, ray, rng, scratch, false),
            Mode::ShadowRays => visualize::radiance(self, ray, rng, scratch, true),
            Mode::PathTrace => path_trace::radiance(self.scene, ray, rng),
            Mode::FinalGather => match self.cache {
                Some(cache) => {
                    let source = final_gather::ModeGather {
                        lighting: self,
                        cache,
                    };
                    final_gather::radiance(&source, ray, rng, scratch)
                }
                None => Vec3::ZERO,
            },
        }
    }
}
