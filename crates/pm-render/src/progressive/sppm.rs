//! Stochastic progressive photon mapping (Hachisuka & Jensen 2009) as pbrt-v4 implements it,
//! the baseline the leak-free progressive renderer is compared with.
//!
//! Per pass, every pixel traces one camera ray (at its next position in the pixel's
//! stratified sequence, [`crate::core::pixel_samples`]) through specular bounces, adding
//! emission and direct light by shadow rays at each diffuse vertex it records as its visible
//! point; the pass's photons (one global map, photons of kind direct left out since shadow
//! rays carry direct light, as pbrt deposits no photon at a path's first hit) within the
//! pixel's radius r add `Φ_p · albedo/π` (zero for photons from behind the surface, as pbrt's
//! diffuse BSDF gives; no other normal test), or `Φ_p · f(wo, wi_p)` where the BSDF has a
//! glossy lobe. Then with M photons found:
//! `N ← N + αM`, `r ← r·√((N + αM)/(N + M))`, `τ ← (τ + Φ)·(r_new/r)²`, and the pixel's
//! radiance is `L_direct/passes + τ/(passes · π r²)` (photon powers are already divided by
//! the photons per pass).
//!
//! **Initial radius.** pbrt-v4 takes one radius for the whole image from the user (default 1
//! scene unit). Here each pixel's radius starts at the k-nearest distance (k from the
//! settings, Euclidean, photons of the kinds gathered) around its first visible point in that
//! pass's map, capped by the maximum search distance: the same start the k-nearest renderer
//! and the progressive renderer's pilot have, so that the comparison does not hinge on a
//! hand-tuned constant.

use super::accumulation::ProgressiveStats;
use super::pass_maps::trace_pass_counted;
use crate::core::pixel_samples::{pixel_position, sample_number};
use crate::core::tiles::PIXEL_SEED_SALT;
use crate::core::{PathVertex, follow_delta_bounces};
use crate::emission::emitter::Emitter;
use crate::error::RenderError;
use crate::estimator::options::EstimatorOptions;
use crate::estimator::weight::{BsdfWeight, Irradiance, PhotonWeight};
use crate::image::Image;
use crate::mode::Mode;
use crate::progress::Progress;
use crate::renderer::in_pool;
use crate::settings::RenderSettings;
use crate::source::direct::{Mis, direct_irradiance, direct_radiance_through};
use glam::{DVec3, Vec3};
use pm_kdtree::{Euclidean, KindMask, Neighbours, PhotonTree};
use pm_trace::bsdf::near_specular::passes_through;
use pm_trace::{Bsdf, MapAssignment, RayKind, Rng, Scene};
use rayon::prelude::*;
use std::f32::consts::{FRAC_1_PI, PI};
use std::ops::ControlFlow;
use std::time::{Duration, Instant};

/// Settings of an SPPM render.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SppmSettings {
    /// Image, photons per pass, k (for the initial radius), maximum distance (caps it), seed,
    /// threads. The mode and `reject_behind` are ignored.
    pub render: RenderSettings,
    /// α (default 2/3): the share of the new photons kept in N.
    pub alpha: f32,
    /// Passes to render; `None` renders until the time budget is spent.
    pub passes: Option<u64>,
    /// Stop after the pass that spends this budget.
    pub time_budget: Option<Duration>,
}

impl SppmSettings {
    /// Bytes of state SPPM keeps per pixel (flux, direct light, photon count, radius).
    pub const BYTES_PER_PIXEL: u64 = size_of::<PixelState>() as u64;

    /// `passes` passes with α = 2/3 and `render`'s settings.
    pub fn new(render: RenderSettings, passes: u64) -> Self {
        SppmSettings {
            render,
            alpha: 2.0 / 3.0,
            passes: Some(passes),
            time_budget: None,
        }
    }

    /// Checks the render settings, α, that the per-pixel state fits
    /// [`crate::image::MAX_PIXEL_STATE_BYTES`], and that the run will stop.
    pub fn validate(&self) -> Result<(), RenderError> {
        self.render.validate()?;
        crate::image::check_pixel_state(self.render.width, self.render.height, Self::BYTES_PER_PIXEL)?;
        if !(self.alpha > 0.0 && self.alpha < 1.0) {
            return Err(RenderError::BadAlpha(self.alpha));
        }
        match (self.passes, self.time_budget) {
            (Some(0), _) | (None, None) => Err(RenderError::ZeroPasses),
            _ => Ok(()),
        }
    }
}

/// One pixel's SPPM state.
#[derive(Clone, Copy, Debug, Default)]
struct PixelState {
    /// Emission and direct light, summed over passes.
    direct: DVec3,
    /// Accumulated flux τ.
    tau: Vec3,
    /// Photon count N.
    n: f32,
    /// Radius r; 0 until the pixel's first visible point.
    radius: f32,
}

/// An SPPM render's image and figures.
#[derive(Clone, Debug)]
pub struct SppmRendered {
    /// The radiance estimate after the last pass.
    pub image: Image,
    /// Counts and timings (`pilot` is zero: SPPM has none).
    pub stats: ProgressiveStats,
}

