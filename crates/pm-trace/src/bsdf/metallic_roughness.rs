//! glTF 2.0's metallic-roughness material as its specification's Appendix B writes it (with
//! `KHR_materials_ior` and `KHR_materials_specular`): a GGX specular lobe over a Lambertian
//! one for the dielectric, a GGX lobe with Schlick's Fresnel of the base colour for the metal.

use super::lobes::Lobes;
use super::microfacet::TrowbridgeReitz;
use super::shading_point::ShadingPoint;
use super::{Bsdf, BsdfSample};
use crate::error::MaterialError;
use crate::sampling::{cosine_hemisphere_in_frame, orthonormal_frame};
use glam::{Vec2, Vec3};
use std::f32::consts::FRAC_1_PI;

/// The glTF 2.0 metallic-roughness material. Made by [`MetallicRoughness::new`] and its
/// `with_` methods, which check every parameter, so a value of this type is always in range.
///
/// # The BRDF (Appendix B, height-correlated Smith visibility)
///
/// With `α = roughness²` (at least [`MIN_ALPHA`](crate::bsdf::MIN_ALPHA)), `H` the half-vector of `wo` and `wi`,
/// `w = (1 − |wo·H|)⁵`, `base = baseColor · tint` and the [`TrowbridgeReitz`] `D` and `V`
/// (`metallic` and `roughness` are the factors times the point's textures:
/// [`MetallicRoughness::at_point`]):
///
/// ```text
/// specular_brdf   = V · D
/// f0              = min(((ior − 1)/(ior + 1))² · specularColor, 1) · specular   (per channel)
/// F               = f0 + (specular − f0) · w                                    (per channel)
/// dielectric_brdf = F · specular_brdf + (1 − max(F.r, F.g, F.b)) · base / π
/// metal_brdf      = specular_brdf · (base + (1 − base) · w)
/// f               = mix(dielectric_brdf, metal_brdf, metallic)
/// ```
///
/// With `ior = 1.5` and `specular = 1`, `specularColor = 1` (the defaults) `F` is Appendix B's
/// `0.04 + 0.96 w` and `dielectric_brdf` its `mix(base/π, specular_brdf, F)`. The
/// `KHR_materials_specular` form (`max` over channels in the diffuse weight, `f0` clamped to
/// 1 before `specular` scales it) is the ratified extension's. `specular = 0` leaves the
/// Lambertian `base/π` alone (how a file says "matte"); glTF's default matte (metallic 0,
/// roughness 1) keeps a Fresnel layer with `f0 = 0.04`, as the specification says.
///
/// Reflection only: `f = 0` unless both directions are above the lobe normal, which is the
/// shading normal when `wo` is above it and the geometric normal otherwise (near a coarse
/// mesh's silhouette, as the mirror does); `f` is reciprocal wherever both directions are above
/// the shading normal.
///
/// # What is approximated
///
/// Single scattering only, as the specification: light that bounces more than once between
/// microfacets is lost, so a white metal's directional albedo falls below one as roughness
/// grows (measured by `tests/ggx.rs`, quadrature and sampling agreeing): at roughness 1 and
/// normal incidence it reflects `1 − ln 2 ≈ 0.307` (a closed form there), a loss of 69 %;
/// 0.38 to 0.76 at other incidences; at roughness 0.6 0.78 to 0.88; at roughness 0.3 0.99 at
/// normal incidence and 0.88 at `cos θo = 0.1`. The specification's `fresnel_mix` is not
/// energy-conserving the other way: the dielectric's diffuse weight `1 − F(wo·H)` is not the
/// light the specular lobe leaves over, so a white dielectric reflects more than it receives
/// at oblique incidence (1.07 at roughness 0.1 and `cos θo = 0.4`, 1.53 at `cos θo = 0.1`; a
/// 0.5 grey one 1.06 there). Both are the specification's, kept so that images agree with
/// other glTF renderers.
///
/// # Sampling
///
/// One-sample multiple importance sampling over two lobes: the specular lobe by visible
/// normals ([`TrowbridgeReitz::sample_visible_normal`], pdf `D_wo(H) / (4 |wo·H|)`) and the
/// diffuse one by the cosine, picked with a probability from their estimated albedos at `wo`
/// (clamped to `[0.1, 0.9]` when both lobes are present, so neither is starved). `pdf` is the
/// mixture `p · pdf_spec + (1 − p) · pdf_diff` and a sample's weight `f · cos θi / pdf` with
/// the whole `f`. A specular sample that reflects below the surface is `None` (that mass is
/// missing from the density: it integrates to less than one at high roughness).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct MetallicRoughness {
    base_color: Vec3,
    metallic: f32,
    roughness: f32,
    ior: f32,
    specular: f32,
    specular_color: Vec3,
}

