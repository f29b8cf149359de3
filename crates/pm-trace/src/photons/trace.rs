//! Deterministic parallel photon tracing: every path draws from its own random stream
//! `(seed, pass, path index)`, chunks of paths run on rayon and are merged in path order, so the
//! stored photons are bit-identical for any thread count.

use super::path::{NearLight, trace_paths};
use crate::sampling::pick_cumulative;
use crate::{MapAssignment, Rng, Scene, TraceError};
use glam::Vec3;
use pm_kdtree::Photon;
use rayon::prelude::*;
use std::time::Instant;

/// Paths per parallel work item.
const CHUNK: u32 = 512;

/// How close to its light the surface of a photon's first hit must pass (1 mm: the distance
/// from where the photon left the light to the plane of the surface at its hit) to count in
/// [`TraceStats::near_light_fraction`].
pub const NEAR_LIGHT_DISTANCE: f32 = 1e-3;

/// The most photon paths one call to [`trace_photons`] traces: 2²⁵ (33,554,432). More are
/// refused with [`TraceError::TooManyPhotons`] before anything is allocated.
pub const MAX_PHOTON_PATHS: u32 = 1 << 25;

/// The most photons one call to [`trace_photons`] stores over all maps: 2²⁶ (67,108,864, 40
/// bytes each while tracing, 2.5 GiB). Paths store one photon per diffuse bounce (up to
/// `max_bounces`), so the count is checked as the waves are merged and the run stops with
/// [`TraceError::TooManyPhotonsStored`] once past it.
pub const MAX_STORED_PHOTONS: u64 = 1 << 26;

/// What to trace.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct TraceOptions {
    /// Number of emitted photon paths (each starts with `Φ_total / photons` on average).
    pub photons: u32,
    /// Seed of the random streams (path `i` of pass `p` draws from
    /// [`Rng::for_pass`]`(seed, p, i)`).
    pub seed: u64,
    /// Pass of a progressive render: each pass traces a fresh, independent set of paths.
    /// Pass 0 (the default) is a single render's trace: `Rng::for_pass(seed, 0, i)` is
    /// `Rng::new(seed, i)`.
    pub pass: u64,
    /// Longest path (surface interactions); Russian roulette ends paths long before in
    /// practice. The cut-off loses the power of longer paths.
    pub max_bounces: u32,
}

impl Default for TraceOptions {
    /// 100,000 photons (Ball & Stejko's count), seed 0, pass 0, at most 64 bounces.
    fn default() -> Self {
        TraceOptions {
            photons: 100_000,
            seed: 0,
            pass: 0,
            max_bounces: 64,
        }
    }
}

/// Statistics of one tracing run.
#[derive(Clone, Debug, PartialEq)]
pub struct TraceStats {
    /// Paths emitted.
    pub emitted: u64,
    /// Photons stored per map, indexed by `PhotonKind as usize` (direct, indirect, caustic).
    pub stored: Vec<[u64; 3]>,
    /// The share of the emitted power (summed over channels) whose first hit lay on a surface
    /// within [`NEAR_LIGHT_DISTANCE`] (1 mm) of its light — the plane of the surface at the
    /// hit passes that close to where the photon left the light: 0 for lights that face into
    /// the scene, near 1 for a light facing into the wall or ceiling it sits on (an area light
    /// emits towards `edge_u × edge_v`: swapping its edges turns it round). That power still
    /// lights the scene, but from the wrong place.
    pub near_light_fraction: f64,
    /// Wall-clock seconds spent tracing.
    pub seconds: f64,
}

impl TraceStats {
    /// Photons stored over all maps and kinds.
    pub fn total_stored(&self) -> u64 {
        self.stored.iter().flatten().sum()
    }
}

/// The photons of each map, in path order, with statistics.
#[derive(Clone, Debug, PartialEq)]
pub struct TracedPhotons {
    photons: Vec<Vec<Photon>>,
    stats: TraceStats,
}

impl TracedPhotons {
    /// Photons per map (`photons_per_map()[map]`).
    pub fn photons_per_map(&self) -> &[Vec<Photon>] {
        &self.photons
    }

    /// The photons of one map. Panics when `map` is not below the map count (the length of
    /// [`TracedPhotons::photons_per_map`]), like slice indexing.
    pub fn photons(&self, map: u32) -> &[Photon] {
        &self.photons[map as usize]
    }

    /// Statistics.
    pub fn stats(&self) -> &TraceStats {
        &self.stats
    }

    /// Photons per map and statistics, by value.
    pub fn into_parts(self) -> (Vec<Vec<Photon>>, TraceStats) {
        (self.photons, self.stats)
    }
}

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

