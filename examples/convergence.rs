//! Equal-time convergence: relative RMSE against a path-traced reference versus wall time for
//! the progressive renderer (cube + crease maps; photons for all light, or shadow rays for
//! direct light as SPPM has it) and the SPPM baseline (one global map), on
//! the report's four scenes. Prints a Markdown table.
//!
//! `cargo run --release --example convergence -- --size 96 --budgets 0.5,1,2,4,8`

use clap::Parser;
use photon_maps::render::progressive::{
    ProgressiveRenderer, ProgressiveSettings, SppmRenderer, SppmSettings,
};
use photon_maps::render::{EstimatorKind, Image, Mode, RenderSettings, Renderer};
use photon_maps::trace::{CreaseAngle, scenes};
use std::time::{Duration, Instant};

/// Equal-time comparison of progressive photon mapping (cube + crease) with SPPM.
#[derive(Parser, Debug)]
struct Args {
    /// Image side in pixels (square images).
    #[arg(long, default_value_t = 96)]
    size: u32,
    /// Photon paths per pass, for both renderers.
    #[arg(long, default_value_t = 50_000)]
    photons: u32,
    /// Wall-time budgets in seconds, comma-separated.
    #[arg(long, default_value = "0.5,1,2,4,8")]
    budgets: String,
    /// Path-traced reference samples per pixel.
    #[arg(long, default_value_t = 2048)]
    reference_spp: u32,
    /// Scenes, comma-separated.
    #[arg(long, default_value = "cornell-box,lit-unlit-rooms,colored-rooms,accordion")]
    scenes: String,
}

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let args = Args::parse();
    let budgets: Vec<f64> = args
        .budgets
        .split(',')
        .map(|b| b.trim().parse())
        .collect::<Result<_, _>>()?;
    let base = RenderSettings {
        width: args.size,
        height: args.size,
        photons: args.photons,
        mode: Mode::Visualize,
        seed: 1,
        ..RenderSettings::default()
    };
    println!(
        "| scene | budget (s) | progressive passes | progressive rel. RMSE | progressive + shadow rays passes | rel. RMSE | SPPM passes | SPPM rel. RMSE | SPPM / progressive | SPPM / progressive + shadow rays |"
    );
    println!("|---|---|---|---|---|---|---|---|---|---|");
    for name in args.scenes.split(',') {
        let scene = scenes::build(name.trim())?;
        let start = Instant::now();
        let reference: Image = Renderer::new(
            EstimatorKind::Disc,
            RenderSettings {
                mode: Mode::PathTrace,
                samples_per_pixel: args.reference_spp,
                seed: 1234,
                ..base
            },
        )
        .render(&scene, &CreaseAngle::default(), &())?
        .image;
        eprintln!("{name}: reference in {:.1} s", start.elapsed().as_secs_f64());
        for &budget in &budgets {
            let time = Some(Duration::from_secs_f64(budget));
            let progressive = |mode| {
                ProgressiveRenderer::new(
                    EstimatorKind::GeometryCube,
                    ProgressiveSettings {
                        passes: None,
                        time_budget: time,
                        ..ProgressiveSettings::new(RenderSettings { mode, ..base }, 1)
                    },
                )
                .render(&scene, &CreaseAngle::default(), &())
            };
            let visualize = progressive(Mode::Visualize)?;
            let shadow = progressive(Mode::ShadowRays)?;
            let sppm = SppmRenderer::new(SppmSettings {
                passes: None,
                time_budget: time,
                ..SppmSettings::new(base, 1)
            })
            .render(&scene, &())?;
            let p = visualize.accumulation.mean().relative_rmse(&reference)?;
            let q = shadow.accumulation.mean().relative_rmse(&reference)?;
            let s = sppm.image.relative_rmse(&reference)?;
            println!(
                "| {name} | {budget} | {} | {p:.4} | {} | {q:.4} | {} | {s:.4} | {:.2} | {:.2} |",
                visualize.stats.passes,
                shadow.stats.passes,
                sppm.stats.passes,
                s / p,
                s / q
            );
        }
    }
    Ok(())
}