/// `value` unless it is NaN, infinite or outside `[lo, hi]`.
fn in_range(
    parameter: &'static str,
    value: f32,
    lo: f32,
    hi: f32,
    range: &'static str,
) -> Result<f32, MaterialError> {
    if value.is_finite() && (lo..=hi).contains(&value) {
        Ok(value)
    } else {
        Err(MaterialError::OutOfRange {
            parameter,
            value,
            range,
        })
    }
}

/// Each channel of `colour` checked by [`in_range`].
fn colour_in_range(
    parameter: &'static str,
    colour: Vec3,
    hi: f32,
    range: &'static str,
) -> Result<Vec3, MaterialError> {
    for c in colour.to_array() {
        in_range(parameter, c, 0.0, hi, range)?;
    }
    Ok(colour)
}

impl MetallicRoughness {
    /// glTF's `pbrMetallicRoughness`: `base_color` per channel in `[0, 1]` (linear),
    /// `metallic` and `roughness` in `[0, 1]`; index of refraction 1.5 and a full, white
    /// specular layer (glTF's defaults without the extensions).
    pub fn new(base_color: Vec3, metallic: f32, roughness: f32) -> Result<Self, MaterialError> {
        Ok(MetallicRoughness {
            base_color: colour_in_range("baseColorFactor", base_color, 1.0, "finite and in [0, 1]")?,
            metallic: in_range("metallicFactor", metallic, 0.0, 1.0, "finite and in [0, 1]")?,
            roughness: in_range("roughnessFactor", roughness, 0.0, 1.0, "finite and in [0, 1]")?,
            ior: 1.5,
            specular: 1.0,
            specular_color: Vec3::ONE,
        })
    }

    /// `KHR_materials_ior`: the dielectric's index of refraction, 1 or more, or 0 (which the
    /// extension allows and which makes `f0 = 1`).
    pub fn with_ior(self, ior: f32) -> Result<Self, MaterialError> {
        if ior == 0.0 {
            return Ok(MetallicRoughness { ior, ..self });
        }
        let ior = in_range("ior", ior, 1.0, f32::MAX, "finite and at least 1, or 0")?;
        Ok(MetallicRoughness { ior, ..self })
    }

    /// `KHR_materials_specular`: the strength of the dielectric's specular layer in `[0, 1]`
    /// (0 removes it) and its colour at normal incidence, each channel finite and
    /// non-negative (it may exceed 1; `f0` is clamped to 1 as the extension says).
    pub fn with_specular(self, specular: f32, specular_color: Vec3) -> Result<Self, MaterialError> {
        Ok(MetallicRoughness {
            specular: in_range("specularFactor", specular, 0.0, 1.0, "finite and in [0, 1]")?,
            specular_color: colour_in_range(
                "specularColorFactor",
                specular_color,
                f32::MAX,
                "finite and non-negative",
            )?,
            ..self
        })
    }

    /// The base colour (before the point's tint).
    pub fn base_color(&self) -> Vec3 {
        self.base_color
    }

