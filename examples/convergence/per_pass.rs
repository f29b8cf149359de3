//! Figures per pass count rather than per second: the light leaked into the unlit room (the
//! progressive renderer with crease or contact maps against SPPM's one map), and the signed
//! error at the accordion's creases against inside its facets; the two tables of the study.

use super::dark_room::dark_room_pixels;
use super::methods::Progressive;
use super::report::{BiasRow, LeakRow, Study};
use photon_maps::render::glam::{Vec2, Vec3};
use photon_maps::render::progressive::{
    ProgressiveRenderer, ProgressiveSettings, SppmRenderer, SppmSettings,
};
use photon_maps::render::{EstimatorKind, Image, RenderSettings};
use photon_maps::trace::{Contact, CreaseAngle, Partitioned, Partitioner, RayKind, Scene, scenes};
use std::ops::ControlFlow;

/// The renderers of the per-pass tables: the progressive ones with the scene's leak-free
/// partition, and SPPM.
pub const METHODS: [Option<EstimatorKind>; 4] = [
    Some(EstimatorKind::Disc),
    Some(EstimatorKind::GeometryCube),
    Some(EstimatorKind::GeometryBall),
    None,
];

/// The label of a per-pass method (`None` is SPPM).
pub fn label(method: Option<EstimatorKind>) -> &'static str {
    match method {
        Some(EstimatorKind::Disc) => "progressive disc",
        Some(EstimatorKind::GeometryCube) => "progressive cube",
        Some(EstimatorKind::GeometryBall) => "progressive ball",
        None => "SPPM (one map)",
    }
}

/// Renders `scene` with `method` up to the largest of `counts` passes and hands the image
/// after each of `counts` to `measure`.
pub fn at_pass_counts(
    method: Option<EstimatorKind>,
    partitioned: &Partitioned,
    base: RenderSettings,
    progressive: Progressive,
    counts: &[u64],
    measure: &mut (dyn FnMut(u64, &Image) + Send),
) -> Result<(), String> {
    let last = counts.iter().copied().max().unwrap_or(1);
    match method {
        Some(estimator) => {
            let render = RenderSettings {
                mode: progressive.direct,
                k: progressive.k,
                ..base
            };
            let settings = ProgressiveSettings {
                alpha: progressive.alpha,
                ..ProgressiveSettings::new(render, last)
            };
            ProgressiveRenderer::new(estimator, settings)
                .render_observed(partitioned, &(), &mut |sum, stats| {
                    if counts.contains(&stats.passes) {
                        measure(stats.passes, &sum.mean());
                    }
                    ControlFlow::Continue(())
                })
                .map_err(|e| e.to_string())?;
        }
        None => {
            let mut failure = None;
            SppmRenderer::new(SppmSettings::new(base, last))
                .render_observed(partitioned.scene(), &(), &mut |snapshot| {
                    let passes = snapshot.stats().passes;
                    if counts.contains(&passes) {
                        match snapshot.image() {
                            Ok(image) => measure(passes, &image),
                            Err(e) => failure = Some(e.to_string()),
                        }
                    }
                    ControlFlow::Continue(())
                })
                .map_err(|e| e.to_string())?;
            if let Some(e) = failure {
                return Err(e);
            }
        }
    }
    Ok(())
}

fn luminance(c: Vec3) -> f64 {
    f64::from(0.2126 * c.x + 0.7152 * c.y + 0.0722 * c.z)
}

/// The two-room scenes' pixels: the dark room's (every sample inside it) and the lit room's
/// (pixel centre's first hit at x < 1 m).
pub struct Rooms {
    dark: Vec<usize>,
    lit: Vec<usize>,
}

impl Rooms {
    /// Classifies a `width × height` image of `scene`.
    pub fn new(scene: &Scene, width: u32, height: u32) -> Self {
        let camera = scene.camera();
        let aspect = width as f32 / height as f32;
        let lit = (0..width * height)
            .filter(|&i| {
                let (x, y) = ((i % width) as f32 + 0.5, (i / width) as f32 + 0.5);
                let ray = camera.ray(x / width as f32, y / height as f32, aspect);
                scene
                    .intersect(&ray, f32::INFINITY, RayKind::Camera)
                    .is_some_and(|h| h.position.x < 1.0 - 1e-3)
            })
            .map(|i| i as usize)
            .collect();
        Rooms {
            dark: dark_room_pixels(scene, width, height),
            lit,
        }
    }

    /// The brightest dark-room pixel's luminance (the truth is exactly 0) and the dark room's
    /// mean luminance over the lit room's.
    pub fn leak(&self, image: &Image) -> (f64, f64) {
        let px = image.pixels();
        let max = self.dark.iter().map(|&i| luminance(px[i])).fold(0.0, f64::max);
        let mean =
            |set: &[usize]| set.iter().map(|&i| luminance(px[i])).sum::<f64>() / set.len().max(1) as f64;
        (max, mean(&self.dark) / mean(&self.lit))
    }
}