/// Renders with stochastic progressive photon mapping in one global map.
#[derive(Clone, Debug)]
pub struct SppmRenderer {
    settings: SppmSettings,
}

impl SppmRenderer {
    /// A renderer with these settings.
    pub fn new(settings: SppmSettings) -> Self {
        SppmRenderer { settings }
    }

    /// Renders the passes from pass 0 (photon streams `(seed, pass, path)` as in the
    /// progressive renderer).
    pub fn render(&self, scene: &Scene, progress: &dyn Progress) -> Result<SppmRendered, RenderError> {
        self.render_observed(scene, progress, &mut |_| ControlFlow::Continue(()))
    }

    /// As [`SppmRenderer::render`], calling `observe` after every pass with the state so far
    /// (whose [`SppmSnapshot::image`] is the estimate after that pass); the run also stops
    /// after a pass for which it returns [`ControlFlow::Break`].
    pub fn render_observed(
        &self,
        scene: &Scene,
        progress: &dyn Progress,
        observe: &mut (dyn FnMut(&SppmSnapshot<'_>) -> ControlFlow<()> + Send),
    ) -> Result<SppmRendered, RenderError> {
        self.settings.validate()?;
        let start = Instant::now();
        let assignment = MapAssignment::single(scene.part_count());
        in_pool(self.settings.render.threads, || {
            let s = &self.settings;
            let r = &s.render;
            let mut options = RenderSettings {
                mode: Mode::ShadowRays,
                reject_behind: true,
                ..*r
            }
            .estimator_options(&scene.bounds());
            options.kinds = KindMask::NOT_DIRECT;
            options.validate()?;
            let mut stats = ProgressiveStats {
                threads: rayon::current_num_threads(),
                map_count: 1,
                ..ProgressiveStats::default()
            };
            progress.phase("guide");
            let emitter = Emitter::new(scene, &assignment, r, &[*scene.camera()])?;
            stats.emission = emitter.report().copied();
            let mut state = vec![PixelState::default(); r.width as usize * r.height as usize];
            stats.accumulation_bytes = (state.capacity() * size_of::<PixelState>()) as u64;
            let mut passes = 0u64;
            loop {
                if s.passes.is_some_and(|n| passes >= n) {
                    break;
                }
                self.pass(
                    scene,
                    &assignment,
                    &emitter,
                    &options,
                    passes,
                    &mut state,
                    &mut stats,
                    progress,
                )?;
                passes += 1;
                progress.pass_done(passes, stats.photons_emitted);
                stats.passes = passes;
                stats.wall = start.elapsed();
                let snapshot = SppmSnapshot {
                    state: &state,
                    width: r.width,
                    height: r.height,
                    stats: &stats,
                };
                if observe(&snapshot).is_break() {
                    break;
                }
                if s.time_budget.is_some_and(|b| start.elapsed() >= b) {
                    break;
                }
            }
            stats.passes = passes;
            stats.wall = start.elapsed();
            let image = SppmSnapshot {
                state: &state,
                width: r.width,
                height: r.height,
                stats: &stats,
            }
            .image()?;
            Ok(SppmRendered { image, stats })
        })?
    }
}

impl SppmRenderer {
    /// Pass `pass`: traces its photons into one map and updates every pixel's state from
    /// them, timing both into `stats`.
    #[allow(clippy::too_many_arguments)]
    fn pass(
        &self,
        scene: &Scene,
        assignment: &MapAssignment,
        emitter: &Emitter,
        options: &EstimatorOptions,
        pass: u64,
        state: &mut [PixelState],
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
            pass,
            stats,
            progress,
        )?;
        progress.phase("render");
        let t = Instant::now();
        let update = Pass {
            scene,
            tree: &maps.trees[0],
            options,
            settings: r,
            alpha: self.settings.alpha,
            pass,
        };
        state.par_chunks_mut(r.width as usize).enumerate().for_each_init(
            Neighbours::new,
            |neighbours, (y, row)| {
                for (x, pixel) in row.iter_mut().enumerate() {
                    update.update(x as u32, y as u32, pixel, neighbours);
                }
            },
        );
        stats.render += t.elapsed();
        Ok(())
    }
}

/// The SPPM state after a pass, as an observer of [`SppmRenderer::render_observed`] sees it.
pub struct SppmSnapshot<'a> {
    state: &'a [PixelState],
    width: u32,
    height: u32,
    stats: &'a ProgressiveStats,
}

impl SppmSnapshot<'_> {
    /// Counts and timings so far (`passes` and `total` up to date).
    pub fn stats(&self) -> &ProgressiveStats {
        self.stats
    }

    /// The radiance estimate after the passes so far: `L_direct/passes + τ/(passes · π r²)`.
    pub fn image(&self) -> Result<Image, RenderError> {
        let n = self.stats.passes.max(1) as f64;
        let pixels = self
            .state
            .iter()
            .map(|p| {
                let indirect = if p.radius > 0.0 {
                    p.tau.as_dvec3() / (n * f64::from(PI * p.radius * p.radius))
                } else {
                    DVec3::ZERO
                };
                (p.direct / n + indirect).as_vec3()
            })
            .collect();
        Image::from_pixels(self.width, self.height, pixels)
    }
}

