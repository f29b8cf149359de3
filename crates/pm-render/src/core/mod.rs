//! The render core: the one path from a camera ray to radiance. A ray follows the delta
//! (mirror and glass) bounces to its first vertex where radiance is *read*, and a
//! [`RadianceSource`] reads it there; every mode is a choice of source, and one tile loop
//! ([`render_tiles`]) renders any source, one-shot or as a progressive pass.
//!
//! ```text
//!  camera ray ──► follow_delta_bounces ──► PathVertex ──► RadianceSource::carried ──► pixel
//!                 (mirror, glass; emission    (hit, throughput,   photon maps, a pass's fixed
//!                  seen on the way)            distance)          volumes, a final gather, a path tracer
//! ```

pub(crate) mod delta;
pub mod pixel_samples;
pub(crate) mod tiles;

pub use delta::specular_bounce;
pub use pm_trace::bsdf::near_specular::{NEAR_SPECULAR_ROUGHNESS, passes_through};
pub use tiles::{Frame, SampleStreams, Tile, render_tiles};

use crate::estimator::scratch::EstimatorScratch;
use glam::Vec3;
use pm_trace::{Hit, Ray, RayKind, Rng, Scene};

/// Longest chain of delta bounces followed to the first vertex where radiance is read.
pub const MAX_DELTA_BOUNCES: u32 = 16;

/// The first vertex of a path where radiance is read: a hit on a non-delta (diffuse) surface,
/// reached through [`PathVertex::bounces`] delta bounces.
#[derive(Clone, Copy, Debug)]
pub struct PathVertex {
    /// The surface hit.
    pub hit: Hit,
    /// The ray that hit it (its direction points at the surface).
    pub ray: Ray,
    /// The product of the delta bounces' factors from the path's start.
    pub throughput: Vec3,
    /// Distance travelled from the path's start (metres).
    pub distance: f32,
    /// Delta bounces before this vertex (0: the path's first hit).
    pub bounces: u32,
}

/// Follows `ray` through delta bounces (surfaces whose [`Bsdf::lobes`](pm_trace::Bsdf::lobes) are all delta: mirror,
/// glass; and near-specular glossy ones, [`passes_through`]) to its
/// first hit where radiance
/// is read, at most [`MAX_DELTA_BOUNCES`] bounces.
/// `visit(hit, ray, throughput, bounce)` sees every hit first, the delta ones and the last,
/// with the throughput that reaches it (so a caller can count emission on the way).
/// `None` when the path leaves the scene, or a bounce ends it, before a non-delta hit.
#[inline]
pub fn follow_delta_bounces(
    scene: &Scene,
    ray: Ray,
    kind: RayKind,
    rng: &mut Rng,
    visit: impl FnMut(&Hit, &Ray, Vec3, u32),
) -> Option<PathVertex> {
    follow_delta_bounces_from(scene, None, ray, kind, rng, visit)
}

/// [`follow_delta_bounces`] for a `ray` that leaves the surface point `from` (a gather ray,
/// made by [`Scene::spawn_ray`]): no ray of the chain searches the triangle it leaves
/// ([`Scene::intersect_from`]), so a sliver's rounding never ends the path at its own start.
/// `None` for `from` is [`follow_delta_bounces`].
#[inline]
pub fn follow_delta_bounces_from(
    scene: &Scene,
    from: Option<&Hit>,
    mut ray: Ray,
    kind: RayKind,
    rng: &mut Rng,
    mut visit: impl FnMut(&Hit, &Ray, Vec3, u32),
) -> Option<PathVertex> {
    let mut throughput = Vec3::ONE;
    let mut distance = 0.0f32;
    let mut left = from.copied();
    for bounces in 0..=MAX_DELTA_BOUNCES {
        let hit = match &left {
            Some(from) => scene.intersect_from(from, &ray, f32::INFINITY, kind)?,
            None => scene.intersect(&ray, f32::INFINITY, kind)?,
        };
        distance += hit.t;
        visit(&hit, &ray, throughput, bounces);
        if !passes_through(scene.material(&hit)) {
            return Some(PathVertex {
                hit,
                ray,
                throughput,
                distance,
                bounces,
            });
        }
        let (next, factor) = specular_bounce(scene, &hit, &ray, rng)?;
        throughput *= factor;
        ray = next;
        left = Some(hit);
    }
    None
}

/// How radiance is read at a path's first non-delta vertex: the one thing render modes differ
/// in. Implement [`RadianceSource::reflected`] (and [`RadianceSource::scene`]); the core does
/// the rest.
///
/// ```
/// use pm_render::core::{PathVertex, RadianceSource};
/// use pm_render::EstimatorScratch;
/// use pm_render::glam::Vec3;
/// use pm_trace::{Rng, Scene};
///
/// /// Every surface reflects a constant radiance (an "ambient" term).
/// struct Ambient<'a> { scene: &'a Scene, radiance: Vec3 }
///
/// impl RadianceSource for Ambient<'_> {
///     fn scene(&self) -> &Scene { self.scene }
///     fn reflected(&self, _: &PathVertex, _: &mut Rng, _: &mut EstimatorScratch) -> Vec3 {
///         self.radiance
///     }
/// }
/// ```
pub trait RadianceSource: Sync {
    /// The scene the paths run through.
    fn scene(&self) -> &Scene;

    /// Radiance reflected at `vertex` back along its ray (W/(m²·sr)), emission not included.
    fn reflected(&self, vertex: &PathVertex, rng: &mut Rng, scratch: &mut EstimatorScratch) -> Vec3;

    /// What the path carries back from `vertex`: its throughput times (emission + reflected).
    /// A source that accumulates along a path of its own (the path tracer) overrides it.
    #[inline]
    fn carried(&self, vertex: &PathVertex, rng: &mut Rng, scratch: &mut EstimatorScratch) -> Vec3 {
        let emitted = self.scene().emission(&vertex.hit);
        vertex.throughput * (emitted + self.reflected(vertex, rng, scratch))
    }
}

/// Radiance arriving along the camera `ray`: emission seen through the delta bounces, plus
/// what `source` reads at the first non-delta vertex.
#[inline]
pub fn camera_radiance<S: RadianceSource + ?Sized>(
    source: &S,
    ray: Ray,
    rng: &mut Rng,
    scratch: &mut EstimatorScratch,
) -> Vec3 {
    let scene = source.scene();
    let mut seen = Vec3::ZERO;
    let vertex = follow_delta_bounces(scene, ray, RayKind::Camera, rng, |hit, _, throughput, _| {
        // Emission on a mirror or glass surface on the way (the last vertex's is the source's).
        if passes_through(scene.material(hit)) {
            let le = scene.emission(hit);
            if le != Vec3::ZERO {
                seen += throughput * le;
            }
        }
    });
    match vertex {
        Some(vertex) => seen + source.carried(&vertex, rng, scratch),
        None => seen,
    }
}
