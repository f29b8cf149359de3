//! One run per (scene, method) to the largest budget, the accumulated image's relative RMSE
//! read after every pass (progressive passes, SPPM iterations, path-traced samples per pixel).

use super::clock::{Clock, ClockKind};
use super::mask::Mask;
use super::saved::Keeper;
use photon_maps::render::glam::DVec3;
use photon_maps::render::progressive::{
    ProgressiveRenderer, ProgressiveSettings, SppmRenderer, SppmSettings,
};
use photon_maps::render::{EstimatorKind, FinalGatherOptions, Image, Mode, RenderSettings, Renderer};
use photon_maps::trace::{CreaseAngle, Partitioner, Scene, SingleMap};
use std::ops::ControlFlow;
use std::path::Path;

/// A renderer the study compares (kept in a run's record by its `--methods` name).
#[derive(Clone, Copy, Debug, PartialEq, Eq, serde::Serialize, serde::Deserialize)]
#[serde(into = "String", try_from = "String")]
pub enum Method {
    /// The unbiased path tracer (next-event estimation), one sample per pixel per batch.
    PathTrace,
    /// pbrt-v4's SPPM: one global map, shadow rays for direct light.
    Sppm,
    /// The progressive renderer with crease maps and this fixed-volume estimator.
    Progressive(EstimatorKind),
    /// The final gather (crease maps, cube estimator; gather rays and camera samples per batch
    /// as [`Progressive::gather`] says), rendered again with fresh photons and seeds per batch
    /// and averaged: its noise falls, its bias stays.
    FinalGather,
    /// The progressive renderer with a final gather per pass (crease maps, cube estimator,
    /// [`Progressive::gather`]): consistent.
    ProgressiveGather,
}

impl Method {
    /// Every method, in the tables' column order.
    pub const ALL: [Method; 5] = [
        Method::PathTrace,
        Method::Sppm,
        Method::Progressive(EstimatorKind::Disc),
        Method::Progressive(EstimatorKind::GeometryCube),
        Method::Progressive(EstimatorKind::GeometryBall),
    ];

    /// The methods the study can run besides [`Method::ALL`] (its default), chosen by name
    /// with `--methods`.
    pub const EXTRA: [Method; 2] = [Method::FinalGather, Method::ProgressiveGather];

    /// The name `--methods` takes.
    pub fn name(self) -> &'static str {
        match self {
            Method::PathTrace => "path-trace",
            Method::Sppm => "sppm",
            Method::Progressive(EstimatorKind::Disc) => "disc",
            Method::Progressive(EstimatorKind::GeometryCube) => "cube",
            Method::Progressive(EstimatorKind::GeometryBall) => "ball",
            Method::FinalGather => "final-gather",
            Method::ProgressiveGather => "progressive-gather",
        }
    }

    /// The column and legend label.
    pub fn label(self) -> &'static str {
        match self {
            Method::PathTrace => "path tracing",
            Method::Sppm => "SPPM",
            Method::Progressive(EstimatorKind::Disc) => "progressive disc",
            Method::Progressive(EstimatorKind::GeometryCube) => "progressive cube",
            Method::Progressive(EstimatorKind::GeometryBall) => "progressive ball",
            Method::FinalGather => "final gather",
            Method::ProgressiveGather => "progressive final gather",
        }
    }
}

impl From<Method> for String {
    fn from(method: Method) -> String {
        method.name().to_owned()
    }
}

impl TryFrom<String> for Method {
    type Error = String;

    fn try_from(name: String) -> Result<Method, String> {
        Method::ALL
            .into_iter()
            .chain(Method::EXTRA)
            .find(|m| m.name() == name)
            .ok_or_else(|| format!("unknown method {name:?}"))
    }
}

