//! A path tracer of its own that reads the library's photon cache for its second bounce: the
//! cache is built by `Renderer::build_photon_cache` (final-gather mode), then this program's own
//! loop (camera rays, shadow rays, cosine-sampled gather rays) asks
//! `RadianceCache::radiance_at` at each gather ray's diffuse hit. It prints its image's mean
//! against the built-in final gather's on the same settings and cache. `--view` draws debug
//! views of the cache instead: its points, their distances, the photon maps.
//!
//! `cargo run --release --example cache_query -- --scene cornell-box --out target/cq.png`

use clap::{Parser, ValueEnum};
use photon_maps::render::glam::Vec3;
use photon_maps::render::{
    EstimatorKind, FinalGatherOptions, Image, Mode, RenderSettings, RenderStats, Renderer,
};
use photon_maps::trace::{Contact, Partitioner, Scene, scenes};
use std::path::{Path, PathBuf};
use std::process::ExitCode;

#[path = "cache_query/tracer.rs"]
mod tracer;
#[path = "cache_query/views.rs"]
mod views;

use tracer::{CacheTracer, Shot};
use views::{View, render_view};

/// Renders with a path tracer of its own that reads the library's photon cache.
#[derive(Parser, Debug)]
#[command(version, about)]
struct Args {
    /// A built-in scene (cornell-box, lit-unlit-rooms, ...) or a .gltf/.glb file.
    #[arg(long, default_value = "cornell-box")]
    scene: String,
    /// Photon paths traced into the cache.
    #[arg(long, default_value_t = 200_000)]
    photons: u32,
    /// Image size, WIDTHxHEIGHT.
    #[arg(long, default_value = "128x128", value_parser = parse_size)]
    size: (u32, u32),
    /// Camera samples per pixel.
    #[arg(long, default_value_t = 16)]
    spp: u32,
    /// Gather rays per camera sample.
    #[arg(long, default_value_t = 4)]
    gather_rays: u32,
    /// Seed of the photons (and of both renders' random streams).
    #[arg(long, default_value_t = 1)]
    seed: u64,
    /// What to draw: the image (and the comparison with the built-in final gather), or a
    /// debug view of the cache.
    #[arg(long, value_enum, default_value = "render")]
    view: ViewChoice,
    /// The points view's splat radius as a share of the scene's bounding-box diagonal.
    #[arg(long, default_value_t = 0.002)]
    splat: f32,
    /// Output image (.png or .exr) [default: target/cache_query-VIEW.png].
    #[arg(long)]
    out: Option<PathBuf>,
}

/// The `--view` choices.
#[derive(Clone, Copy, Debug, PartialEq, Eq, ValueEnum)]
enum ViewChoice {
    /// The image, rendered by this program's own loop, and its mean against the built-in.
    Render,
    /// The cache points, splatted.
    Points,
    /// The distance from each pixel's hit to the cache point that answers there.
    Radii,
    /// The photon map of each pixel's hit, a colour per map.
    Maps,
}

fn parse_size(s: &str) -> Result<(u32, u32), String> {
    let (w, h) = s.split_once('x').ok_or("expected WIDTHxHEIGHT")?;
    let parse = |v: &str| v.parse::<u32>().map_err(|e| format!("{v}: {e}"));
    Ok((parse(w)?, parse(h)?))
}

fn main() -> ExitCode {
    match run(Args::parse()) {
        Ok(()) => ExitCode::SUCCESS,
        Err(e) => {
            eprintln!("error: {e}");
            ExitCode::FAILURE
        }
    }
}

fn load_scene(arg: &str) -> Result<Scene, String> {
    let lower = arg.to_ascii_lowercase();
    if lower.ends_with(".gltf") || lower.ends_with(".glb") {
        return photon_maps::trace::gltf::load_scene(Path::new(arg)).map_err(|e| e.to_string());
    }
    scenes::build(arg).map_err(|e| e.to_string())
}

