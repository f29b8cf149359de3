//! Progressive, consistent photon mapping whose every pass is leak-free and edge-true.
//!
//! Passes 0, 1, 2, … each trace a fresh, independent set of photons (path `p` of pass `i`
//! draws from [`pm_trace::Rng::for_pass`]`(seed, i, p)`), build the maps the partition gives
//! (crease or contact maps keep photons on the surfaces they belong to), render one sample
//! per pixel from streams `(seed, i, pixel)`, at sample number `i` of the pixel's stratified
//! sequence of positions ([`crate::core::pixel_samples`]), and add it to a running sum. Photons of
//! earlier passes are dropped: memory is one pass's maps, the pilot maps (below) and the sum.
//!
//! # The scheme and why
//!
//! Knaus & Zwicker (2011) make photon mapping consistent by averaging independent passes
//! whose gather radius shrinks as `r_i² = r_0² · s_i²` with `s_i² = Π_{j<i} (j + α)/(j + 1)`
//! (α = 2/3 by default): the variance of pass i grows as `1/r_i²`, slowly enough that the
//! variance of the average falls as `N^(−α)`, while the bias of pass i, proportional to
//! `r_i²`, falls as well; the mean squared error falls as `N^(−2/3)` for α = 2/3.
//!
//! Their argument needs each pass's estimate to be an unbiased estimate of the irradiance
//! smoothed over a volume that does *not* depend on that pass's photons. A k-nearest estimate
//! violates this: its radius is the k-th photon's distance, so it is biased even on a
//! uniformly lit plane (the k-th photon sits on the rim; the estimate is `k/(k−1)` times too
//! high in expectation), a bias that does not shrink with the radius and would dominate at
//! small k. So here:
//!
//! - The volume at a surface point x is fixed by a **pilot** photon map, traced once from its
//!   own streams (pass [`PILOT_PASS`]) with the same settings and partition: `r_pilot(x)` is
//!   the estimator's k-nearest extent (the k-th Euclidean distance for the disc and ball, the
//!   k-th Chebyshev distance — a cube's half-size — for the cube; the maximum distance where
//!   fewer than k are found) in x's pilot map, taken at the *site* nearest to x (sites: every
//!   16th pilot photon, each one's extent computed once, when a point first takes it; a
//!   k-nearest search per pixel and pass cost as much as the pass's own gather). Every shard
//!   rebuilds the same pilot, so the volume is a deterministic function of x. It adapts to the
//!   photon density as the k-nearest estimate does.
//! - Pass i gathers **every** photon of x's map within `r_i(x) = r_pilot(x) · s_i` and divides
//!   by the volume's area: `π r_i²` for the disc, and for the cube and the ball the area of the
//!   map's own polygons inside it (Hey & Purgathofer's estimate,
//!   [`FixedVolumeEstimator::irradiance_within`]). Given the pilot, the pass's estimate is then
//!   exactly unbiased for the irradiance smoothed over the pass's volume, the geometric area
//!   keeps edges true at every radius, and the smoothing bias vanishes as `s_i → 0`.
//!
//! A pass depends only on its index (its photons' streams and its pixels' sample numbers), so
//! a run can be split into shards of passes rendered anywhere and merged ([`Shard::merge`]).

pub(crate) mod accumulation;
pub(crate) mod pass_maps;
pub(crate) mod pass_source;
pub(crate) mod pass_sum;
pub(crate) mod pilot;
pub(crate) mod schedule;
pub(crate) mod settings;
pub(crate) mod shard;
#[cfg(feature = "exr")]
pub(crate) mod shard_exr;
pub(crate) mod sppm;

pub use accumulation::{Accumulation, ProgressiveRendered, ProgressiveStats};
pub use pass_sum::PassSums;
pub use schedule::{MAX_PASS, PILOT_PASS, radius_scale};
pub use settings::{PROGRESSIVE_VERSION, ProgressiveSettings};
pub use shard::{Shard, ShardError, ShardHeader, plan_merge};
pub use sppm::{SppmRendered, SppmRenderer, SppmSettings, SppmSnapshot};

use crate::cache::RadianceCache;
use crate::core::tiles::SampleStreams;
use crate::core::tiles::Tile;
use crate::core::tiles::render_tiles;
use crate::emission::emitter::Emitter;
use crate::error::RenderError;
use crate::estimator::fixed::FixedVolumeEstimator;
use crate::estimator::options::EstimatorOptions;
use crate::estimator::point::MapView;
use crate::mode::Mode;
use crate::progress::Progress;
use crate::renderer::in_pool;
use crate::source::final_gather::FinalGatherSource;
use crate::source::photon_read::DirectLight;
use glam::Vec3;
use pass_maps::trace_pass_counted;
use pass_source::{PassGather, PassPhotonSource, PassVolumes};
use pilot::Pilot;
use pm_kdtree::PhotonTree;
use pm_trace::{MapAssignment, Partitioned, PhotonMaps, Scene};
use std::ops::ControlFlow;
use std::time::Instant;