/// One pass's photons and what the per-pixel update reads.
struct Pass<'a> {
    scene: &'a Scene,
    /// The pass's one global map.
    tree: &'a PhotonTree,
    options: &'a EstimatorOptions,
    settings: &'a RenderSettings,
    alpha: f32,
    pass: u64,
}

impl Pass<'_> {
    fn update(&self, x: u32, y: u32, pixel: &mut PixelState, neighbours: &mut Neighbours) {
        let s = self.settings;
        let scene = self.scene;
        let pixel_index = y as u64 * s.width as u64 + x as u64;
        let mut rng = Rng::for_pass(s.seed ^ PIXEL_SEED_SALT, self.pass, pixel_index);
        let at = pixel_position(s.seed, pixel_index, sample_number(self.pass, 1, 0));
        let u = (x as f32 + at.x) / s.width as f32;
        let v = (y as f32 + at.y) / s.height as f32;
        let ray = scene.camera().ray(u, v, s.width as f32 / s.height as f32);
        let mut seen = Vec3::ZERO;
        let vertex = follow_delta_bounces(scene, ray, RayKind::Camera, &mut rng, |hit, _, throughput, _| {
            if passes_through(scene.material(hit)) {
                let le = scene.emission(hit);
                if le != Vec3::ZERO {
                    seen += throughput * le;
                }
            }
        });
        if seen != Vec3::ZERO && seen.is_finite() {
            pixel.direct += seen.as_dvec3();
        }
        let Some(PathVertex {
            hit, throughput, ray, ..
        }) = vertex
        else {
            return;
        };
        // The visible point: emission and direct light by shadow rays, then the pass's photons
        // within the pixel's radius, weighted by the BSDF where it has a glossy lobe (pbrt's
        // `beta · f(wo, wi)`), read as `albedo/π` times their power where it is diffuse.
        let material = scene.material(&hit);
        let wo = -ray.direction;
        let glossy = material
            .lobes()
            .has_glossy()
            .then(|| BsdfWeight::new(material, scene.shading_point(&hit), wo));
        let albedo = scene.albedo_at(&hit);
        let direct = match &glossy {
            Some(_) => {
                let at = scene.shading_point(&hit);
                let through =
                    direct_radiance_through(scene, &hit, &at, material, wo, Mis::ShadowRaysOnly, &mut rng);
                scene.emission(&hit) + through
            }
            None => scene.emission(&hit) + albedo * FRAC_1_PI * direct_irradiance(scene, &hit, &mut rng),
        };
        let direct = throughput * direct;
        if direct.is_finite() {
            pixel.direct += direct.as_dvec3();
        }
        let tree = self.tree;
        if pixel.radius == 0.0 {
            pixel.radius = initial_radius(tree, hit.position, self.options, neighbours);
        }
        let weight: &dyn PhotonWeight = match &glossy {
            Some(w) => w,
            None => &Irradiance,
        };
        let (phi, m) = gather(
            tree,
            hit.position,
            scene.shading_normal_at(&hit),
            pixel.radius,
            self.options,
            weight,
        );
        if m > 0 {
            let m = m as f32;
            let n_new = pixel.n + self.alpha * m;
            let r_new = pixel.radius * (n_new / (pixel.n + m)).sqrt();
            let ratio = (r_new / pixel.radius).powi(2);
            let reflected = match glossy {
                Some(_) => throughput * phi,
                None => throughput * albedo * FRAC_1_PI * phi,
            };
            pixel.tau = (pixel.tau + reflected) * ratio;
            pixel.n = n_new;
            pixel.radius = r_new;
        }
    }
}

/// The k-nearest distance at `at` (capped by the maximum distance).
fn initial_radius(
    tree: &PhotonTree,
    at: Vec3,
    options: &EstimatorOptions,
    neighbours: &mut Neighbours,
) -> f32 {
    tree.nearest_k::<Euclidean>(at, options.k, options.max_distance, options.kinds, neighbours);
    let r = neighbours.extent();
    if r > 0.0 { r } else { options.max_distance }
}

/// Power (watts) times `weight`, and count, of the photons within `radius` of `at` arriving
/// from the side `normal` faces.
fn gather(
    tree: &PhotonTree,
    at: Vec3,
    normal: Vec3,
    radius: f32,
    options: &EstimatorOptions,
    weight: &dyn PhotonWeight,
) -> (Vec3, u32) {
    let mut power = Vec3::ZERO;
    let mut count = 0u32;
    tree.for_each_within::<Euclidean>(at, radius, |i, _| {
        let p = tree.get(i);
        if !options.kinds.accepts(p.kind()) {
            return;
        }
        count += 1;
        let direction = p.direction_l1();
        if direction.dot(normal) < 0.0 {
            power += p.relative_power() * weight.weight(direction);
        }
    });
    (power * tree.power_scale().watts(), count)
}
