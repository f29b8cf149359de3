//! The textured area light: triangles whose emitted radiance is a constant factor times an
//! emission texture, with power and light selection from each triangle's mean emission.

use super::{EmittedRay, Light, LightSample};
use crate::emission::{EmissionTexture, MAX_SUBDIVISIONS, MEAN_LOOKUP_BUDGET, subdivisions, triangle_mean};
use crate::ray::Ray;
use crate::rng::Rng;
use crate::sampler::Sampler;
use crate::sampling::{cosine_hemisphere_in_frame, orthonormal_frame, pick_cumulative};
use crate::sides::Sides;
use crate::texture::Texture;
use glam::{DVec3, Vec2, Vec3};
use std::sync::Arc;

/// Triangles emitting `factor × texture(uv)` W/(m²·sr), cosine-distributed, from the front
/// or from both sides.
///
/// **Power and selection.** Each triangle's mean emission `L̄ᵢ` is the texture's mean over it
/// by a fixed, deterministic quadrature ([`triangle_mean`] on about two sub-triangles per
/// texel, at most [`MAX_SUBDIVISIONS`]² points a triangle and [`MEAN_LOOKUP_BUDGET`] points a
/// light). The light's power is `π · sides · Σ Aᵢ L̄ᵢ`; triangles are chosen with
/// probability `pᵢ ∝ Aᵢ · sum(L̄ᵢ)` (the sum of the three channels) and points uniformly on
/// them.
///
/// **Estimates read the texture.** Photons and shadow-ray samples carry the emission at the
/// point actually sampled, divided by that point's density: a photon's `weight` is
/// `L(y) / sum(L̄ᵢ) · S / Σ Aⱼ L̄ⱼ` per channel (with `S = Σ Aⱼ sum(L̄ⱼ)`), whose expectation
/// is the *exact* texture integral over the quadrature's estimate of it, 1 up to the
/// quadrature error; a shadow sample's `radiance_over_pdf` is `L(y) · cos θ_y / d² ·
/// S / sum(L̄ᵢ)`. Both estimators are therefore unbiased for the texture as the camera sees it
/// ([`crate::Scene::emission`] reads the same texture at a hit), with one approximation: a
/// triangle whose quadrature mean is zero although the texture is not (a bright feature
/// smaller than the quadrature's spacing, under half a texel) is never sampled, and its light
/// is lost. [`Light::power`] is the quadrature's value, which only sets how photons are
/// shared between lights; the photons' power follows the texture itself.
#[derive(Clone, Debug, PartialEq)]
pub struct TexturedAreaLight {
    triangles: Vec<[Vec3; 3]>,
    uvs: Vec<[Vec2; 3]>,
    /// Per triangle, an orthonormal frame `[t, b, n]` around its unit normal `n`.
    frames: Vec<[Vec3; 3]>,
    /// Per triangle, the sum over channels of its mean emission `L̄ᵢ`.
    mean_sums: Vec<f32>,
    /// Cumulative `Aᵢ · sum(L̄ᵢ)`, last = `S`.
    cumulative: Vec<f32>,
    factor: Vec3,
    /// The texture and sampler (its per-vertex `uvs` unused: `uvs` above hold the corners').
    texture: EmissionTexture,
    two_sided: bool,
    /// `π · sides · Σ Aᵢ L̄ᵢ`.
    power: Vec3,
    /// Per channel, `S / Σ Aᵢ L̄ᵢ` (zero for a dark channel).
    weight_scale: Vec3,
    /// Total area of the triangles kept (m², one side).
    area: f32,
    /// Why the input was refused, if it was.
    invalid: Option<String>,
}