fn run(args: Args) -> Result<(), String> {
    let scene = load_scene(&args.scene)?;
    let partitioned = Contact::default().partition(scene).map_err(|e| e.to_string())?;
    let scene = partitioned.scene();
    let (width, height) = args.size;
    let settings = RenderSettings {
        width,
        height,
        samples_per_pixel: args.spp,
        photons: args.photons,
        seed: args.seed,
        mode: Mode::FinalGather,
        final_gather: FinalGatherOptions {
            gather_rays: args.gather_rays,
            ..FinalGatherOptions::default()
        },
        ..RenderSettings::default()
    };
    let renderer = Renderer::new(EstimatorKind::GeometryCube, settings);
    let mut stats = RenderStats::default();
    let photons = renderer
        .build_photon_cache(&partitioned, &(), &mut stats)
        .map_err(|e| e.to_string())?;
    let cache = photons
        .radiance
        .as_ref()
        .ok_or("the final gather built no irradiance cache")?;
    println!(
        "cache: {} maps, {} points, lookup within {:.4} m",
        cache.map_count(),
        cache.len(),
        cache.max_distance()
    );
    let view = match args.view {
        ViewChoice::Render => None,
        ViewChoice::Points => Some(View::Points),
        ViewChoice::Radii => Some(View::Radii),
        ViewChoice::Maps => Some(View::Maps),
    };
    let out = args
        .out
        .clone()
        .unwrap_or_else(|| PathBuf::from(format!("target/cache_query-{:?}.png", args.view).to_lowercase()));
    let image = match view {
        Some(view) => {
            let splat = args.splat * scene.bounds().diagonal();
            let (image, median) =
                render_view(scene, cache, view, args.size, splat).map_err(|e| e.to_string())?;
            println!(
                "{view:?} view; median distance to the answering cache point {median:.4} m, splat {splat:.4} m"
            );
            image
        }
        None => {
            let tracer = CacheTracer {
                scene,
                maps: &photons.maps,
                cache,
                estimator: renderer.estimator(),
                options: settings.estimator_options(&scene.bounds()),
                gather_rays: args.gather_rays,
                corner: settings.final_gather.corner_distance_in(&scene.bounds()),
            };
            let shot = Shot {
                width,
                height,
                samples: args.spp,
                seed: args.seed,
            };
            let own = tracer.render(shot).map_err(|e| e.to_string())?;
            let builtin = renderer
                .render_from_cache(scene, &photons, &(), &mut stats)
                .map_err(|e| e.to_string())?;
            report_means(&own, &builtin);
            own
        }
    };
    write(&image, &out)?;
    println!("wrote {}", out.display());
    Ok(())
}

/// Prints both images' means and their relative difference per channel.
fn report_means(own: &Image, builtin: &Image) {
    let (a, b) = (own.mean(), builtin.mean());
    let rel = (a - b) / b.max(Vec3::splat(f32::MIN_POSITIVE));
    println!(
        "mean, own tracer reading radiance_at: {:.5} {:.5} {:.5}",
        a.x, a.y, a.z
    );
    println!(
        "mean, built-in final gather:          {:.5} {:.5} {:.5}",
        b.x, b.y, b.z
    );
    println!(
        "difference: {:+.2} % {:+.2} % {:+.2} % (one render each; tests/cache_query.rs compares over seeds)",
        100.0 * rel.x,
        100.0 * rel.y,
        100.0 * rel.z
    );
}

/// Writes `image` as PNG or EXR by the extension of `path`, creating `target/` for the default.
fn write(image: &Image, path: &Path) -> Result<(), String> {
    // Only the default folder is created: a folder the user names must exist.
    if path.parent() == Some(Path::new("target")) {
        std::fs::create_dir_all("target").map_err(|e| e.to_string())?;
    }
    let ext = path
        .extension()
        .and_then(|e| e.to_str())
        .map(str::to_ascii_lowercase);
    match ext.as_deref() {
        Some("png") => image.write_png(path, 0.0).map_err(|e| e.to_string()),
        Some("exr") => image.write_exr(path).map_err(|e| e.to_string()),
        _ => Err(format!("{}: expected a .png or .exr file", path.display())),
    }
}
