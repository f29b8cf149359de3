//! An automatic photon count: photons traced in doubling batches until the irradiance the
//! renderer's estimator reads at a fixed set of probe points changes less than a threshold
//! between batches.
//!
//! **Exactness.** Batch `k` holds paths `0..start·2ᵏ` of one photon stream: batch `k + 1`
//! traces only the new paths `start·2ᵏ..start·2ᵏ⁺¹` ([`pm_trace::trace_photon_paths`], each
//! path its own random stream `(seed, path index)`) and halves the power of the photons held
//! (a path's power is `Φ / N`; with `N` doubled, a power of two, halving is exact in floating
//! point and a path's decisions do not depend on the scale of its power). So the maps at the
//! count the run stops at are, bit for bit, the maps of a plain run with that count and seed,
//! and so is every image rendered from them.
//!
//! **The estimate compared.** Probe points are photons of the first batch (about
//! [`AutoPhotons::probes`] of them, evenly over the stored order), each placed on its surface
//! as a cache point is, with the extent of the estimator's k-nearest search there in the first
//! batch. After each batch the irradiance in that *fixed* volume is estimated from the whole
//! map ([`FixedVolumeEstimator::irradiance_within`], all photon kinds, as the final gather's
//! cache reads them) and compared with the previous batch's as a relative RMS change over
//! probes and channels, `sqrt(Σ (Eₖ − Eₖ₋₁)² / Σ Eₖ²)`. The volume is fixed because a
//! k-nearest estimate's relative noise is about `1/sqrt(k)` whatever the photon count (only
//! its radius, its blur, shrinks): its change between batches would not fall. In a fixed
//! volume the photons found double with each batch, so the change falls as `1/sqrt(N)`: the
//! rule stops when the lighting at the scale of the first batch's gather radius is resolved
//! to the threshold. With about k photons per volume at the start, the first change is about
//! `1/sqrt(2k)` (0.07 for k = 100) and each doubling divides it by about √2.
//!
//! **Cost.** Tracing costs what the final count costs (no path is traced twice); the maps are
//! built once per batch (about twice the final build over the doubling series) and the probes
//! are one k-nearest estimate each per batch, negligible.
//!
//! **Caveat.** The stopping count is data-dependent: renders made at "the count the rule
//! chose" are not an unbiased sample of renders at a fixed count (a batch that happens to
//! agree with the previous one stops early). Each render is still exactly the render at its
//! count; for an unbiased study fix `photons` to the count found.

use crate::cache::map_of_parts;
use crate::error::RenderError;
use crate::estimator::point::{MapView, SurfacePoint};
use crate::estimator::{EstimatorOptions, EstimatorScratch, FixedVolumeEstimator};
use crate::mode::Mode;
use crate::progress::Progress;
use crate::renderer::{PhotonCache, Rendered, Renderer, in_pool};
use crate::settings::RenderSettings;
use crate::stats::RenderStats;
use glam::DVec3;
use pm_kdtree::{KindMask, Photon};
use pm_trace::{
    MapAssignment, Partitioned, PhotonMaps, Scene, TraceOptions, TracedPhotons, trace_photon_paths,
};
use pm_trace::{Ray, RayKind};
use rayon::prelude::*;
use std::time::Instant;

/// How to choose the photon count automatically.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct AutoPhotons {
    /// Photon paths of the first batch; batch `k` holds `start · 2ᵏ`. At most 2²⁴ (so that
    /// every count is exact in `f32`).
    pub start: u32,
    /// Stop once the relative RMS change between two batches is below this; in (0, 1).
    pub threshold: f64,
    /// The most photon paths (at most [`pm_trace::MAX_PHOTON_PATHS`]): no batch goes past it.
    pub max_photons: u32,
    /// The most batches (at least 2: the first change needs two).
    pub max_batches: u32,
    /// About how many probe points (at least 1).
    pub probes: u32,
}

impl AutoPhotons {
    /// Probe points by default.
    pub const DEFAULT_PROBES: u32 = 1024;
    /// Batches by default.
    pub const DEFAULT_MAX_BATCHES: u32 = 12;

    /// Start at `start` paths, stop below `threshold`, with the default bounds (up to
    /// [`pm_trace::MAX_PHOTON_PATHS`], 12 batches, 1024 probes).
    pub fn new(start: u32, threshold: f64) -> Self {
        AutoPhotons {
            start,
            threshold,
            max_photons: pm_trace::MAX_PHOTON_PATHS,
            max_batches: Self::DEFAULT_MAX_BATCHES,
            probes: Self::DEFAULT_PROBES,
        }
    }

    /// Refuses a threshold outside (0, 1) ([`RenderError::BadAutoThreshold`]) and a start of
    /// 0 or past 2²⁴ or past the maximum, a maximum past [`pm_trace::MAX_PHOTON_PATHS`],
    /// fewer than 2 batches or no probes ([`RenderError::BadAutoPhotons`]).
    pub fn validate(&self) -> Result<(), RenderError> {
        if !(self.threshold > 0.0 && self.threshold < 1.0) {
            return Err(RenderError::BadAutoThreshold(self.threshold));
        }
        let bad = |m: String| Err(RenderError::BadAutoPhotons(m));
        if self.start == 0 || self.start > 1 << 24 {
            return bad(format!("start of {} photons: expected 1 to 2^24", self.start));
        }
        if self.max_photons > pm_trace::MAX_PHOTON_PATHS {
            return bad(format!(
                "maximum of {} photons: expected at most {}",
                self.max_photons,
                pm_trace::MAX_PHOTON_PATHS
            ));
        }
        if self.start > self.max_photons {
            return bad(format!(
                "start of {} photons past the maximum of {}",
                self.start, self.max_photons
            ));
        }
        if self.max_batches < 2 {
            return bad(format!("{} batches: expected at least 2", self.max_batches));
        }
        if self.probes == 0 {
            return bad("no probe points: expected at least 1".into());
        }
        Ok(())
    }
}