    /// The metalness, 0 (dielectric) to 1 (metal).
    pub fn metallic(&self) -> f32 {
        self.metallic
    }

    /// The perceptual roughness; `α = roughness²`.
    pub fn roughness(&self) -> f32 {
        self.roughness
    }

    /// The dielectric's index of refraction.
    pub fn ior(&self) -> f32 {
        self.ior
    }

    /// The dielectric's specular strength.
    pub fn specular(&self) -> f32 {
        self.specular
    }

    /// The dielectric's specular colour.
    pub fn specular_color(&self) -> Vec3 {
        self.specular_color
    }

    /// This material at `at`: the base colour times the point's tint, metallic, roughness,
    /// specular strength and specular colour times its
    /// [`TextureFactors`](super::shading_point::TextureFactors) (the first three kept in
    /// `[0, 1]`, the colour not negative, a NaN read as 0). Every [`Bsdf`] method evaluates
    /// this; with no texture (tint and factors one) it is `self`, bit for bit.
    #[inline]
    pub fn at_point(&self, at: &ShadingPoint) -> MetallicRoughness {
        let unit = |x: f32| if x.is_nan() { 0.0 } else { x.clamp(0.0, 1.0) };
        let colour = self.specular_color * at.factors.specular_color;
        MetallicRoughness {
            base_color: self.base_color * at.tint,
            metallic: unit(self.metallic * at.factors.metallic),
            roughness: unit(self.roughness * at.factors.roughness),
            specular: unit(self.specular * at.factors.specular),
            specular_color: Vec3::select(colour.cmpge(Vec3::ZERO), colour, Vec3::ZERO),
            ..*self
        }
    }

    /// The microfacet distribution, `α = roughness²` raised to [`MIN_ALPHA`](crate::bsdf::MIN_ALPHA).
    pub fn distribution(&self) -> TrowbridgeReitz {
        TrowbridgeReitz::new(self.roughness * self.roughness)
    }

    /// The dielectric's reflectance at normal incidence,
    /// `min(((ior − 1)/(ior + 1))² · specularColor, 1) · specular`.
    pub fn dielectric_f0(&self) -> Vec3 {
        let r = (self.ior - 1.0) / (self.ior + 1.0);
        (r * r * self.specular_color).min(Vec3::ONE) * self.specular
    }

    /// The dielectric's Fresnel term for `w = (1 − |wo·H|)⁵`.
    #[inline]
    fn dielectric_fresnel(&self, w: f32) -> Vec3 {
        let f0 = self.dielectric_f0();
        f0 + (Vec3::splat(self.specular) - f0) * w
    }

    /// True when the specular lobe is not identically zero.
    #[inline]
    fn has_specular(&self) -> bool {
        self.metallic > 0.0 || self.specular > 0.0
    }

    /// True when the diffuse lobe is not identically zero for the base colour `base`: some
    /// dielectric, a colour, and a Fresnel term that is not one everywhere.
    #[inline]
    fn has_diffuse(&self, base: Vec3) -> bool {
        self.metallic < 1.0 && base.max_element() > 0.0 && self.dielectric_f0().max_element() < 1.0
    }

    /// The probability of sampling the specular lobe for `wo` at `cos_o` above the normal.
    #[inline]
    fn specular_probability(&self, base: Vec3, cos_o: f32) -> f32 {
        if !self.has_specular() {
            return 0.0;
        }
        if !self.has_diffuse(base) {
            return 1.0;
        }
        let (specular, diffuse) = self.lobe_albedos(base, cos_o);
        let (s, d) = (specular.element_sum(), diffuse.element_sum());
        (s / (s + d)).clamp(0.1, 0.9)
    }

