//! Deterministic parallel photon tracing: every path draws from its own random stream
//! `(seed, pass, path index)`, chunks of paths run on rayon and are merged in path order, so the
//! stored photons are bit-identical for any thread count.

use super::scatter::{glass_direction, mirror_direction};
use crate::sampling::{cosine_hemisphere, pick_cumulative};
use crate::{Hit, MapAssignment, Material, Ray, RayKind, Rng, Scene, TraceError};
use glam::{Vec2, Vec3};
use pm_kdtree::{Photon, PhotonKind};
use rayon::prelude::*;
use std::time::Instant;

/// Paths per parallel work item.
const CHUNK: u32 = 512;

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
struct LightPicker {
    cumulative: Vec<f32>,
    /// Per light, `power / (N · p)` for `N` photons and selection probability `p`.
    photon_power: Vec<Vec3>,
}

impl LightPicker {
    fn new(scene: &Scene, photons: u32) -> Result<Self, TraceError> {
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
    fn pick(&self, rng: &mut Rng) -> (usize, Vec3) {
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
    let trace_wave = |first: u32, buffers: &mut [Vec<(u32, Photon)>]| {
        buffers.par_iter_mut().enumerate().for_each(|(i, out)| {
            out.clear();
            let chunk = first + i as u32;
            if chunk >= chunks {
                return;
            }
            let begin = chunk * CHUNK;
            let end = begin.saturating_add(CHUNK).min(options.photons);
            trace_paths(scene, assignment, options, &picker, (begin, end), paired, out);
        });
    };
    let mut traced: Vec<Vec<(u32, Photon)>> = vec![Vec::new(); wave as usize];
    let mut tracing: Vec<Vec<(u32, Photon)>> = vec![Vec::new(); wave as usize];
    trace_wave(0, &mut traced);
    let first_wave_paths = (u64::from(wave) * u64::from(CHUNK)).min(u64::from(options.photons));
    merged.reserve_for(&traced, options.photons as f64 / first_wave_paths as f64);
    let mut first = wave;
    while first < chunks {
        let (appended, ()) = rayon::join(|| merged.append(&traced), || trace_wave(first, &mut tracing));
        appended?;
        std::mem::swap(&mut traced, &mut tracing);
        first += wave;
    }
    merged.append(&traced)?;
    let Merged { photons, stored, .. } = merged;
    let stats = TraceStats {
        emitted: options.photons as u64,
        stored,
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

/// Traces paths `begin..end` into `out`, in path order.
///
/// `paired` (chosen by [`Scene::prefers_ray_pairs`]: scenes large enough for memory to
/// dominate) keeps two paths in flight and casts their rays together with
/// [`Scene::intersect_pair`]; when one ends, the next path takes its place at once. Photons of
/// a path that ends before an older one are held back until the older one has ended, so the
/// order (and every photon) is what one path at a time gives.
fn trace_paths(
    scene: &Scene,
    assignment: &MapAssignment,
    options: &TraceOptions,
    picker: &LightPicker,
    (begin, end): (u32, u32),
    paired: bool,
    out: &mut Vec<(u32, Photon)>,
) {
    if !paired {
        for path in begin..end {
            let mut p = PhotonPath::start(scene, options, picker, path);
            while p.is_live() {
                let hit = scene.intersect(&p.ray, f32::INFINITY, RayKind::Other);
                p.interact(scene, assignment, hit, out);
            }
        }
        return;
    }
    /// A path in flight and the photons it has stored so far.
    struct Slot {
        path: PhotonPath,
        index: u32,
        photons: Vec<(u32, Photon)>,
    }
    let mut next = begin;
    let mut start = |photons: Vec<(u32, Photon)>| {
        (next < end).then(|| {
            next += 1;
            Slot {
                path: PhotonPath::start(scene, options, picker, next - 1),
                index: next - 1,
                photons,
            }
        })
    };
    let mut slots = [start(Vec::new()), start(Vec::new())];
    // Photons of ended paths newer than the oldest path in flight, in path order.
    let mut waiting = Vec::new();
    loop {
        match &mut slots {
            [Some(a), Some(b)] => {
                let [hit_a, hit_b] = scene.intersect_pair([&a.path.ray, &b.path.ray], f32::INFINITY);
                a.path.interact(scene, assignment, hit_a, &mut a.photons);
                b.path.interact(scene, assignment, hit_b, &mut b.photons);
            }
            [Some(s), None] | [None, Some(s)] => {
                let hit = scene.intersect(&s.path.ray, f32::INFINITY, RayKind::Other);
                s.path.interact(scene, assignment, hit, &mut s.photons);
            }
            [None, None] => break,
        }
        for k in 0..2 {
            if slots[k].as_ref().is_none_or(|s| s.path.is_live()) {
                continue;
            }
            let ended = slots[k].take().expect("checked above");
            let mut photons = ended.photons;
            if slots[1 - k].as_ref().is_some_and(|o| o.index < ended.index) {
                waiting.append(&mut photons);
            } else {
                out.append(&mut photons);
                out.append(&mut waiting);
            }
            slots[k] = start(photons);
        }
    }
}

/// One photon path in flight: emitted from a light, then carried from surface to surface
/// until it is absorbed, leaves the scene or reaches `max_bounces` interactions.
struct PhotonPath {
    rng: Rng,
    power: Vec3,
    /// The ray to cast next.
    ray: Ray,
    diffuse_bounces: u32,
    specular: bool,
    /// Interactions left before the cut-off; zero once the path has ended.
    bounces_left: u32,
}

impl PhotonPath {
    /// Path `path` of the run, emitted from a light picked in proportion to its power.
    #[inline]
    fn start(scene: &Scene, options: &TraceOptions, picker: &LightPicker, path: u32) -> Self {
        let mut rng = Rng::for_pass(options.seed, options.pass, path as u64);
        let (li, photon_power) = picker.pick(&mut rng);
        let emitted = scene.lights()[li].emit(&mut rng);
        PhotonPath {
            rng,
            power: photon_power * emitted.weight,
            // Step off the emitter's own surface (area lights start on their geometry).
            ray: Ray {
                origin: emitted.ray.at(scene.epsilon()),
                direction: emitted.ray.direction,
            },
            diffuse_bounces: 0,
            specular: false,
            bounces_left: options.max_bounces,
        }
    }

    #[inline]
    fn is_live(&self) -> bool {
        self.bounces_left > 0
    }

    /// What the path does at `hit`, the closest hit of its ray (`None`: it left the scene):
    /// a photon stored in `out` at a diffuse hit, then absorption or the next ray.
    #[inline]
    fn interact(
        &mut self,
        scene: &Scene,
        assignment: &MapAssignment,
        hit: Option<Hit>,
        out: &mut Vec<(u32, Photon)>,
    ) {
        self.bounces_left -= 1;
        let Some(hit) = hit else {
            self.bounces_left = 0;
            return;
        };
        let direction = match *scene.material(&hit) {
            Material::Lambertian { .. } => {
                let albedo = scene.albedo_at(&hit);
                let kind = match (self.diffuse_bounces, self.specular) {
                    (0, false) => PhotonKind::Direct,
                    (0, true) => PhotonKind::Caustic,
                    _ => PhotonKind::Indirect,
                };
                out.push((
                    assignment.map_of(hit.part),
                    Photon {
                        position: hit.position,
                        power: self.power,
                        direction: self.ray.direction,
                        kind,
                    },
                ));
                // Russian roulette on albedo: survive with q, scale by albedo / q (unbiased).
                let q = albedo.max_element().min(1.0);
                if self.rng.next_f32() >= q {
                    self.bounces_left = 0;
                    return;
                }
                self.power *= albedo / q;
                self.diffuse_bounces += 1;
                cosine_hemisphere(hit.normal, Vec2::new(self.rng.next_f32(), self.rng.next_f32()))
            }
            Material::Mirror { .. } => {
                self.power *= scene.albedo_at(&hit);
                if self.power.max_element() <= 0.0 {
                    self.bounces_left = 0;
                    return;
                }
                self.specular = true;
                mirror_direction(self.ray.direction, hit.normal, scene.shading_normal_at(&hit))
            }
            Material::Glass { ior } => {
                self.specular = true;
                let eta = if hit.front_face { 1.0 / ior } else { ior };
                glass_direction(
                    self.ray.direction,
                    hit.normal,
                    scene.shading_normal_at(&hit),
                    eta,
                    &mut self.rng,
                )
            }
        };
        self.ray = scene.spawn_ray(&hit, direction);
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::scenes::scale::split_rooms;

    /// Paths traced two at a time store exactly the photons, in exactly the order, of paths
    /// traced one at a time (every path draws from its own stream, and the second path's
    /// photons are held back until the first has ended), on a scene large enough to use pairs
    /// and for an odd number of paths.
    #[test]
    fn paths_traced_in_pairs_store_what_paths_traced_one_at_a_time_store() {
        let scene = split_rooms(60).unwrap();
        assert!(scene.prefers_ray_pairs());
        let assignment = crate::Partitioner::partition(&crate::CreaseAngle::default(), &scene);
        let options = TraceOptions {
            photons: 2_001,
            seed: 7,
            ..TraceOptions::default()
        };
        let picker = LightPicker::new(&scene, options.photons).unwrap();
        let trace = |paired: bool| {
            let mut out = Vec::new();
            trace_paths(
                &scene,
                &assignment,
                &options,
                &picker,
                (0, options.photons),
                paired,
                &mut out,
            );
            out
        };
        let (one, two) = (trace(false), trace(true));
        assert!(one.len() > 5_000, "{}", one.len());
        assert_eq!(one.len(), two.len());
        for (k, ((ma, a), (mb, b))) in one.iter().zip(&two).enumerate() {
            assert_eq!(ma, mb, "photon {k}");
            assert_eq!(
                a.position.to_array().map(f32::to_bits),
                b.position.to_array().map(f32::to_bits),
                "photon {k}"
            );
            assert_eq!(
                a.power.to_array().map(f32::to_bits),
                b.power.to_array().map(f32::to_bits),
                "photon {k}"
            );
            assert_eq!(a.direction, b.direction, "photon {k}");
            assert_eq!(a.kind, b.kind, "photon {k}");
        }
    }
}
