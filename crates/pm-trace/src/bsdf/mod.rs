//! How light scatters at a surface point: the [`Bsdf`] trait renderer authors implement, and
//! the built-in [`Lambertian`], [`Mirror`], [`Glass`] and glTF's [`MetallicRoughness`] (over
//! the [`TrowbridgeReitz`] microfacet distribution) that implement it.
//!
//! # Conventions
//!
//! - **World space, with the normals at hand.** Every method takes a [`ShadingPoint`]: the
//!   unit geometric normal, the unit shading normal (interpolated vertex normals, on the
//!   geometric normal's side), whether the front was hit, the texture tint, the material's
//!   textured factors ([`TextureFactors`]) and the position.
//!   Directions are world-space unit vectors. World space, not a local frame, because the
//!   renderer keeps two normals apart: a bounce is made about the shading normal, but the
//!   geometric normal decides sides (a mirror or glass bounce falls back to it near a coarse
//!   mesh's silhouette; a diffuse bounce below it is dropped). A local frame would hide the
//!   second normal; a BSDF that wants one builds it from [`ShadingPoint::shading`] with
//!   [`crate::sampling::orthonormal_frame`].
//! - **`wo` and `wi` both point away from the surface.** For a ray of direction `d` that hit
//!   the surface (a camera ray or a photon's), `wo = -d`, and a sampled `wi` is where the path
//!   goes on. The geometric and shading normals are on `wo`'s side. The built-ins are
//!   symmetric in the two (the photon tracer and the camera paths sample them alike).
//! - **`eval` is `f(wo, wi)` alone**, in 1/sr, without the cosine; [`BsdfSample::weight`] is
//!   `f · |cos θi| / pdf` with the cosine taken about the shading normal.
//! - **Delta lobes** (a mirror, smooth glass) have no density: `eval` and `pdf` give 0 for
//!   every pair of directions (they meet the lobe's direction with probability 0), and only
//!   `sample` finds them. A delta sample reports `pdf` = the discrete probability of choosing
//!   that lobe (the Fresnel reflectance for glass's reflection, 1 for a mirror) and `weight` =
//!   the lobe's reflectance divided by that probability; its [`BsdfSample::lobe`] says it was
//!   a delta lobe.
//! - **Random numbers**: [`Bsdf::sample`] takes them as arguments (`u` for the direction,
//!   `u_lobe` to pick a lobe), so tests can feed any numbers; the renderer calls
//!   [`Bsdf::sample_from`], which draws them from the path's stream. Its default draws `u.x`,
//!   `u.y`, then `u_lobe`; the built-ins override it to draw only what they use (a mirror
//!   nothing, glass one number and only when refraction is possible), which keeps the
//!   renderer's streams, and so its images, what they were before this trait existed.
//!
//! # What the renderer asks of a BSDF
//!
//! - [`Bsdf::lobes`] decides the path: a surface with only delta lobes is followed through
//!   (the render core's delta chain, the photon tracer's specular bounces); a surface with a
//!   diffuse or glossy lobe stores photons and is where radiance is read.
//!   A surface with no diffuse lobe whose [`Bsdf::glossy_roughness`] is below the render
//!   core's near-specular threshold is followed through too, by sampling the BSDF.
//! - Where a surface has a glossy lobe, [`Bsdf::eval`] is what every photon-map estimate
//!   reads: radiance `Σ Φ_p f(wo, wi_p) / A` with `wi_p` the direction a photon came from
//!   (the whole `f`, diffuse lobe included); the final gather samples its gather rays from
//!   [`Bsdf::sample`] there and shadow rays evaluate `f` per light.
//! - [`Bsdf::diffuse_albedo`] is what the photon-map estimators read where the non-delta part
//!   is diffuse only: radiance `ρ_d/π · E` from the irradiance `E` (so a Lambertian surface
//!   renders exactly as before), and what the irradiance cache is multiplied by.
//! - [`Bsdf::albedo`] (the directional albedo, reflection plus transmission) is the photon
//!   tracer's Russian roulette probability; the sampled [`BsdfSample::weight`] then carries the
//!   photon's power, so the roulette is unbiased for any albedo in `(0, 1]` reported.
//! - The path tracer's next-event estimation evaluates `f` per light sample on a BSDF with a
//!   glossy lobe, and reads the diffuse lobe (`diffuse_albedo/π` times the light's irradiance,
//!   combined by multiple importance sampling with cosine-distributed bounces) on one whose
//!   non-delta part is one Lambertian lobe sampled by the cosine, as the example below is.
//!
//! # Example: a renderer author's own BSDF
//!
//! ```
//! use pm_trace::bsdf::{Bsdf, BsdfSample, Lobes, ShadingPoint};
//! use pm_trace::glam::{Vec2, Vec3};
//! use pm_trace::sampling::cosine_hemisphere;
//! use std::f32::consts::FRAC_1_PI;
//!
//! /// A grey diffuse surface.
//! #[derive(Debug)]
//! struct Matte(f32);
//!
//! impl Bsdf for Matte {
//!     fn lobes(&self) -> Lobes {
//!         Lobes::DIFFUSE_REFLECTION
//!     }
//!     fn eval(&self, at: &ShadingPoint, _wo: Vec3, wi: Vec3) -> Vec3 {
//!         if at.shading.dot(wi) > 0.0 { Vec3::splat(self.0 * FRAC_1_PI) } else { Vec3::ZERO }
//!     }
//!     fn pdf(&self, at: &ShadingPoint, _wo: Vec3, wi: Vec3) -> f32 {
//!         at.shading.dot(wi).max(0.0) * FRAC_1_PI
//!     }
//!     fn sample(&self, at: &ShadingPoint, wo: Vec3, u: Vec2, _u_lobe: f32) -> Option<BsdfSample> {
//!         let wi = cosine_hemisphere(at.shading, u);
//!         let pdf = self.pdf(at, wo, wi);
//!         // f · cos / pdf = (ρ/π) · cos / (cos/π) = ρ.
//!         (pdf > 0.0).then(|| BsdfSample { wi, weight: Vec3::splat(self.0), pdf, lobe: Lobes::DIFFUSE_REFLECTION })
//!     }
//!     fn albedo(&self, _at: &ShadingPoint, _wo: Vec3) -> Vec3 {
//!         Vec3::splat(self.0)
//!     }
//!     fn diffuse_albedo(&self, _at: &ShadingPoint) -> Vec3 {
//!         Vec3::splat(self.0)
//!     }
//! }
//!
//! // In a scene: `Surface::with_bsdf(&MATTE)` with `static MATTE: Matte = Matte(0.5);`.
//! let at = ShadingPoint::facing(Vec3::Y);
//! let s = Matte(0.5).sample(&at, Vec3::Y, Vec2::new(0.3, 0.7), 0.5).unwrap();
//! assert!(s.wi.y > 0.0 && (s.weight - Vec3::splat(0.5)).abs().max_element() < 1e-6);
//! ```

