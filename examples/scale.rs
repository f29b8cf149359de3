//! How cost grows with the work: times per phase and peak heap memory as the triangle count
//! grows (the rooms with every face split N × N, 24 → 240k triangles; a field of separate
//! cubes) and as the photon count grows (the Cornell box, 10⁴ → 10⁷ photons). Prints markdown
//! tables (the "How cost grows" section of `docs/results.md` is this output).
//!
//! `cargo run --release --example scale` (about a minute on 2 cores; `--quick` for a smaller
//! sweep).

use clap::Parser;
use photon_maps::render::{EstimatorKind, Mode, RenderSettings, Renderer};
use photon_maps::trace::{CreaseAngle, Partitioner, Scene, scenes};
use std::time::Instant;

use tracking_allocator::{peak, reset_peak};

#[path = "../tests/support/tracking_allocator.rs"]
mod tracking_allocator;

fn mib(bytes: usize) -> f64 {
    bytes as f64 / (1024.0 * 1024.0)
}

/// One row of the triangle sweep.
fn triangle_row(name: &str) -> Result<String, String> {
    let base = reset_peak();
    let start = Instant::now();
    let scene = scenes::build(name).map_err(|e| e.to_string())?;
    let build_scene = start.elapsed().as_secs_f64();
    let scene_peak = peak() - base;
    let triangles = triangle_count(&scene);
    let scene_bytes = scene.heap_bytes();
    let settings = RenderSettings {
        width: 128,
        height: 128,
        photons: 1_000_000,
        ..RenderSettings::default()
    };
    let crease = CreaseAngle::default()
        .partition(scene)
        .map_err(|e| e.to_string())?;
    reset_peak();
    let cube = Renderer::new(EstimatorKind::GeometryCube, settings)
        .render(&crease, &())
        .map_err(|e| e.to_string())?;
    let render_peak = peak() - base;
    let disc = Renderer::new(EstimatorKind::Disc, settings)
        .render(&crease, &())
        .map_err(|e| e.to_string())?;
    let path_traced = Renderer::new(
        EstimatorKind::Disc,
        RenderSettings {
            mode: Mode::PathTrace,
            samples_per_pixel: 16,
            ..settings
        },
    )
    .render(&crease, &())
    .map_err(|e| e.to_string())?;
    let s = &cube.stats;
    Ok(format!(
        "| {name} | {triangles} | {build_scene:.3} | {:.0} | {:.2} | {:.3} | {:.3} | {:.3} | {:.2} | {:.3} | {:.1} | {:.1} |",
        scene_bytes as f64 / triangles as f64,
        s.photons_emitted as f64 / s.trace.as_secs_f64() / 1e6,
        s.trace.as_secs_f64(),
        s.build.as_secs_f64(),
        s.render.as_secs_f64(),
        s.render.as_secs_f64() / disc.stats.render.as_secs_f64(),
        path_traced.stats.render.as_secs_f64(),
        mib(scene_peak),
        mib(render_peak),
    ))
}

/// One row of the photon sweep.
fn photon_row(photons: u32) -> Result<String, String> {
    let scene = scenes::build("cornell-box").map_err(|e| e.to_string())?;
    let settings = RenderSettings {
        width: 128,
        height: 128,
        photons,
        ..RenderSettings::default()
    };
    let crease = CreaseAngle::default()
        .partition(scene)
        .map_err(|e| e.to_string())?;
    let base = reset_peak();
    let out = Renderer::new(EstimatorKind::GeometryCube, settings)
        .render(&crease, &())
        .map_err(|e| e.to_string())?;
    let peak = peak() - base;
    let s = &out.stats;
    let mean = out.image.mean();
    Ok(format!(
        "| {photons} | {} | {:.3} | {:.2} | {:.3} | {:.3} | {:.1} | {:.0} | ({:.4}, {:.4}, {:.4}) | {} |",
        s.photons_stored,
        s.trace.as_secs_f64(),
        s.photons_emitted as f64 / s.trace.as_secs_f64() / 1e6,
        s.build.as_secs_f64(),
        s.render.as_secs_f64(),
        mib(peak),
        peak as f64 / s.photons_stored.max(1) as f64,
        mean.x,
        mean.y,
        mean.z,
        s.photon_channels_below_range,
    ))
}

/// How each phase's time and the heap grow with triangles and photons: prints Markdown
/// tables (about a minute on 2 cores); writes nothing.
#[derive(Parser, Debug)]
struct Args {
    /// A smaller sweep: split rooms up to N = 30 (21,600 triangles), 1,000 cubes, up to 10⁶ photons.
    #[arg(long)]
    quick: bool,
}

fn triangle_count(scene: &Scene) -> usize {
    scene
        .meshes()
        .iter()
        .map(|m| {
            let mesh = m.half_edge_mesh();
            mesh.faces()
                .map(|f| mesh.face_vertices(f).len() - 2)
                .sum::<usize>()
        })
        .sum()
}

fn main() -> Result<(), String> {
    let quick = Args::parse().quick;
    let threads = rayon::current_num_threads();
    println!("Measured with `cargo run --release --example scale` on {threads} threads.\n");
    println!(
        "Triangles: crease maps, 1,000,000 photons, 128×128. Scene bytes are what the built scene holds \
         (`Scene::heap_bytes`); peaks are heap bytes at the highest point while building the scene, \
         and while tracing, building maps and rendering with the cube estimator. \
         Path traced: 16 samples per pixel, render phase.\n"
    );
    println!(
        "| scene | triangles | scene build s | scene B/triangle | trace M paths/s | trace s | map build s | cube render s | cube / disc render | path-traced render s | scene peak MiB | render peak MiB |"
    );
    println!("|---|---|---|---|---|---|---|---|---|---|---|---|");
    let splits: &[u32] = if quick { &[1, 10, 30] } else { &[1, 10, 30, 100] };
    for n in splits {
        println!("{}", triangle_row(&format!("split-rooms-{n}"))?);
    }
    let cubes: &[u32] = if quick { &[1_000] } else { &[1_000, 10_000] };
    for n in cubes {
        println!("{}", triangle_row(&format!("cube-field-{n}"))?);
    }
    println!(
        "\nPhotons: the Cornell box, crease maps, cube estimator (k = 100), 128×128. The peak is \
         the heap's highest point during the render (photons traced in full precision, then \
         encoded into the maps); per stored photon.\n"
    );
    println!(
        "| photons | stored | trace s | trace M paths/s | map build s | render s | peak MiB | peak B/stored photon | mean RGB | channels below range |"
    );
    println!("|---|---|---|---|---|---|---|---|---|---|");
    let counts: &[u32] = if quick {
        &[10_000, 100_000, 1_000_000]
    } else {
        &[10_000, 100_000, 1_000_000, 10_000_000]
    };
    for &n in counts {
        println!("{}", photon_row(n)?);
    }
    Ok(())
}
