//! Deterministic parallel photon tracing: every path draws from its own random stream
//! `(seed, pass, path index)`, chunks of paths run on rayon and are merged in path order, so the
//! stored photons are bit-identical for any thread count.

use super::guide::EmissionGuide;
use super::light_picker::LightPicker;
use super::options::{MAX_PHOTON_PATHS, MAX_STORED_PHOTONS, TraceOptions};
use super::path::{NearLight, trace_paths};
use super::traced::{TraceStats, TracedPhotons};
use crate::error::TraceError;
use crate::partition::assignment::MapAssignment;
use crate::scene::Scene;
use pm_kdtree::Photon;
use rayon::prelude::*;
use std::ops::Range;
use std::time::Instant;

/// Paths per parallel work item.
const CHUNK: u32 = 512;

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
    trace_photon_paths(scene, assignment, options, 0..options.photons)
}

/// Traces paths `paths` (a range of path indices within `0..options.photons`) of the run
/// `options` describes: each path is the path of that index in [`trace_photons`] (its own
/// random stream, its power `Φ / options.photons` at emission), so the photons of `0..a` then
/// `a..n` are, in order, the photons of `0..n`. [`TraceStats::emitted`] counts the paths of
/// the range.
///
/// Errors: those of [`trace_photons`], and a range that is empty or reaches past
/// `options.photons` ([`TraceError::ZeroPhotons`], [`TraceError::TooManyPhotons`]).
pub fn trace_photon_paths(
    scene: &Scene,
    assignment: &MapAssignment,
    options: &TraceOptions,
    paths: Range<u32>,
) -> Result<TracedPhotons, TraceError> {
    trace_paths_emitted(scene, assignment, options, paths, None)
}

/// [`trace_photon_paths`] with camera-driven emission: each path is emitted as there, then
/// traced on with its bin's keep probability under `guide` (and carrying its power over that
/// probability) or dropped at its light. Unbiased: every estimate's expected value is that
/// of [`trace_photon_paths`] (see [`EmissionGuide`]). `options.photons` counts the paths
/// emitted, dropped ones included ([`EmissionGuide::photons_to_emit`] gives the count that
/// traces about a given number); [`TraceStats::emitted`] counts the range's paths, and
/// [`TraceStats::traced`] those traced on.
pub fn trace_guided_photon_paths(
    scene: &Scene,
    assignment: &MapAssignment,
    options: &TraceOptions,
    paths: Range<u32>,
    guide: &EmissionGuide,
) -> Result<TracedPhotons, TraceError> {
    trace_paths_emitted(scene, assignment, options, paths, Some(guide))
}

/// The paths `paths` of the run, each emitted as `guide` (if any) says.
fn trace_paths_emitted(
    scene: &Scene,
    assignment: &MapAssignment,
    options: &TraceOptions,
    paths: Range<u32>,
    guide: Option<&EmissionGuide>,
) -> Result<TracedPhotons, TraceError> {
    let start = Instant::now();
    check_request(scene, assignment, options)?;
    if paths.is_empty() {
        return Err(TraceError::ZeroPhotons);
    }
    if paths.end > options.photons {
        return Err(TraceError::TooManyPhotons { photons: paths.end });
    }
    let picker = LightPicker::new(scene, options.photons)?;
    let (merged, near_light) = trace_in_waves(scene, assignment, options, &picker, guide, paths.clone())?;
    let Merged { photons, stored, .. } = merged;
    let near_light_fraction = if near_light.emitted > 0.0 {
        near_light.near / near_light.emitted
    } else {
        0.0
    };
    let stats = TraceStats {
        emitted: u64::from(paths.end - paths.start),
        traced: near_light.traced,
        stored,
        near_light_fraction,
        seconds: start.elapsed().as_secs_f64(),
    };
    Ok(TracedPhotons { photons, stats })
}

/// Refuses zero photons, more than [`MAX_PHOTON_PATHS`], and an assignment made for another
/// scene.
pub(super) fn check_request(
    scene: &Scene,
    assignment: &MapAssignment,
    options: &TraceOptions,
) -> Result<(), TraceError> {
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
    Ok(())
}

/// Traces every path in waves of chunks: each wave in parallel into buffers that are reused
/// (cache-warm, no fresh pages), merged in path order while the next one traces. Returns the
/// merged photons and the near-light figures summed in chunk order (so they do not depend on
/// the thread count).
fn trace_in_waves(
    scene: &Scene,
    assignment: &MapAssignment,
    options: &TraceOptions,
    picker: &LightPicker,
    guide: Option<&EmissionGuide>,
    paths: Range<u32>,
) -> Result<(Merged, NearLight), TraceError> {
    let maps = assignment.map_count() as usize;
    let mut merged = Merged {
        photons: vec![Vec::new(); maps],
        stored: vec![[0u64; 3]; maps],
        total: 0,
    };
    let count = paths.end - paths.start;
    let chunks = count.div_ceil(CHUNK);
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
                let begin = paths.start + chunk * CHUNK;
                let end = begin.saturating_add(CHUNK).min(paths.end);
                trace_paths(
                    scene,
                    assignment,
                    options,
                    picker,
                    guide,
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
    let mut near_light = NearLight::default();
    let mut add_near = |near: &[NearLight]| {
        for n in near {
            near_light.emitted += n.emitted;
            near_light.near += n.near;
            near_light.traced += n.traced;
        }
    };
    trace_wave(0, &mut traced, &mut traced_near);
    let first_wave_paths = (u64::from(wave) * u64::from(CHUNK)).min(u64::from(count));
    merged.reserve_for(&traced, count as f64 / first_wave_paths as f64);
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
    Ok((merged, near_light))
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