impl TexturedAreaLight {
    /// Triangles `triangles` with corner texture coordinates `uvs` (one triple per triangle)
    /// emitting `factor × texture` read with `sampler`. Degenerate triangles and triangles of zero mean emission are skipped; lists of
    /// different lengths or a non-finite factor make [`Light::validate`] fail.
    pub fn new(
        triangles: &[[Vec3; 3]],
        uvs: &[[Vec2; 3]],
        factor: Vec3,
        texture: Arc<Texture>,
        sampler: Sampler,
        sides: Sides,
    ) -> Self {
        let mut light = TexturedAreaLight {
            triangles: Vec::new(),
            uvs: Vec::new(),
            frames: Vec::new(),
            mean_sums: Vec::new(),
            cumulative: Vec::new(),
            factor,
            texture: EmissionTexture {
                uvs: Vec::new(),
                texture,
                sampler,
            },
            two_sided: sides.emits_back(),
            power: Vec3::ZERO,
            weight_scale: Vec3::ZERO,
            area: 0.0,
            invalid: None,
        };
        if triangles.len() != uvs.len() {
            light.invalid = Some(format!(
                "{} triangles but {} texture-coordinate triples",
                triangles.len(),
                uvs.len()
            ));
            return light;
        }
        if !(factor.is_finite() && factor.min_element() >= 0.0) {
            light.invalid = Some(format!("emission factor {factor} is not finite and non-negative"));
            return light;
        }
        let per_triangle = MEAN_LOOKUP_BUDGET / (triangles.len() as u64).max(1);
        let limit = ((per_triangle as f64).sqrt() as u32).clamp(1, MAX_SUBDIVISIONS);
        let (mut weighted, mut scalar, mut area) = (DVec3::ZERO, 0.0f64, 0.0f64);
        for (t, &uv) in triangles.iter().zip(uvs) {
            let n = (t[1] - t[0]).cross(t[2] - t[0]);
            let a = 0.5 * n.length();
            if !(a > 0.0 && a.is_finite()) {
                continue;
            }
            let m = subdivisions(&light.texture.texture, uv, limit);
            let mean = factor * triangle_mean(&light.texture, uv, m);
            let sum = mean.element_sum();
            if !(sum > 0.0 && sum.is_finite()) {
                continue;
            }
            weighted += mean.as_dvec3() * a as f64;
            scalar += sum as f64 * a as f64;
            area += a as f64;
            light.triangles.push(*t);
            light.uvs.push(uv);
            let n = n.normalize();
            let (tb, bb) = orthonormal_frame(n);
            light.frames.push([tb, bb, n]);
            light.mean_sums.push(sum);
            light.cumulative.push(scalar as f32);
        }
        let sides = if light.two_sided { 2.0 } else { 1.0 };
        light.power = (weighted * (std::f64::consts::PI * sides)).as_vec3();
        light.weight_scale = Vec3::from_array(
            weighted
                .to_array()
                .map(|w| if w > 0.0 { (scalar / w) as f32 } else { 0.0 }),
        );
        light.area = area as f32;
        light
    }

    /// Total area of the emitting triangles kept (m², one side).
    pub fn area(&self) -> f32 {
        self.area
    }

    /// Number of triangles kept (non-degenerate, with a positive mean emission).
    pub fn triangle_count(&self) -> usize {
        self.triangles.len()
    }

    /// True when both sides emit.
    pub fn is_two_sided(&self) -> bool {
        self.two_sided
    }

    /// The emitted radiance at barycentric weights `w` of kept triangle `i`.
    #[inline]
    fn radiance_at(&self, i: usize, w: Vec3) -> Vec3 {
        self.factor * self.texture.at(self.uvs[i], w)
    }

    /// A kept triangle (by `Aᵢ · sum(L̄ᵢ)`), a uniform point on it and its barycentric weights.
    #[inline]
    fn sample_point(&self, rng: &mut Rng) -> Option<(usize, Vec3, Vec3)> {
        if self.cumulative.is_empty() {
            return None;
        }
        let i = pick_cumulative(&self.cumulative, rng.next_f32());
        let u = Vec2::new(rng.next_f32(), rng.next_f32());
        let s = u.x.sqrt();
        let w = Vec3::new(1.0 - s, u.y * s, s * (1.0 - u.y));
        let [a, b, c] = self.triangles[i];
        Some((i, a * w.x + b * w.y + c * w.z, w))
    }
}

impl Light for TexturedAreaLight {
    fn validate(&self) -> Result<(), String> {
        if let Some(reason) = &self.invalid {
            return Err(reason.clone());
        }
        if self.triangles.is_empty() {
            return Err("no triangle has a positive area and a positive mean emission".into());
        }
        Ok(())
    }

    fn power(&self) -> Vec3 {
        self.power
    }

    fn emit(&self, rng: &mut Rng) -> EmittedRay {
        let Some((i, p, w)) = self.sample_point(rng) else {
            // No emitting triangle means zero power; a tracer never picks such a light.
            return EmittedRay {
                ray: Ray {
                    origin: Vec3::ZERO,
                    direction: Vec3::Y,
                },
                weight: Vec3::ZERO,
            };
        };
        let [t, b, n] = self.frames[i];
        let n = if self.two_sided && rng.next_f32() < 0.5 {
            -n
        } else {
            n
        };
        let d = cosine_hemisphere_in_frame(t, b, n, Vec2::new(rng.next_f32(), rng.next_f32()));
        EmittedRay {
            ray: Ray {
                origin: p,
                direction: d,
            },
            weight: self.radiance_at(i, w) / self.mean_sums[i] * self.weight_scale,
        }
    }

    fn sample_incident(&self, point: Vec3, _normal: Vec3, rng: &mut Rng) -> Option<LightSample> {
        let (i, y, w) = self.sample_point(rng)?;
        let to = y - point;
        let d2 = to.length_squared();
        let distance = d2.sqrt();
        let direction = (to / distance).try_normalize()?;
        let n = self.frames[i][2];
        let cos_light = if self.two_sided {
            direction.dot(n).abs()
        } else {
            -direction.dot(n)
        };
        if cos_light <= 0.0 {
            return None;
        }
        // pdf_area = sum(L̄ᵢ) / S → pdf_solid_angle = pdf_area · d² / cos θ_y.
        let total = self.cumulative.last().copied().unwrap_or(0.0);
        Some(LightSample {
            direction,
            distance,
            radiance_over_pdf: self.radiance_at(i, w) * (total * cos_light / (self.mean_sums[i] * d2)),
        })
    }
}
