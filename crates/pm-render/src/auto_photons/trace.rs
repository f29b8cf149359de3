//! The doubling batches and the probes' estimate (see the module above).

use super::settings::{AutoBatch, AutoPhotons, AutoPhotonsReport};
use crate::cache::build::photon_surface_point;
use crate::cache::map_of_parts;
use crate::error::RenderError;
use crate::estimator::fixed::FixedVolumeEstimator;
use crate::estimator::options::EstimatorOptions;
use crate::estimator::point::{MapView, SurfacePoint};
use crate::estimator::scratch::EstimatorScratch;
use glam::DVec3;
use pm_kdtree::{KindMask, Photon};
use pm_trace::{MapAssignment, PhotonMaps, Scene, TraceOptions, TracedPhotons, trace_photon_paths};
use rayon::prelude::*;

/// Photon maps traced in doubling batches (`auto`) until the probes' irradiance, estimated
/// with `estimator` and `options`, changes less than the threshold; the maps are bit-identical
/// to those of [`pm_trace::trace_photons`] with the count reached and `seed`. Runs on the
/// current rayon pool. The near-light fraction of the result is the path-weighted mean of
/// the batches' (equal to a plain run's up to rounding). Returns the maps, the report and
/// that fraction.
///
/// Errors: bad `auto` ([`AutoPhotons::validate`]) or `options`, a trace or map error, and a
/// first batch that yields no probe point ([`RenderError::BadAutoPhotons`]).
pub fn trace_auto<E: FixedVolumeEstimator>(
    scene: &Scene,
    assignment: &MapAssignment,
    estimator: &E,
    options: &EstimatorOptions,
    auto: &AutoPhotons,
    seed: u64,
) -> Result<(PhotonMaps, AutoPhotonsReport, f64), RenderError> {
    auto.validate()?;
    options.validate()?;
    let options = EstimatorOptions {
        kinds: KindMask::ALL,
        leave_out_boundary: true,
        ..*options
    };
    let map_of_part = map_of_parts(assignment);
    let mut photons: Vec<Vec<Photon>> = vec![Vec::new(); assignment.map_count() as usize];
    let mut held = 0u32;
    let mut near_light = 0.0f64;
    let mut probes: Option<Vec<Probe>> = None;
    let mut previous: Option<Vec<DVec3>> = None;
    let mut report = AutoPhotonsReport {
        photons: 0,
        threshold: auto.threshold,
        converged: false,
        probes: 0,
        batches: Vec::new(),
    };
    loop {
        let count = if held == 0 { auto.start } else { held * 2 };
        let trace = TraceOptions {
            photons: count,
            seed,
            ..TraceOptions::default()
        };
        let traced = trace_photon_paths(scene, assignment, &trace, held..count)?;
        let (new, stats) = traced.into_parts();
        near_light += stats.near_light_fraction * f64::from(count - held);
        for (list, added) in photons.iter_mut().zip(new) {
            // Paths of the doubled run carry half the power: exact (a power of two).
            list.iter_mut().for_each(|p| p.power *= 0.5);
            list.extend(added);
        }
        held = count;
        let traced = TracedPhotons::new(photons.clone(), u64::from(held))?;
        let maps = PhotonMaps::build(scene, assignment, traced)?;
        let probes = probes.get_or_insert_with(|| {
            choose_probes(scene, &map_of_part, &maps, auto.probes, estimator, &options)
        });
        if probes.is_empty() {
            // Nothing to compare: every batch would "agree", or none would.
            return Err(RenderError::BadAutoPhotons(format!(
                "no probe point: the first batch of {} photon paths stored no photon on a surface \
                 of the maps (start with more photons)",
                auto.start
            )));
        }
        let values = probe_irradiance(&maps, probes, estimator, &options);
        let change = previous.as_ref().map(|old| relative_change(old, &values));
        report.probes = values.len();
        report.batches.push(AutoBatch {
            photons: held,
            change,
        });
        previous = Some(values);
        let converged = change.is_some_and(|c| c < auto.threshold);
        let bounded = report.batches.len() as u32 >= auto.max_batches
            || u64::from(held) * 2 > u64::from(auto.max_photons);
        if converged || bounded {
            report.photons = held;
            report.converged = converged;
            return Ok((maps, report, near_light / f64::from(held)));
        }
    }
}

/// A probe: a surface point of a map, and the extent of the fixed volume estimated in.
#[derive(Clone, Copy, Debug)]
struct Probe {
    map: u32,
    at: SurfacePoint,
    extent: f32,
}

/// About `count` photons of `maps` (the first batch's), spread evenly over each map's stored
/// order, each placed on the surface it landed on (by a short cast back along its travel, as
/// a cache point is; a photon whose surface is not found in its map is skipped) with the
/// extent of the estimator's k-nearest search there.
fn choose_probes<E: FixedVolumeEstimator>(
    scene: &Scene,
    map_of_part: &[u32],
    maps: &PhotonMaps,
    count: u32,
    estimator: &E,
    options: &EstimatorOptions,
) -> Vec<Probe> {
    let total: usize = maps.iter().map(|m| m.tree().len()).sum();
    let stride = (total / count as usize).max(1);
    let mut probes = Vec::new();
    for (m, map) in maps.iter().enumerate() {
        let view = MapView {
            tree: map.tree(),
            polygons: map.geometry(),
        };
        let indices: Vec<u32> = (0..map.tree().len() as u32).step_by(stride).collect();
        probes.par_extend(
            indices
                .par_iter()
                .map_init(EstimatorScratch::new, |scratch, &i| {
                    let (at, _) = photon_surface_point(scene, map.tree(), i, map_of_part, m as u32)?;
                    let extent = estimator.nearest_extent(at, view, options, scratch)?;
                    Some(Probe {
                        map: m as u32,
                        at,
                        extent,
                    })
                })
                .flatten(),
        );
    }
    probes
}

/// The irradiance at every probe from `maps`, in the probe's fixed volume.
fn probe_irradiance<E: FixedVolumeEstimator>(
    maps: &PhotonMaps,
    probes: &[Probe],
    estimator: &E,
    options: &EstimatorOptions,
) -> Vec<DVec3> {
    probes
        .par_iter()
        .map_init(EstimatorScratch::new, |scratch, probe| {
            let map = maps.map(probe.map);
            let view = MapView {
                tree: map.tree(),
                polygons: map.geometry(),
            };
            estimator
                .irradiance_within(probe.at, view, probe.extent, options, scratch)
                .as_dvec3()
        })
        .collect()
}

/// `sqrt(Σ (new − old)² / Σ new²)` over probes and channels (0 when both are all zero).
pub fn relative_change(old: &[DVec3], new: &[DVec3]) -> f64 {
    let (mut diff, mut norm) = (0.0, 0.0);
    for (a, b) in old.iter().zip(new) {
        diff += (*b - *a).length_squared();
        norm += b.length_squared();
    }
    if norm > 0.0 {
        (diff / norm).sqrt()
    } else if diff > 0.0 {
        1.0
    } else {
        0.0
    }
}