    /// Estimates of the specular and diffuse lobes' directional albedos at `cos_o`: the
    /// Fresnel terms at `wo·H = cos θo` (at least their cosine-weighted hemispherical mean,
    /// so that no present lobe gets zero), ignoring the microfacets' shadowing.
    #[inline]
    fn lobe_albedos(&self, base: Vec3, cos_o: f32) -> (Vec3, Vec3) {
        let w = schlick_weight(cos_o).max(1.0 / 21.0);
        let f_d = self.dielectric_fresnel(w);
        let f_m = base + (Vec3::ONE - base) * w;
        let m = self.metallic;
        let specular = (1.0 - m) * f_d + m * f_m;
        let diffuse = (1.0 - m) * (1.0 - f_d.max_element()) * base;
        (specular, diffuse)
    }
}

/// `(1 − c)⁵`, Schlick's weight.
#[inline]
fn schlick_weight(c: f32) -> f32 {
    let x = (1.0 - c).clamp(0.0, 1.0);
    let x2 = x * x;
    x2 * x2 * x
}

/// The local frame lobes are shaped in: `(t, b, n)` with `n` the shading normal when `wo` is
/// above it, else the geometric normal.
#[derive(Clone, Copy)]
struct Frame {
    t: Vec3,
    b: Vec3,
    n: Vec3,
}

impl Frame {
    #[inline]
    fn at(at: &ShadingPoint, wo: Vec3) -> Frame {
        let n = if at.shading.dot(wo) > 0.0 {
            at.shading
        } else {
            at.geometric
        };
        let (t, b) = orthonormal_frame(n);
        Frame { t, b, n }
    }

    #[inline]
    fn to_local(self, v: Vec3) -> Vec3 {
        Vec3::new(v.dot(self.t), v.dot(self.b), v.dot(self.n))
    }

    #[inline]
    fn to_world(self, v: Vec3) -> Vec3 {
        self.t * v.x + self.b * v.y + self.n * v.z
    }
}

impl MetallicRoughness {
    /// `f` for local `lo`, `li` (both above the surface) and the tinted base colour.
    #[inline]
    fn eval_local(&self, base: Vec3, lo: Vec3, li: Vec3) -> Vec3 {
        if lo.z <= 0.0 || li.z <= 0.0 {
            return Vec3::ZERO;
        }
        let Some(h) = (lo + li).try_normalize() else {
            return Vec3::ZERO;
        };
        let distribution = self.distribution();
        let specular_brdf = distribution.visibility(lo, li) * distribution.d(h);
        let w = schlick_weight(lo.dot(h).abs());
        let f_d = self.dielectric_fresnel(w);
        let dielectric = f_d * specular_brdf + (1.0 - f_d.max_element()) * base * FRAC_1_PI;
        let metal = specular_brdf * (base + (Vec3::ONE - base) * w);
        dielectric.lerp(metal, self.metallic)
    }

    /// The sampling density of local `li` for local `lo` (both above the surface).
    #[inline]
    fn pdf_local(&self, base: Vec3, lo: Vec3, li: Vec3) -> f32 {
        if lo.z <= 0.0 || li.z <= 0.0 {
            return 0.0;
        }
        let p = self.specular_probability(base, lo.z);
        let diffuse = li.z * FRAC_1_PI;
        let specular = match (lo + li).try_normalize() {
            // D_wo(H) / (4 wo·H) = G1(wo) D(H) / (4 cos θo).
            Some(h) if p > 0.0 => {
                let distribution = self.distribution();
                distribution.g1(lo) * distribution.d(h) / (4.0 * lo.z)
            }
            _ => 0.0,
        };
        p * specular + (1.0 - p) * diffuse
    }
}