pub(crate) mod glass;
pub(crate) mod lambertian;
pub(crate) mod lobes;
pub(crate) mod metallic_roughness;
pub(crate) mod microfacet;
pub(crate) mod mirror;
pub mod near_specular;
pub mod scatter;
pub(crate) mod shading_point;

pub use glass::Glass;
pub use lambertian::Lambertian;
pub use lobes::Lobes;
pub use metallic_roughness::MetallicRoughness;
pub use microfacet::{MIN_ALPHA, TrowbridgeReitz};
pub use mirror::Mirror;
pub use near_specular::{NEAR_SPECULAR_ROUGHNESS, passes_through};
pub use shading_point::{ShadingPoint, TextureFactors};

use crate::rng::Rng;
use glam::{Vec2, Vec3};

/// A direction sampled from a [`Bsdf`].
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct BsdfSample {
    /// The sampled direction, unit length, pointing away from the surface.
    pub wi: Vec3,
    /// `f(wo, wi) · |cos θi| / pdf` (for a delta lobe: its reflectance over `pdf`).
    pub weight: Vec3,
    /// The density of `wi` in solid angle, or for a delta lobe the probability of choosing it.
    pub pdf: f32,
    /// The one lobe the direction was sampled from.
    pub lobe: Lobes,
}