/// Traces `options.photons` photon paths from the scene's lights and stores a photon at every
/// diffuse hit, in the map `assignment` gives the part hit.
///
/// Errors: zero photons, no lights, a light with negative or non-finite power, all lights
/// at zero power, or an assignment made for another scene.
pub fn trace_photons(
    scene: &Scene,
    assignment: &MapAssignment,
    options: &TraceOptions,
) -> Result<TracedPhotons, TraceError> {
    let start = Instant::now();
    if options.photons == 0 {
        return Err(TraceError::ZeroPhotons);
    }
    if options.photons > MAX_PHOTON_PATHS {
        return Err(TraceError::TooManyPhotons {
            photons: options.photons,
        });
    }
    if assignment.part_count() != scene.part_count() {
        return Err(TraceError::AssignmentMismatch {
            assigned: assignment.part_count(),
            parts: scene.part_count(),
        });
    }
    let picker = LightPicker::new(scene, options.photons)?;
    let maps = assignment.map_count() as usize;
    let mut merged = Merged {
        photons: vec![Vec::new(); maps],
        stored: vec![[0u64; 3]; maps],
        total: 0,
    };
    // Waves of chunks traced in parallel into buffers that are reused (cache-warm, no fresh
    // pages); each wave is merged in path order while the next one traces.
    let chunks = options.photons.div_ceil(CHUNK);
    // At most one wave of buffers beyond what the run needs (and no u32 overflow below).
    let wave = (16 * rayon::current_num_threads()).min(chunks as usize).max(1) as u32;
    let paired = scene.prefers_ray_pairs();
    let trace_wave = |first: u32, buffers: &mut [Vec<(u32, Photon)>], near: &mut [NearLight]| {
        buffers
            .par_iter_mut()
            .zip(near.par_iter_mut())
            .enumerate()
            .for_each(|(i, (out, near))| {
                out.clear();
                *near = NearLight::default();
                let chunk = first + i as u32;
                if chunk >= chunks {
                    return;
                }
                let begin = chunk * CHUNK;
                let end = begin.saturating_add(CHUNK).min(options.photons);
                trace_paths(
                    scene,
                    assignment,
                    options,
                    &picker,
                    (begin, end),
                    paired,
                    out,
                    near,
                );
            });
    };
    let mut traced: Vec<Vec<(u32, Photon)>> = vec![Vec::new(); wave as usize];
    let mut tracing: Vec<Vec<(u32, Photon)>> = vec![Vec::new(); wave as usize];
    let mut traced_near = vec![NearLight::default(); wave as usize];
    let mut tracing_near = vec![NearLight::default(); wave as usize];
    // Summed in chunk order, so the figure does not depend on the thread count.
    let mut near_light = NearLight::default();
    let mut add_near = |near: &[NearLight]| {
        for n in near {
            near_light.emitted += n.emitted;
            near_light.near += n.near;
        }
    };
    trace_wave(0, &mut traced, &mut traced_near);
    let first_wave_paths = (u64::from(wave) * u64::from(CHUNK)).min(u64::from(options.photons));
    merged.reserve_for(&traced, options.photons as f64 / first_wave_paths as f64);
    let mut first = wave;
    while first < chunks {
        let (appended, ()) = rayon::join(
            || merged.append(&traced),
            || trace_wave(first, &mut tracing, &mut tracing_near),
        );
        appended?;
        add_near(&traced_near);
        std::mem::swap(&mut traced, &mut tracing);
        std::mem::swap(&mut traced_near, &mut tracing_near);
        first += wave;
    }
    merged.append(&traced)?;
    add_near(&traced_near);
    let Merged { photons, stored, .. } = merged;
    let near_light_fraction = if near_light.emitted > 0.0 {
        near_light.near / near_light.emitted
    } else {
        0.0
    };
    let stats = TraceStats {
        emitted: options.photons as u64,
        stored,
        near_light_fraction,
        seconds: start.elapsed().as_secs_f64(),
    };
    Ok(TracedPhotons { photons, stats })
}

/// The photons of each map in path order, and their counts by kind.
struct Merged {
    photons: Vec<Vec<Photon>>,
    stored: Vec<[u64; 3]>,
    /// Photons held over all maps (kept, not recounted per wave: maps may be many).
    total: u64,
}

impl Merged {
    /// Appends one wave's buffers (in path order); errors past [`MAX_STORED_PHOTONS`].
    fn append(&mut self, buffers: &[Vec<(u32, Photon)>]) -> Result<(), TraceError> {
        let adding: u64 = buffers.iter().map(|b| b.len() as u64).sum();
        if self.total + adding > MAX_STORED_PHOTONS {
            return Err(TraceError::TooManyPhotonsStored {
                limit: MAX_STORED_PHOTONS,
            });
        }
        for &(m, p) in buffers.iter().flatten() {
            self.stored[m as usize][p.kind as usize] += 1;
            self.photons[m as usize].push(p);
        }
        self.total += adding;
        Ok(())
    }

    /// Reserves room for the whole run from the first wave's photons per map, scaled by
    /// `scale` (paths in the run over paths in the wave) with 5 % slack, never past
    /// [`MAX_STORED_PHOTONS`] in all (the merge refuses more).
    fn reserve_for(&mut self, buffers: &[Vec<(u32, Photon)>], scale: f64) {
        let mut counts = vec![0usize; self.photons.len()];
        for &(m, _) in buffers.iter().flatten() {
            counts[m as usize] += 1;
        }
        let total: usize = counts.iter().sum();
        let total_wanted = total as f64 * scale * 1.05;
        let shrink = (MAX_STORED_PHOTONS as f64 / total_wanted.max(1.0)).min(1.0);
        for (photons, count) in self.photons.iter_mut().zip(counts) {
            photons.reserve((count as f64 * scale * 1.05 * shrink).ceil() as usize);
        }
    }
}