/// Renders progressively with one fixed-volume estimator.
///
/// ```no_run
/// # use pm_render::{EstimatorKind, RenderSettings};
/// # use pm_render::progressive::{ProgressiveRenderer, ProgressiveSettings};
/// # use pm_trace::Partitioner;
/// # fn f(scene: pm_trace::Scene) -> Result<(), pm_render::RenderError> {
/// let settings = ProgressiveSettings::new(RenderSettings { photons: 50_000, ..Default::default() }, 32);
/// let partitioned = pm_trace::CreaseAngle::default().partition(scene)?;
/// let out = ProgressiveRenderer::new(EstimatorKind::GeometryCube, settings).render(&partitioned, &())?;
/// let image = out.accumulation.mean();
/// # Ok(()) }
/// ```
#[derive(Clone, Debug)]
pub struct ProgressiveRenderer<E> {
    estimator: E,
    settings: ProgressiveSettings,
}

impl<E: FixedVolumeEstimator> ProgressiveRenderer<E> {
    /// A renderer with this estimator and these settings.
    pub fn new(estimator: E, settings: ProgressiveSettings) -> Self {
        ProgressiveRenderer { estimator, settings }
    }

    /// The settings.
    pub fn settings(&self) -> &ProgressiveSettings {
        &self.settings
    }

    /// Traces the pilot, then renders the passes (`settings.passes` of them from
    /// `settings.first_pass`, or until the time budget is spent) into a sum.
    pub fn render(
        &self,
        partitioned: &Partitioned,
        progress: &dyn Progress,
    ) -> Result<ProgressiveRendered, RenderError> {
        self.render_observed(partitioned, progress, &mut |_, _| ControlFlow::Continue(()))
    }

    /// As [`ProgressiveRenderer::render`], calling `observe` with the sum and the figures so
    /// far after every pass; the run also stops after a pass for which it returns
    /// [`ControlFlow::Break`]. (A convergence study reads the image at chosen times this way
    /// without rendering again.) The observer's own time counts in the wall time.
    pub fn render_observed(
        &self,
        partitioned: &Partitioned,
        progress: &dyn Progress,
        observe: &mut (dyn FnMut(&Accumulation, &ProgressiveStats) -> ControlFlow<()> + Send),
    ) -> Result<ProgressiveRendered, RenderError> {
        self.settings.validate()?;
        let start = Instant::now();
        let (scene, assignment) = (partitioned.scene(), partitioned.assignment());
        let mut rendered = in_pool(self.settings.render.threads, || {
            self.render_in_pool(scene, assignment, progress, start, observe)
        })??;
        rendered.identity = self.identity(partitioned);
        Ok(rendered)
    }

    /// A text naming everything that changes this renderer's image of `partitioned`: the
    /// settings ([`ProgressiveSettings::identity`]), the estimator ([`crate::Estimator::identity`])
    /// and the partition ([`Partitioned::identity`]). Shards merge only when theirs are equal.
    pub fn identity(&self, partitioned: &Partitioned) -> String {
        format!(
            "{} estimator={} {}",
            self.settings.identity(),
            self.estimator.identity(),
            partitioned.identity()
        )
    }

    fn render_in_pool(
        &self,
        scene: &Scene,
        assignment: &MapAssignment,
        progress: &dyn Progress,
        start: Instant,
        observe: &mut (dyn FnMut(&Accumulation, &ProgressiveStats) -> ControlFlow<()> + Send),
    ) -> Result<ProgressiveRendered, RenderError> {
        let s = &self.settings;
        let r = &s.render;
        let mut stats = ProgressiveStats {
            threads: rayon::current_num_threads(),
            map_count: assignment.map_count(),
            ..ProgressiveStats::default()
        };
        let options = r.estimator_options(&scene.bounds());
        options.validate()?;
        progress.phase("guide");
        let emitter = Emitter::new(scene, assignment, r, &[*scene.camera()])?;
        stats.emission = emitter.report().copied();
        progress.phase("pilot");
        // Uniform whatever the passes' emission: the pilot sets each point's volume from the
        // density uniform emission gives, so that camera-driven passes put more photons in
        // the same volumes (less noise) rather than shrinking them.
        let traced = Emitter::uniform().trace(scene, assignment, r, PILOT_PASS)?;
        let pilot = Pilot::new(
            PhotonMaps::build(scene, assignment, traced)?,
            &self.estimator,
            &options,
        )?;
        stats.pilot = start.elapsed();
        stats.pilot_bytes = pilot.heap_bytes() as u64;
        let mut accumulation = Accumulation::new(r.width, r.height, s.first_pass)?;
        stats.accumulation_bytes = accumulation.sums.heap_bytes();
        loop {
            if s.passes.is_some_and(|n| accumulation.passes >= n) {
                break;
            }
            // A run on a time budget stops at the last pass there is.
            let Some(pass) = s
                .first_pass
                .checked_add(accumulation.passes)
                .filter(|&p| p <= MAX_PASS)
            else {
                break;
            };
            self.render_pass(
                scene,
                assignment,
                &emitter,
                &pilot,
                &options,
                pass,
                &mut accumulation,
                &mut stats,
                progress,
            )?;
            accumulation.passes += 1;
            progress.pass_done(accumulation.passes, stats.photons_emitted);
            stats.passes = accumulation.passes;
            stats.maps_read = pilot.maps_built() as u32;
            stats.wall = start.elapsed();
            if observe(&accumulation, &stats).is_break() {
                break;
            }
            if s.time_budget.is_some_and(|b| start.elapsed() >= b) {
                break;
            }
        }
        stats.passes = accumulation.passes;
        stats.wall = start.elapsed();
        Ok(ProgressiveRendered {
            accumulation,
            stats,
            identity: String::new(),
        })
    }
}