/// A bidirectional scattering distribution function: how much of the light arriving from `wi`
/// leaves towards `wo`. See the [module docs](self) for the conventions (world space, both
/// directions away from the surface, `eval` without the cosine, delta lobes) and an example.
///
/// Contract (the tests in `tests/custom_bsdf.rs` and this crate's check the built-ins by it):
/// - `eval` is non-negative and finite; it is 0 for delta lobes.
/// - `pdf(wo, wi)` is the density `sample` draws `wi` with over its non-delta lobes
///   (including the probability of picking that lobe), and integrates to at most 1.
/// - A non-delta sample has `weight = eval(wo, wi) · |shading · wi| / pdf` and
///   `pdf = self.pdf(wo, wi) > 0`.
/// - `albedo(wo)` is the mean of `weight` over samples (the directional albedo, `∫ f |cos|`
///   plus the delta lobes' reflectance), each channel in `[0, 1]` for an energy-conserving
///   surface.
/// - Nothing panics on any direction; a direction the BSDF cannot sample gives `None`.
pub trait Bsdf: Send + Sync + std::fmt::Debug {
    /// The lobes this BSDF has.
    fn lobes(&self) -> Lobes;

    /// `f(wo, wi)` per RGB channel (1/sr), without the cosine; 0 for delta lobes.
    fn eval(&self, at: &ShadingPoint, wo: Vec3, wi: Vec3) -> Vec3;

    /// The density (per steradian) with which [`Bsdf::sample`] picks `wi`; 0 for delta lobes.
    fn pdf(&self, at: &ShadingPoint, wo: Vec3, wi: Vec3) -> f32;

    /// A direction `wi` from uniform numbers `u ∈ [0,1)²` (the direction) and `u_lobe ∈ [0,1)`
    /// (the lobe); `None` when the surface absorbs or nothing can be sampled.
    fn sample(&self, at: &ShadingPoint, wo: Vec3, u: Vec2, u_lobe: f32) -> Option<BsdfSample>;

    /// [`Bsdf::sample`] with its numbers drawn from `rng`: by default `u.x`, `u.y`, then
    /// `u_lobe`. Override to draw fewer (the same distribution, from fewer numbers).
    #[inline]
    fn sample_from(&self, at: &ShadingPoint, wo: Vec3, rng: &mut Rng) -> Option<BsdfSample> {
        let u = Vec2::new(rng.next_f32(), rng.next_f32());
        let u_lobe = rng.next_f32();
        self.sample(at, wo, u, u_lobe)
    }

    /// The directional albedo for light leaving towards `wo`: `∫ f(wo, wi) |cos θi| dwi` plus
    /// the delta lobes' reflectance and transmittance (the photon tracer's Russian roulette).
    fn albedo(&self, at: &ShadingPoint, wo: Vec3) -> Vec3;

    /// The perceptual roughness (glTF's, `α = roughness²`) of this BSDF's sharpest glossy
    /// lobe, or `None` (the default) without a glossy lobe or where it has no such number.
    /// The render core follows a camera path through a surface with no diffuse lobe whose
    /// glossy roughness is below its near-specular threshold (pbrt-v4's rule), sampling the
    /// BSDF there instead of reading photons; `None` is never near-specular.
    #[inline]
    fn glossy_roughness(&self) -> Option<f32> {
        None
    }

    /// The reflectance `ρ_d` of the diffuse lobe (its `f = ρ_d/π`): what the photon-map
    /// estimators multiply irradiance by, `ρ_d/π · E`. Zero (the default) without a diffuse
    /// lobe.
    #[inline]
    fn diffuse_albedo(&self, at: &ShadingPoint) -> Vec3 {
        let _ = at;
        Vec3::ZERO
    }
}
