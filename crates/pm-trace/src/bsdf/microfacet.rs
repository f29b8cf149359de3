//! The Trowbridge-Reitz (GGX) microfacet distribution: its normal density `D`, Smith masking
//! `Λ`/`G1`, height-correlated shadowing-masking `G2` and visibility `V`, and visible-normal
//! sampling (Dupuy & Benyoub 2023's spherical caps), in a local frame whose `z` is the normal.
//!
//! References: Walter et al. 2007 (GGX), Heitz 2014 ("Understanding the Masking-Shadowing
//! Function in Microfacet-Based BRDFs": `Λ`, the height-correlated `G2`, the visible-normal
//! density `D_ω(ωm) = G1(ω) max(0, ω·ωm) D(ωm) / cos θ`), Heitz 2018 and Dupuy & Benyoub 2023
//! (sampling `D_ω` exactly), pbrt-v4's `TrowbridgeReitzDistribution`.
//!
//! Every formula is written with `sin² θ = x² + y²` rather than `1 − cos² θ`, so that near the
//! normal (where a smooth surface's lobe lives) nothing cancels in single precision.

use glam::{Vec2, Vec3};
use std::f32::consts::{FRAC_1_PI, TAU};

/// The smallest `α` kept: below it the lobe is narrower than single precision resolves near
/// the normal (`1 − cos θ` at `θ = α = 1e-3` is `5e-7`, a few ulps of one). pbrt-v4 turns a
/// surface this smooth into a delta lobe; here it stays a glossy lobe of this width (about
/// 0.06° across), so a roughness of 0 renders as a very sharp, still sampled, highlight.
pub const MIN_ALPHA: f32 = 1e-3;

/// The isotropic Trowbridge-Reitz (GGX) distribution of microfacet normals of width `α`.
/// Directions are unit vectors in a local frame whose `z` axis is the macro-surface normal.
/// References: Walter et al. 2007; Heitz 2014 (`Λ`, height-correlated `G2`, the visible-normal
/// density); Dupuy & Benyoub 2023 (spherical-cap sampling, equivalent to Heitz 2018);
/// pbrt-v4's `TrowbridgeReitzDistribution`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct TrowbridgeReitz {
    alpha: f32,
}

impl TrowbridgeReitz {
    /// The distribution of width `alpha` (glTF's `roughness²`), raised to [`MIN_ALPHA`] when
    /// below it (a NaN becomes [`MIN_ALPHA`] too).
    #[inline]
    pub fn new(alpha: f32) -> Self {
        TrowbridgeReitz {
            alpha: alpha.max(MIN_ALPHA),
        }
    }

    /// The width `α` used.
    #[inline]
    pub fn alpha(&self) -> f32 {
        self.alpha
    }

    /// The density of microfacet normals per unit projected area, `D(ωm)` (1/sr):
    /// `α² / (π (α² cos² θm + sin² θm)²)` above the surface, 0 below. `∫ D cos θm dωm = 1`.
    #[inline]
    pub fn d(&self, wm: Vec3) -> f32 {
        if wm.z <= 0.0 {
            return 0.0;
        }
        let a2 = self.alpha * self.alpha;
        let sin2 = wm.x * wm.x + wm.y * wm.y;
        let t = a2 * wm.z * wm.z + sin2;
        if t <= 0.0 {
            return 0.0;
        }
        a2 * FRAC_1_PI / (t * t)
    }

    /// `√(cos² θ + α² sin² θ)`, the term `Λ`, `G1` and `V` share (`cos θ · √(1 + α² tan² θ)`).
    #[inline]
    fn root(&self, w: Vec3) -> f32 {
        let a2 = self.alpha * self.alpha;
        (w.z * w.z + a2 * (w.x * w.x + w.y * w.y)).sqrt()
    }

    /// Smith's auxiliary function `Λ(ω) = (√(1 + α² tan² θ) − 1) / 2` (infinite at grazing).
    #[inline]
    pub fn lambda(&self, w: Vec3) -> f32 {
        let c = w.z.abs();
        if c == 0.0 {
            return f32::INFINITY;
        }
        0.5 * (self.root(w) / c - 1.0)
    }

    /// Smith's masking `G1(ω) = 1 / (1 + Λ(ω)) = 2 |cos θ| / (|cos θ| + √(cos² θ + α² sin² θ))`.
    #[inline]
    pub fn g1(&self, w: Vec3) -> f32 {
        let c = w.z.abs();
        let r = self.root(w);
        if c + r == 0.0 {
            return 0.0;
        }
        2.0 * c / (c + r)
    }

    /// The height-correlated shadowing-masking `G2(ωo, ωi) = 1 / (1 + Λ(ωo) + Λ(ωi))`.
    #[inline]
    pub fn g2(&self, wo: Vec3, wi: Vec3) -> f32 {
        let (co, ci) = (wo.z.abs(), wi.z.abs());
        let t = ci * self.root(wo) + co * self.root(wi);
        if t == 0.0 {
            return 0.0;
        }
        2.0 * co * ci / t
    }

    /// glTF's visibility `V = G2 / (4 |cos θo| |cos θi|)
    /// = 1 / (2 (|cos θi| √(cos² θo + α² sin² θo) + |cos θo| √(cos² θi + α² sin² θi)))`,
    /// so that the specular BRDF is `V · D`. Zero when either direction is grazing.
    #[inline]
    pub fn visibility(&self, wo: Vec3, wi: Vec3) -> f32 {
        let (co, ci) = (wo.z.abs(), wi.z.abs());
        if co == 0.0 || ci == 0.0 {
            return 0.0;
        }
        0.5 / (ci * self.root(wo) + co * self.root(wi))
    }

    /// The density of normals visible from `w` (above the surface), per steradian of `ωm`:
    /// `D_ω(ωm) = G1(ω) max(0, ω·ωm) D(ωm) / cos θ`; integrates to 1 over the sphere.
    #[inline]
    pub fn visible_normal_pdf(&self, w: Vec3, wm: Vec3) -> f32 {
        if w.z <= 0.0 {
            return 0.0;
        }
        self.g1(w) * w.dot(wm).max(0.0) * self.d(wm) / w.z
    }

    /// A microfacet normal drawn from [`Self::visible_normal_pdf`] for `w` (above the surface)
    /// from `u ∈ [0,1)²`: Dupuy & Benyoub 2023 — stretch `w` to the hemisphere configuration
    /// (`α = 1`), sample the spherical cap of directions whose half-vector with it is visible,
    /// take the half-vector, unstretch.
    #[inline]
    pub fn sample_visible_normal(&self, w: Vec3, u: Vec2) -> Vec3 {
        let a = self.alpha;
        let wh = Vec3::new(a * w.x, a * w.y, w.z).normalize();
        let phi = TAU * u.x;
        let z = (1.0 - u.y) * (1.0 + wh.z) - wh.z;
        let sin_theta = (1.0 - z * z).clamp(0.0, 1.0).sqrt();
        let (s, c) = phi.sin_cos();
        let h = Vec3::new(sin_theta * c, sin_theta * s, z) + wh;
        Vec3::new(a * h.x, a * h.y, h.z.max(0.0)).normalize_or(Vec3::Z)
    }
}
