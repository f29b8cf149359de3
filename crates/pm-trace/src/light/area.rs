//! The area light: any set of triangles emitting constant radiance from their front side
//! (counter-clockwise winding) or from both sides, cosine-distributed.

use super::{EmittedRay, IncidentPdf, Light, LightSample};
use crate::ray::Ray;
use crate::rng::Rng;
use crate::sampling::{cosine_hemisphere_in_frame, orthonormal_frame, pick_cumulative, uniform_triangle};
use crate::sides::Sides;
use glam::{Vec2, Vec3};
use std::f32::consts::PI;

/// Triangles emitting `radiance` (W/(m²·sr) per channel) on their front side, or on both
/// sides after [`AreaLight::with_sides`]`(`[`Sides::Double`]`)`; power `π · radiance · area`
/// per emitting side. Photons start at uniform points (triangles chosen by area) with
/// cosine-distributed directions (on a side chosen with probability ½ when both emit).
#[derive(Clone, Debug, PartialEq)]
pub struct AreaLight {
    triangles: Vec<[Vec3; 3]>,
    /// Per triangle, an orthonormal frame `[t, b, n]` around its unit normal `n`.
    frames: Vec<[Vec3; 3]>,
    /// Cumulative areas, last = total.
    cumulative: Vec<f32>,
    radiance: Vec3,
    /// True when the back side emits too.
    two_sided: bool,
}

impl AreaLight {
    /// The most triangles of a light that offers multiple importance sampling
    /// ([`Light::supports_mis`]).
    pub const MIS_MAX_TRIANGLES: usize = 64;

    /// The parallelogram `corner + s·edge_u + t·edge_v`, `(s, t) ∈ [0,1]²`, front side along
    /// `edge_u × edge_v`.
    pub fn quad(corner: Vec3, edge_u: Vec3, edge_v: Vec3, radiance: Vec3) -> Self {
        let (a, b, c, d) = (corner, corner + edge_u, corner + edge_u + edge_v, corner + edge_v);
        Self::from_triangles(&[[a, b, c], [a, c, d]], radiance)
    }

    /// Emissive triangles (degenerate ones are skipped).
    pub fn from_triangles(triangles: &[[Vec3; 3]], radiance: Vec3) -> Self {
        let mut light = AreaLight {
            triangles: Vec::new(),
            frames: Vec::new(),
            cumulative: Vec::new(),
            radiance,
            two_sided: false,
        };
        let mut total = 0.0;
        for t in triangles {
            let n = (t[1] - t[0]).cross(t[2] - t[0]);
            let area = 0.5 * n.length();
            if !(area > 0.0 && area.is_finite()) {
                continue;
            }
            total += area;
            light.triangles.push(*t);
            let n = n.normalize();
            let (t, b) = orthonormal_frame(n);
            light.frames.push([t, b, n]);
            light.cumulative.push(total);
        }
        light
    }

    /// The same light emitting from both sides when `sides` is [`Sides::Double`], from the
    /// front otherwise (the camera culling of [`Sides::Single`] is the scene's business).
    pub fn with_sides(mut self, sides: Sides) -> Self {
        self.two_sided = sides.emits_back();
        self
    }

    /// True when both sides emit.
    pub fn is_two_sided(&self) -> bool {
        self.two_sided
    }

    /// Total emitting area (m²), one side.
    pub fn area(&self) -> f32 {
        self.cumulative.last().copied().unwrap_or(0.0)
    }

    /// Emitted radiance.
    pub fn radiance(&self) -> Vec3 {
        self.radiance
    }

    /// The emitting triangles.
    pub fn triangles(&self) -> &[[Vec3; 3]] {
        &self.triangles
    }

    /// A uniform point on the light and the frame `[t, b, n]` of its triangle.
    #[inline]
    fn sample_point(&self, rng: &mut Rng) -> Option<(Vec3, [Vec3; 3])> {
        let total = self.area();
        if total <= 0.0 {
            return None;
        }
        let i = pick_cumulative(&self.cumulative, rng.next_f32());
        let t = &self.triangles[i];
        Some((
            uniform_triangle(t[0], t[1], t[2], Vec2::new(rng.next_f32(), rng.next_f32())),
            self.frames[i],
        ))
    }
}

