//! Learning an [`EmissionGuide`]: a pilot of uniformly emitted photon paths, each counted in
//! its emission bin as seen or not (see `guide.rs` for what the guide does with the counts).

use super::guide::{BinMap, EmissionGuide, GuideOptions, bin};
use super::light_picker::LightPicker;
use super::options::TraceOptions;
use super::path::pilot_path;
use super::trace::check_request;
use crate::error::TraceError;
use crate::partition::assignment::MapAssignment;
use crate::scene::Scene;
use glam::Vec3;
use rayon::prelude::*;

/// Pilot paths per parallel work item.
const PILOT_CHUNK: u32 = 1024;
/// Salt of the pilot's seed, so that its streams are not any pass of the run.
const PILOT_SALT: u64 = 0x6775_6964_655f_7069; // "guide_pi"

impl EmissionGuide {
    /// Learns the guide from `guide.pilot_photons` pilot paths of the run `options` describes
    /// (its seed and bounce limit; not its photon count or pass): a path is seen when
    /// `seen(map, position)` holds for one of the photons it stores. When no pilot path is
    /// seen, every bin keeps every photon (the guide changes nothing).
    ///
    /// Errors: those of [`trace_photons`](super::trace_photons), and bad `guide` options
    /// ([`TraceError::InvalidGuide`]).
    pub fn learn(
        scene: &Scene,
        assignment: &MapAssignment,
        options: &TraceOptions,
        guide: &GuideOptions,
        seen: &(dyn Fn(u32, Vec3) -> bool + Sync),
    ) -> Result<Self, TraceError> {
        guide.validate().map_err(TraceError::InvalidGuide)?;
        let pilot = TraceOptions {
            photons: guide.pilot_photons,
            seed: crate::rng::fmix64(options.seed ^ PILOT_SALT),
            pass: u64::MAX,
            max_bounces: options.max_bounces,
        };
        check_request(scene, assignment, &pilot)?;
        let picker = LightPicker::new(scene, pilot.photons)?;
        let bounds = scene.bounds();
        let chunks = pilot.photons.div_ceil(PILOT_CHUNK);
        let counts = (0..chunks)
            .into_par_iter()
            .map(|chunk| {
                let begin = chunk * PILOT_CHUNK;
                let end = (begin + PILOT_CHUNK).min(pilot.photons);
                let mut counts: BinMap<[u32; 2]> = BinMap::default();
                let mut stored = Vec::new();
                for path in begin..end {
                    stored.clear();
                    let (light, ray) = pilot_path(scene, assignment, &pilot, &picker, path, &mut stored);
                    let key = bin(light, &ray, &bounds);
                    let is_seen = stored.iter().any(|(map, p)| seen(*map, p.position));
                    let c = counts.entry(key).or_default();
                    c[0] += 1;
                    c[1] += u32::from(is_seen);
                }
                counts
            })
            .reduce(BinMap::default, |mut a, b| {
                for (k, [n, s]) in b {
                    let c = a.entry(k).or_default();
                    c[0] += n;
                    c[1] += s;
                }
                a
            });
        Ok(Self::from_counts(counts, bounds, pilot.photons, guide.floor))
    }
}