/// One batch of an automatic photon count.
#[derive(Clone, Debug, PartialEq)]
pub struct AutoBatch {
    /// Photon paths held after the batch.
    pub photons: u32,
    /// Relative RMS change of the probes' irradiance from the previous batch (`None` for the
    /// first).
    pub change: Option<f64>,
}

/// What an automatic photon count did.
#[derive(Clone, Debug, PartialEq)]
pub struct AutoPhotonsReport {
    /// The count it stopped at: the maps are those of a plain run with this many photons.
    pub photons: u32,
    /// The threshold asked for.
    pub threshold: f64,
    /// True when the last change fell below the threshold (false: a bound stopped it).
    pub converged: bool,
    /// Probe points compared.
    pub probes: usize,
    /// Every batch, in order.
    pub batches: Vec<AutoBatch>,
}

/// Photon maps traced in doubling batches (`auto`) until the probes' irradiance, estimated
/// with `estimator` and `options`, changes less than the threshold; the maps are bit-identical
/// to those of [`pm_trace::trace_photons`] with the count reached and `seed`. Runs on the
/// current rayon pool. The near-light fraction of the result is the path-weighted mean of
/// the batches' (equal to a plain run's up to rounding).
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
    let total: usize = maps.maps().iter().map(|m| m.tree().len()).sum();
    let stride = (total / count as usize).max(1);
    let back = 4.0 * scene.epsilon();
    let mut probes = Vec::new();
    for (m, map) in maps.maps().iter().enumerate() {
        let view = MapView {
            tree: map.tree(),
            polygons: map.geometry(),
        };
        let indices: Vec<u32> = (0..map.tree().len() as u32).step_by(stride).collect();
        probes.par_extend(
            indices
                .par_iter()
                .map_init(EstimatorScratch::new, |scratch, &i| {
                    let photon = map.tree().get(i);
                    let (position, direction) = (photon.position(), photon.direction());
                    let ray = Ray {
                        origin: position - direction * back,
                        direction,
                    };
                    let hit = scene.intersect(&ray, 2.0 * back, RayKind::Other)?;
                    if map_of_part.get(hit.part.0 as usize) != Some(&(m as u32)) {
                        return None;
                    }
                    let at = SurfacePoint {
                        position,
                        normal: scene.shading_normal_at(&hit),
                        front_face: hit.front_face,
                    };
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

impl<E: FixedVolumeEstimator> Renderer<E> {
    /// [`Renderer::build_photon_cache`] with the photon count chosen by `auto`
    /// ([`trace_auto`], with this renderer's estimator, options and seed; `settings.photons`
    /// is not read): the maps (and the final gather's cache) are the bits of
    /// `build_photon_cache` with `photons` the count reached, which `stats.auto_photons`
    /// reports with every batch's change. The trace phase covers the batches' tracing,
    /// building and probing; the build phase is zero.
    pub fn build_photon_cache_auto(
        &self,
        partitioned: &Partitioned,
        auto: &AutoPhotons,
        progress: &dyn Progress,
        stats: &mut RenderStats,
    ) -> Result<PhotonCache, RenderError> {
        auto.validate()?;
        let settings = self.settings();
        let mode = settings.mode;
        if !mode.uses_photons() {
            return Err(RenderError::UnreadMaps(mode));
        }
        let scene = partitioned.scene();
        let assignment = partitioned.assignment();
        in_pool(settings.threads, || {
            progress.phase("trace");
            let start = Instant::now();
            let options = settings.estimator_options(&scene.bounds());
            let (maps, report, near_light) =
                trace_auto(scene, assignment, self.estimator(), &options, auto, settings.seed)?;
            // The settings of the count reached check what depends on it (cache density).
            let chosen = Renderer::new(
                self.estimator(),
                RenderSettings {
                    photons: report.photons,
                    ..*settings
                },
            );
            chosen.settings().validate()?;
            stats.trace = start.elapsed();
            stats.photons_emitted = u64::from(report.photons);
            stats.photons_stored = maps.maps().iter().map(|m| m.tree().len() as u64).sum();
            stats.near_light_fraction = near_light;
            stats.map_count = assignment.map_count();
            stats.photon_channels_below_range = maps.channels_below_range();
            stats.occupancy = maps.occupancy(settings.k);
            stats.auto_photons = Some(report);
            let radiance = match mode {
                Mode::FinalGather => Some(chosen.build_cache(scene, &maps, progress, stats)?),
                _ => None,
            };
            Ok(PhotonCache {
                maps,
                radiance,
                photons_emitted: stats.photons_emitted,
                near_light_fraction: near_light,
            })
        })?
    }

    /// [`Renderer::render`] with the photon count chosen by `auto`
    /// ([`Renderer::build_photon_cache_auto`]): the image is the bits of `render` with
    /// `photons` the count reached.
    pub fn render_auto(
        &self,
        partitioned: &Partitioned,
        auto: &AutoPhotons,
        progress: &dyn Progress,
    ) -> Result<Rendered, RenderError> {
        let mut stats = RenderStats {
            threads: match self.settings().threads {
                0 => rayon::current_num_threads(),
                n => n,
            },
            ..RenderStats::default()
        };
        let cache = self.build_photon_cache_auto(partitioned, auto, progress, &mut stats)?;
        let image = self.render_from_cache(partitioned.scene(), &cache, progress, &mut stats)?;
        Ok(Rendered { image, stats })
    }
}