impl<E: FixedVolumeEstimator> ProgressiveRenderer<E> {
    /// Pass `pass`: traces its photons, builds its maps (and for the final gather its cache),
    /// renders it through the mode's source and adds it to `accumulation`'s sums, timing each
    /// phase into `stats`.
    #[allow(clippy::too_many_arguments)]
    fn render_pass(
        &self,
        scene: &Scene,
        assignment: &MapAssignment,
        emitter: &Emitter,
        pilot: &Pilot<'_, E>,
        options: &EstimatorOptions,
        pass: u64,
        accumulation: &mut Accumulation,
        stats: &mut ProgressiveStats,
        progress: &dyn Progress,
    ) -> Result<(), RenderError> {
        let r = &self.settings.render;
        let maps = trace_pass_counted(
            scene,
            assignment,
            r,
            emitter,
            pass,
            options.kinds,
            accumulation.passes,
            stats,
            progress,
        )?;
        let scale = radius_scale(pass, f64::from(self.settings.alpha)) as f32;
        let cache = if r.mode == Mode::FinalGather {
            progress.phase("precompute");
            let t = Instant::now();
            let cache = self.pass_cache(scene, assignment, &maps.trees, pilot, options, scale)?;
            stats.precompute += t.elapsed();
            Some(cache)
        } else {
            None
        };
        progress.phase("render");
        let t = Instant::now();
        let volumes = PassVolumes {
            scene,
            trees: &maps.trees,
            pilot,
            estimator: &self.estimator,
            options,
            scale,
        };
        let (frame, streams) = (r.frame(), SampleStreams { seed: r.seed, pass });
        let sums = &mut accumulation.sums;
        let add = |tile: &Tile, pixels: &[Vec3]| sums.add_tile(tile, pixels);
        // The mode chooses what the pass reads at a diffuse hit; the core renders it.
        match (&cache, r.mode) {
            (Some(cache), _) => {
                let reads = PassGather {
                    volumes: &volumes,
                    cache,
                    options: r.final_gather,
                };
                render_tiles(&FinalGatherSource { reads }, &frame, streams, progress, add)
            }
            (None, mode) => {
                let direct = match mode {
                    Mode::ShadowRays => DirectLight::ShadowRays,
                    _ => DirectLight::Photons,
                };
                let source = PassPhotonSource {
                    volumes: &volumes,
                    direct,
                };
                render_tiles(&source, &frame, streams, progress, add)
            }
        };
        stats.render += t.elapsed();
        Ok(())
    }

    /// A pass's final-gather cache: irradiance at one photon in n of the pass (from the others), each in the
    /// pass's fixed volume there (the pilot's extent times the pass's shrink factor).
    fn pass_cache(
        &self,
        scene: &Scene,
        assignment: &MapAssignment,
        trees: &[PhotonTree],
        pilot: &Pilot<'_, E>,
        options: &EstimatorOptions,
        scale: f32,
    ) -> Result<RadianceCache, RenderError> {
        let trees: Vec<&PhotonTree> = trees.iter().collect();
        RadianceCache::build_with(
            scene,
            &trees,
            assignment,
            self.settings.render.final_gather.cache_every,
            options.max_distance,
            |point, scratch| {
                let map = point.map;
                let Some(extent) = pilot.extent(map, point.at.position, scratch) else {
                    return Vec3::ZERO;
                };
                let Some(polygons) = pilot.polygons(map as u32) else {
                    return Vec3::ZERO;
                };
                let view = MapView {
                    tree: point.photons,
                    polygons,
                };
                self.estimator
                    .irradiance_within(point.at, view, extent * scale, options, scratch)
            },
        )
    }
}