/// The progressive renderer's own settings (SPPM keeps pbrt-v4's).
#[derive(Clone, Copy, Debug)]
pub struct Progressive {
    /// [`Mode::PhotonMap`] (photons for all light) or [`Mode::ShadowRays`] (shadow rays for
    /// direct light, as SPPM has it).
    pub direct: Mode,
    /// k of the pilot's extents (the first pass's gather volume holds about k photons).
    pub k: usize,
    /// Knaus & Zwicker's α.
    pub alpha: f32,
    /// The final-gather methods' gather rays per camera sample and corner distance (the other
    /// options at their defaults).
    pub final_gather: FinalGatherOptions,
    /// The final-gather methods' camera samples per pixel per pass (each pass traces its
    /// photons and builds its cache once for all of them).
    pub gather_samples: u32,
}

impl Progressive {
    /// The final-gather methods' settings in words, for the study's header.
    pub fn describe_gather(&self) -> String {
        let g = &self.final_gather;
        let corner = match g.corner_distance {
            None => format!(
                "an extra bounce for gather hits closer than {} % of the scene's diagonal",
                100.0 * FinalGatherOptions::CORNER_FRACTION
            ),
            Some(d) if d > 0.0 => format!("an extra bounce for gather hits closer than {d} m"),
            Some(_) => "no extra bounce".to_owned(),
        };
        format!(
            "{} gather rays per camera sample, {} camera samples per pixel per pass, {corner}",
            g.gather_rays, self.gather_samples
        )
    }
}

/// The error after one pass.
#[derive(Clone, Copy, Debug, serde::Serialize, serde::Deserialize)]
pub struct Sample {
    /// Rendering seconds when the pass ended.
    pub seconds: f64,
    /// Passes (or samples per pixel) so far.
    pub passes: u64,
    /// Relative RMSE against the reference.
    pub rel_rmse: f64,
}

/// The samples of one run.
#[derive(serde::Serialize, serde::Deserialize)]
pub struct Run {
    pub method: Method,
    pub samples: Vec<Sample>,
}

impl Run {
    /// The error after `passes` passes, if the run got there.
    pub fn after(&self, passes: u64) -> Option<f64> {
        self.samples
            .iter()
            .find(|s| s.passes == passes)
            .map(|s| s.rel_rmse)
    }

    /// The error of the image one has at `seconds`: the last pass that ended by then
    /// (`None` when none had).
    pub fn at(&self, seconds: f64) -> Option<Sample> {
        self.samples
            .iter()
            .take_while(|s| s.seconds <= seconds)
            .last()
            .copied()
    }
}

/// What a run is measured against and for how long.
pub struct Measure<'a> {
    /// The path-traced reference.
    pub reference: &'a Image,
    /// The pixels the error counts.
    pub mask: &'a Mask,
    /// Stop after the pass that ends past this many seconds.
    pub max_seconds: f64,
    /// What the seconds count.
    pub clock: ClockKind,
    /// Where to keep the image each budget's error is read from, for `--rescore`: the
    /// folder, the scene's name and the budgets.
    pub keep: Option<(&'a Path, &'a str, &'a [f64])>,
}