/// The accordion's facets are 0.25 m wide at ±45°, folds at x = i·STEP along z (pm-trace's
/// accordion scene, checked against its bounds in [`Creases::new`]).
const STEP: f32 = 0.25 * std::f32::consts::FRAC_1_SQRT_2;
const FACETS: usize = 8;

/// The accordion's pixels near an interior crease and well inside a facet.
pub struct Creases {
    crease: Vec<usize>,
    interior: Vec<usize>,
}

impl Creases {
    /// Pixels whose centre's first hit lies within `band` metres of an interior fold (crease),
    /// or farther than 0.1 m from every fold and from the strip's border (interior).
    pub fn new(scene: &Scene, width: u32, height: u32, band: f32) -> Result<Self, String> {
        let bounds = scene.bounds();
        let expected = FACETS as f32 * STEP;
        if ((bounds.max.x - bounds.min.x) - expected).abs() > 0.05 * expected {
            return Err("the accordion's size changed: update STEP and FACETS".into());
        }
        let fold = |i: usize| Vec2::new(i as f32 * STEP, if i.is_multiple_of(2) { 0.0 } else { STEP });
        let camera = scene.camera();
        let aspect = width as f32 / height as f32;
        let (mut crease, mut interior) = (Vec::new(), Vec::new());
        for i in 0..(width * height) as usize {
            let (x, y) = (
                (i % width as usize) as f32 + 0.5,
                (i / width as usize) as f32 + 0.5,
            );
            let ray = camera.ray(x / width as f32, y / height as f32, aspect);
            let Some(hit) = scene.intersect(&ray, f32::INFINITY, RayKind::Camera) else {
                continue;
            };
            let p = hit.position;
            let xy = Vec2::new(p.x, p.y);
            let to_crease = (1..FACETS)
                .map(|f| xy.distance(fold(f)))
                .fold(f32::INFINITY, f32::min);
            let to_border = xy
                .distance(fold(0))
                .min(xy.distance(fold(FACETS)))
                .min(p.z - bounds.min.z)
                .min(bounds.max.z - p.z);
            if to_crease < band {
                crease.push(i);
            } else if to_crease > 0.1 && to_border > 0.1 {
                interior.push(i);
            }
        }
        Ok(Creases { crease, interior })
    }

    /// Signed relative error (Σ(estimate − truth)/Σ truth, luminance) at the creases and
    /// inside the facets.
    pub fn bias(&self, image: &Image, reference: &Image) -> (f64, f64) {
        let bias = |set: &[usize]| {
            let (mut d, mut t) = (0.0, 0.0);
            for &i in set {
                let truth = luminance(reference.pixels()[i]);
                d += luminance(image.pixels()[i]) - truth;
                t += truth;
            }
            d / t.max(f64::MIN_POSITIVE)
        };
        (bias(&self.crease), bias(&self.interior))
    }
}

/// The leak table (lit-unlit-rooms with crease maps, touching-rooms with contact maps) and
/// the accordion's crease table (against `reference`, the accordion's), at `counts` passes,
/// into `study`.
pub fn tables(
    base: RenderSettings,
    progressive: Progressive,
    counts: &[u64],
    reference: &Image,
    study: &mut Study,
) -> Result<(), String> {
    let size = base.width;
    for (name, partitioner) in [
        (
            "lit-unlit-rooms",
            Box::new(CreaseAngle::default()) as Box<dyn Partitioner>,
        ),
        ("touching-rooms", Box::new(Contact::default())),
    ] {
        let partitioned = partitioner
            .partition(scenes::build(name).map_err(|e| e.to_string())?)
            .map_err(|e| e.to_string())?;
        let rooms = Rooms::new(partitioned.scene(), size, size);
        for method in METHODS {
            at_pass_counts(
                method,
                &partitioned,
                base,
                progressive,
                counts,
                &mut |passes, image| {
                    let (max, ratio) = rooms.leak(image);
                    study.leaks.push(LeakRow {
                        scene: name.to_owned(),
                        method: label(method).to_owned(),
                        passes,
                        dark_max: max,
                        ratio,
                    });
                },
            )?;
        }
        eprintln!("{name}: leaks measured");
    }
    let accordion = scenes::build("accordion").map_err(|e| e.to_string())?;
    let creases = Creases::new(&accordion, size, size, 0.03)?;
    let accordion = CreaseAngle::default()
        .partition(accordion)
        .map_err(|e| e.to_string())?;
    for method in METHODS {
        at_pass_counts(
            method,
            &accordion,
            base,
            progressive,
            counts,
            &mut |passes, image| {
                let (crease, interior) = creases.bias(image, reference);
                study.creases.push(BiasRow {
                    method: label(method).to_owned(),
                    passes,
                    crease,
                    interior,
                });
            },
        )?;
    }
    eprintln!("accordion: crease bias measured");
    Ok(())
}
