//! The renderer's calls with an automatic photon count.

use super::settings::AutoPhotons;
use super::trace::trace_auto;
use crate::error::RenderError;
use crate::estimator::fixed::FixedVolumeEstimator;
use crate::mode::Mode;
use crate::progress::Progress;
use crate::renderer::{PhotonCache, Rendered, Renderer, in_pool};
use crate::settings::RenderSettings;
use crate::stats::RenderStats;
use pm_trace::Partitioned;
use std::time::Instant;

impl<E: FixedVolumeEstimator> Renderer<E> {
    /// [`Renderer::build_photon_cache`] with the photon count chosen by `auto`
    /// ([`trace_auto`], with this renderer's estimator, options and seed; `settings.photons`
    /// is not read; camera-driven emission is refused): the maps (and the final gather's cache) are the bits of
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
        // Its batches are ranges of one uniform run, so that the count reached gives the
        // bits of a fixed count; a guided run's paths depend on its count.
        if settings.emission != crate::emission::choice::PhotonEmission::Uniform {
            return Err(RenderError::BadEmission(
                "an automatic photon count traces uniform batches: choose one or the other".to_owned(),
            ));
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
            stats.photons_stored = maps.iter().map(|m| m.tree().len() as u64).sum();
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