impl Light for AreaLight {
    fn validate(&self) -> Result<(), String> {
        let area = self.area();
        if !(area > 0.0 && area.is_finite()) {
            return Err(format!(
                "emitting area {area} m² (no finite, non-degenerate triangle)"
            ));
        }
        Ok(())
    }

    fn power(&self) -> Vec3 {
        let sides = if self.two_sided { 2.0 } else { 1.0 };
        self.radiance * (PI * sides * self.area())
    }

    fn emit(&self, rng: &mut Rng) -> EmittedRay {
        match self.sample_point(rng) {
            Some((p, [t, b, n])) => {
                // One extra draw, only for two-sided lights: one-sided photons are unchanged.
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
                    weight: Vec3::ONE,
                }
            }
            // Zero area means zero power; a tracer never picks such a light.
            None => EmittedRay {
                ray: Ray {
                    origin: Vec3::ZERO,
                    direction: Vec3::Y,
                },
                weight: Vec3::ZERO,
            },
        }
    }

    /// True up to [`AreaLight::MIS_MAX_TRIANGLES`] triangles: [`Light::incident_pdf`] tests
    /// every triangle, and a renderer asks at every diffuse bounce, so a large emitting mesh
    /// keeps shadow rays alone.
    fn supports_mis(&self) -> bool {
        self.triangles.len() <= Self::MIS_MAX_TRIANGLES
    }

    /// The nearest of the light's triangles the ray meets on an emitting side, and the density
    /// of [`Light::sample_incident`] there: `d² / (A cos θ_light)` (points uniform over the
    /// total area `A`).
    fn incident_pdf(&self, point: Vec3, direction: Vec3) -> Option<IncidentPdf> {
        let area = self.area();
        if area <= 0.0 {
            return None;
        }
        let mut nearest: Option<(f32, f32)> = None;
        for (t, frame) in self.triangles.iter().zip(&self.frames) {
            let Some(d) = ray_triangle(point, direction, t) else {
                continue;
            };
            let cos = direction.dot(frame[2]);
            let cos_light = if self.two_sided { cos.abs() } else { -cos };
            if cos_light > 0.0 && nearest.is_none_or(|(best, _)| d < best) {
                nearest = Some((d, cos_light));
            }
        }
        let (distance, cos_light) = nearest?;
        Some(IncidentPdf {
            distance,
            pdf: distance * distance / (area * cos_light),
        })
    }

    fn sample_incident(&self, point: Vec3, _normal: Vec3, rng: &mut Rng) -> Option<LightSample> {
        let (y, [_, _, n]) = self.sample_point(rng)?;
        let to = y - point;
        let d2 = to.length_squared();
        let distance = d2.sqrt();
        let direction = (to / distance).try_normalize()?;
        let cos_light = if self.two_sided {
            direction.dot(n).abs()
        } else {
            -direction.dot(n)
        };
        if cos_light <= 0.0 {
            return None;
        }
        // pdf_area = 1/A → pdf_solid_angle = d² / (A cos θ_light).
        Some(LightSample {
            direction,
            distance,
            radiance_over_pdf: self.radiance * (self.area() * cos_light / d2),
        })
    }
}

/// Distance along the ray `origin + t · direction` (t > 0) to triangle `t`, by Möller and
/// Trumbore's test; `None` when it misses.
fn ray_triangle(origin: Vec3, direction: Vec3, t: &[Vec3; 3]) -> Option<f32> {
    let (e1, e2) = (t[1] - t[0], t[2] - t[0]);
    let p = direction.cross(e2);
    let det = e1.dot(p);
    if det.abs() < 1e-12 {
        return None;
    }
    let inv = 1.0 / det;
    let s = origin - t[0];
    let u = s.dot(p) * inv;
    if !(0.0..=1.0).contains(&u) {
        return None;
    }
    let q = s.cross(e1);
    let v = direction.dot(q) * inv;
    if v < 0.0 || u + v > 1.0 {
        return None;
    }
    let d = e2.dot(q) * inv;
    (d > 0.0).then_some(d)
}