/// Renders `scene` with `method` until `measure.max_seconds` of rendering, reading the error
/// against the reference after every pass.
pub fn run(
    method: Method,
    scene: &Scene,
    base: RenderSettings,
    progressive: Progressive,
    measure: &Measure<'_>,
) -> Result<Run, String> {
    let Measure {
        reference,
        mask,
        max_seconds,
        clock,
        keep,
    } = *measure;
    let mut keeper = match keep {
        Some((dir, scene, budgets)) => Some(Keeper::new(dir, scene, method.name(), budgets)?),
        None => None,
    };
    let mut clock = Clock::start(clock, base.threads);
    let mut samples = Vec::new();
    let mut failure = None;
    let mut record = |clock: &mut Clock, passes: u64, image: &dyn Fn() -> Result<Image, String>| {
        let seconds = clock.seconds();
        clock.exclude(|| match image() {
            Ok(i) => {
                let sample = Sample {
                    seconds,
                    passes,
                    rel_rmse: mask.relative_rmse(&i, reference),
                };
                samples.push(sample);
                if let Some(Err(e)) = keeper.as_mut().map(|k| k.push(sample, i)) {
                    failure = Some(e);
                }
            }
            Err(e) => failure = Some(e),
        });
        if seconds >= max_seconds || failure.is_some() {
            ControlFlow::Break(())
        } else {
            ControlFlow::Continue(())
        }
    };
    match method {
        // Independent images, one per batch (fresh seed, and for the final gather fresh
        // photons), averaged.
        Method::PathTrace | Method::FinalGather => {
            let mut sum = vec![DVec3::ZERO; reference.pixels().len()];
            let partitioned = if method == Method::PathTrace {
                SingleMap.partition(scene.clone())
            } else {
                CreaseAngle::default().partition(scene.clone())
            }
            .map_err(|e| e.to_string())?;
            for batch in 0u64.. {
                let seed = base.seed.wrapping_add(batch);
                let image = if method == Method::PathTrace {
                    let settings = RenderSettings {
                        mode: Mode::PathTrace,
                        samples_per_pixel: 1,
                        seed,
                        ..base
                    };
                    Renderer::new(EstimatorKind::Disc, settings).render(&partitioned, &())
                } else {
                    let settings = RenderSettings {
                        mode: Mode::FinalGather,
                        samples_per_pixel: progressive.gather_samples,
                        seed,
                        final_gather: progressive.final_gather,
                        ..base
                    };
                    Renderer::new(EstimatorKind::GeometryCube, settings).render(&partitioned, &())
                }
                .map_err(|e| e.to_string())?
                .image;
                for (s, p) in sum.iter_mut().zip(image.pixels()) {
                    *s += p.as_dvec3();
                }
                let n = (batch + 1) as f64;
                let mean = || {
                    let pixels = sum.iter().map(|s| (*s / n).as_vec3()).collect();
                    Image::from_pixels(base.width, base.height, pixels).map_err(|e| e.to_string())
                };
                if record(&mut clock, batch + 1, &mean).is_break() {
                    break;
                }
            }
        }
        Method::Sppm => {
            let settings = SppmSettings {
                passes: Some(u64::MAX),
                ..SppmSettings::new(base, 1)
            };
            SppmRenderer::new(settings)
                .render_observed(scene, &(), &mut |snapshot| {
                    record(&mut clock, snapshot.stats().passes, &|| {
                        snapshot.image().map_err(|e| e.to_string())
                    })
                })
                .map_err(|e| e.to_string())?;
        }
        Method::Progressive(_) | Method::ProgressiveGather => {
            let (estimator, mode) = match method {
                Method::Progressive(estimator) => (estimator, progressive.direct),
                _ => (EstimatorKind::GeometryCube, Mode::FinalGather),
            };
            let render = RenderSettings {
                mode,
                k: progressive.k,
                samples_per_pixel: if method == Method::ProgressiveGather {
                    progressive.gather_samples
                } else {
                    base.samples_per_pixel
                },
                final_gather: progressive.final_gather,
                ..base
            };
            let settings = ProgressiveSettings {
                passes: Some(u64::MAX),
                alpha: progressive.alpha,
                ..ProgressiveSettings::new(render, 1)
            };
            let crease = CreaseAngle::default()
                .partition(scene.clone())
                .map_err(|e| e.to_string())?;
            ProgressiveRenderer::new(estimator, settings)
                .render_observed(&crease, &(), &mut |sum, stats| {
                    record(&mut clock, stats.passes, &|| Ok(sum.mean()))
                })
                .map_err(|e| e.to_string())?;
        }
    }
    if let Some(e) = failure {
        return Err(e);
    }
    if let Some(keeper) = keeper {
        keeper.finish()?;
    }
    Ok(Run { method, samples })
}
