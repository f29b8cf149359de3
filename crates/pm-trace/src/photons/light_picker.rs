//! Which light emits a photon: lights chosen in proportion to their power, and the power each
//! photon of a light starts with.

use crate::error::TraceError;
use crate::rng::Rng;
use crate::sampling::pick_cumulative;
use crate::scene::Scene;
use glam::Vec3;

/// Light selection in proportion to power (sum over channels), and the power each photon of
/// a light starts with.
pub(super) struct LightPicker {
    cumulative: Vec<f32>,
    /// Per light, `power / (N · p)` for `N` photons and selection probability `p`.
    photon_power: Vec<Vec3>,
}

impl LightPicker {
    pub(super) fn new(scene: &Scene, photons: u32) -> Result<Self, TraceError> {
        if scene.lights().is_empty() {
            return Err(TraceError::NoLights);
        }
        let mut cumulative = Vec::with_capacity(scene.lights().len());
        let mut total = 0.0f32;
        for (i, light) in scene.lights().iter().enumerate() {
            let p = light.power();
            if !p.is_finite() || p.min_element() < 0.0 {
                return Err(TraceError::InvalidPower {
                    light: i,
                    power: p.to_array(),
                });
            }
            total += p.element_sum();
            cumulative.push(total);
        }
        if total.partial_cmp(&0.0) != Some(std::cmp::Ordering::Greater) {
            return Err(TraceError::InvalidPower {
                light: scene.lights().len(),
                power: [0.0; 3],
            });
        }
        let photon_power = scene
            .lights()
            .iter()
            .enumerate()
            .map(|(i, light)| {
                let lo = if i == 0 { 0.0 } else { cumulative[i - 1] };
                let p_light = (cumulative[i] - lo) / total;
                light.power() / (photons as f32 * p_light)
            })
            .collect();
        Ok(LightPicker {
            cumulative,
            photon_power,
        })
    }

    /// Index of a light drawn in proportion to power, and its photons' starting power.
    #[inline]
    pub(super) fn pick(&self, rng: &mut Rng) -> (usize, Vec3) {
        let i = if self.cumulative.len() == 1 {
            // Keep the stream's use identical whatever the light count.
            rng.next_f32();
            0
        } else {
            pick_cumulative(&self.cumulative, rng.next_f32())
        };
        (i, self.photon_power[i])
    }
}