impl Bsdf for MetallicRoughness {
    /// Glossy reflection unless `metallic` and `specular` are both 0; diffuse reflection unless
    /// the surface is a pure metal, black, or its dielectric Fresnel is one everywhere. These
    /// are the factors' lobes: a point's [`TextureFactors`](super::shading_point::TextureFactors)
    /// can only lower metallic and roughness, so a textured surface may lack the glossy lobe
    /// at a point (metallic 0 there, specular 0) or gain a diffuse one (metallic below one).
    fn lobes(&self) -> Lobes {
        let glossy = if self.has_specular() {
            Lobes::GLOSSY_REFLECTION
        } else {
            Lobes::NONE
        };
        let diffuse = if self.has_diffuse(self.base_color) {
            Lobes::DIFFUSE_REFLECTION
        } else {
            Lobes::NONE
        };
        glossy | diffuse
    }

    fn eval(&self, at: &ShadingPoint, wo: Vec3, wi: Vec3) -> Vec3 {
        let frame = Frame::at(at, wo);
        let m = self.at_point(at);
        m.eval_local(m.base_color, frame.to_local(wo), frame.to_local(wi))
    }

    fn pdf(&self, at: &ShadingPoint, wo: Vec3, wi: Vec3) -> f32 {
        let frame = Frame::at(at, wo);
        let m = self.at_point(at);
        m.pdf_local(m.base_color, frame.to_local(wo), frame.to_local(wi))
    }

    /// The specular lobe when `u_lobe` is below its probability, else the diffuse one; `None`
    /// when `wo` is below the lobe normal or a specular reflection goes below the surface.
    fn sample(&self, at: &ShadingPoint, wo: Vec3, u: Vec2, u_lobe: f32) -> Option<BsdfSample> {
        let frame = Frame::at(at, wo);
        let m = self.at_point(at);
        let base = m.base_color;
        let lo = frame.to_local(wo);
        if lo.z <= 0.0 {
            return None;
        }
        let p = m.specular_probability(base, lo.z);
        let (li, lobe) = if u_lobe < p {
            let h = m.distribution().sample_visible_normal(lo, u);
            (2.0 * lo.dot(h) * h - lo, Lobes::GLOSSY_REFLECTION)
        } else {
            let li = cosine_hemisphere_in_frame(Vec3::X, Vec3::Y, Vec3::Z, u);
            (li, Lobes::DIFFUSE_REFLECTION)
        };
        let pdf = m.pdf_local(base, lo, li);
        if li.z <= 0.0 || pdf.is_nan() || pdf <= 0.0 {
            return None;
        }
        let weight = m.eval_local(base, lo, li) * li.z / pdf;
        weight.is_finite().then(|| BsdfSample {
            wi: frame.to_world(li),
            weight,
            pdf,
            lobe,
        })
    }

    /// The roughness, while the specular (glossy) lobe is present.
    fn glossy_roughness(&self) -> Option<f32> {
        self.has_specular().then_some(self.roughness)
    }

    /// An estimate, each channel in `[0, 1]`: the Fresnel-weighted lobes at `wo·H = cos θo`
    /// (see [`MetallicRoughness`]), which ignores the microfacets' shadowing and so overestimates
    /// the true albedo at high roughness; the photon tracer's roulette is unbiased for any
    /// value in `(0, 1]`, and this one is positive whenever a lobe is.
    fn albedo(&self, at: &ShadingPoint, wo: Vec3) -> Vec3 {
        let frame = Frame::at(at, wo);
        let cos_o = frame.to_local(wo).z;
        if cos_o <= 0.0 {
            return Vec3::ZERO;
        }
        let m = self.at_point(at);
        let (specular, diffuse) = m.lobe_albedos(m.base_color, cos_o);
        (specular + diffuse).min(Vec3::ONE)
    }

    /// The diffuse lobe's reflectance at normal incidence, `(1 − metallic) · (1 − max(f0)) ·
    /// base`: the Lambertian part the estimators read as `ρ_d/π · E` (its `1 − max F` falls
    /// towards grazing angles, which this ignores).
    fn diffuse_albedo(&self, at: &ShadingPoint) -> Vec3 {
        let m = self.at_point(at);
        (1.0 - m.metallic) * (1.0 - m.dielectric_f0().max_element()) * m.base_color
    }
}
