//! `--frames N --orbit DEGREES`: a short fly-through rendered from one photon cache. The maps
//! (and the final gather's irradiance cache) are built once, or loaded with `--load-cache`;
//! each frame renders with `Renderer::render_from_cache` after `Partitioned::with_camera`.
//! Frame i turns the scene's camera by i × DEGREES / N about the vertical (+y) axis through the
//! scene's bounds centre, so frame 0 is the scene's own camera and `--orbit 360` loops.

use super::files::{NamedFile, check_outputs, load_scene, say, scene_dependencies, scene_inputs};
use super::report::{Record, Setup, contacts_json, contacts_summary, json_number, json_object, summary};
use super::{Args, TileBar, Variant, cache, default_out};
use photon_maps::render::glam::{Quat, Vec3};
use photon_maps::render::image::write_atomically;
use photon_maps::render::{EstimatorKind, RenderSettings, Renderer};
use photon_maps::trace::Camera;
use std::io::Write as _;
use std::path::{Path, PathBuf};

/// The most frames one run renders.
pub const MAX_FRAMES: u32 = 10_000;

/// Refuses what a fly-through cannot honour, before anything is loaded.
fn check(args: &Args, frames: u32, orbit: f64) -> Result<(), String> {
    if args.compare {
        return Err("--compare renders four variants of one view; --frames renders one variant from several views: drop one".into());
    }
    if frames == 0 || frames > MAX_FRAMES {
        return Err(format!("--frames {frames}: give 1 to {MAX_FRAMES} frames"));
    }
    if !orbit.is_finite() || orbit.abs() > 360.0 {
        return Err(format!(
            "--orbit {orbit}: give the degrees the camera turns over all frames, -360 to 360"
        ));
    }
    Ok(())
}

/// The turn of frame `i` of `frames`, degrees: `i × orbit / frames`.
pub fn frame_degrees(i: u32, frames: u32, orbit: f64) -> f64 {
    orbit * f64::from(i) / f64::from(frames)
}

/// `camera` turned by `degrees` about the vertical axis through `centre` (its view direction
/// and up turned with it); exactly `camera` for a turn of zero.
pub fn orbit_camera(camera: &Camera, centre: Vec3, degrees: f64) -> Camera {
    if degrees == 0.0 {
        return *camera;
    }
    let turn = Quat::from_rotation_y(degrees.to_radians() as f32);
    let position = centre + turn * (camera.position() - centre);
    Camera::new(
        position,
        position + turn * camera.forward(),
        turn * camera.up(),
        camera.vfov(),
    )
}

/// Frame `i`'s image paths beside `base`: `<stem>-<i>.exr` and `.png`, `i` zero-padded to the
/// width of the last frame's number.
fn frame_paths(base: &Path, i: u32, frames: u32) -> (PathBuf, PathBuf) {
    let stem = base.file_stem().and_then(|s| s.to_str()).unwrap_or("frame");
    let width = (frames - 1).to_string().len();
    let name = base.with_file_name(format!("{stem}-{i:0width$}"));
    (name.with_extension("exr"), name.with_extension("png"))
}

/// Renders the fly-through; `frames` and `orbit` as given.
pub fn run(args: &Args, settings: RenderSettings, estimator: EstimatorKind) -> Result<(), String> {
    let (frames, orbit) = match (args.frames, args.orbit) {
        (Some(frames), Some(orbit)) => (frames, orbit),
        (Some(_), None) => {
            return Err(
                "--frames needs --orbit DEGREES (the turn over all frames; 0 keeps the scene's camera)"
                    .into(),
            );
        }
        (None, _) => return Err("--orbit needs --frames N (the number of frames of the fly-through)".into()),
    };
    check(args, frames, orbit)?;
    let scene_name = super::files::scene_name(&args.scene);
    let base = args.out.clone().unwrap_or_else(|| default_out(&scene_name));
    if base.is_dir() {
        return Err(format!(
            "--out {} is a folder; name a file (its frames' .exr and .png are written beside it)",
            base.display()
        ));
    }
    // Every output checked against the others and the inputs before the scene is read.
    let dependencies = scene_dependencies(&args.scene);
    let mut inputs = scene_inputs(&args.scene, &dependencies);
    inputs.extend(args.load_cache.as_deref().map(|path| NamedFile {
        option: "--load-cache",
        path,
    }));
    let paths: Vec<(PathBuf, PathBuf)> = (0..frames).map(|i| frame_paths(&base, i, frames)).collect();
    let mut outputs = Vec::new();
    for (exr, png) in &paths {
        outputs.push(NamedFile {
            option: "a frame's EXR",
            path: exr,
        });
        outputs.push(NamedFile {
            option: "a frame's PNG",
            path: png,
        });
    }
    outputs.extend(args.stats_json.as_deref().map(|path| NamedFile {
        option: "--stats-json",
        path,
    }));
    outputs.extend(args.save_cache.as_deref().map(|path| NamedFile {
        option: "--save-cache",
        path,
    }));
    check_outputs(&outputs, &inputs)?;

    let mut timer = photon_maps::geom::StepTimer::start();
    let (scene, _) = load_scene(&args.scene, args.light_units.into())?;
    let load = timer.lap();
    let origin_offset = scene.origin_offset().to_array();
    let variant = Variant {
        label: "fly-through",
        maps: args.maps(),
        estimator,
    };
    let mut partitioned = variant
        .maps
        .partitioner(args.contact_gap)?
        .partition(scene)
        .map_err(crate::choices::partition_message)?;
    let before_render = Setup {
        load,
        partition: Some(timer.lap()),
    };
    let contacts = (
        contacts_summary(partitioned.record()),
        contacts_json(partitioned.record()),
    );
    let renderer = Renderer::new(estimator, settings);
    let bar = TileBar::new("fly-through set-up");
    let camera = *partitioned.scene().camera();
    let centre = partitioned.scene().bounds().center();
    // Camera-driven emission learns what every frame sees.
    let cameras: Vec<Camera> = (0..frames)
        .map(|i| orbit_camera(&camera, centre, frame_degrees(i, frames, orbit)))
        .collect();
    let (cache, setup, cache_use) = cache::obtain_cache(args, &renderer, &partitioned, &cameras, &bar)?;
    let setup_seconds = match &cache_use {
        Some(used) if used.what == "loaded" => used.seconds,
        _ => (setup.trace + setup.build + setup.precompute).as_secs_f64(),
    };
    let mut first = None;
    let mut cache_use = cache_use;
    let (mut frame_json, mut render_total) = (Vec::new(), 0.0);
    for (i, (exr, png)) in (0..frames).zip(&paths) {
        let degrees = frame_degrees(i, frames, orbit);
        partitioned = partitioned
            .with_camera(orbit_camera(&camera, centre, degrees))
            .map_err(|e| format!("frame {i} (orbit {degrees}°): {e}"))?;
        let mut stats = setup.clone();
        bar.0.set_message(format!("frame {i}"));
        let image = renderer
            .render_from_cache(partitioned.scene(), &cache, &bar, &mut stats)
            .map_err(|e| e.to_string())?;
        image.write_exr(exr).map_err(|e| e.to_string())?;
        image.write_png(png, args.exposure()).map_err(|e| e.to_string())?;
        let (seconds, mean) = (stats.render.as_secs_f64(), image.mean().to_array());
        render_total += seconds;
        if first.is_none() {
            // Frame 0's figures in full: the set-up (trace, build, precompute or the load) and
            // its render.
            let record = Record {
                args,
                scene: &scene_name,
                variant: &variant,
                settings: &settings,
                stats,
                mean,
                contacts: contacts.clone(),
                origin_offset,
                cache: cache_use.take(),
                setup: before_render,
            };
            say(&summary(&record));
            first = Some(json_object(&record));
        }
        say(&format!(
            "frame {i} (orbit {degrees:.3}°): render {seconds:.3} s, mean rgb ({:.4}, {:.4}, {:.4}); wrote {} and {}",
            mean[0],
            mean[1],
            mean[2],
            exr.display(),
            png.display()
        ));
        frame_json.push(format!(
            "{{\"frame\": {i}, \"orbit_degrees\": {}, \"render_seconds\": {}, \"mean_rgb\": [{}, {}, {}]}}",
            json_number(degrees),
            json_number(seconds),
            json_number(f64::from(mean[0])),
            json_number(f64::from(mean[1])),
            json_number(f64::from(mean[2])),
        ));
    }
    bar.0.finish_and_clear();
    let per_frame = render_total / f64::from(frames);
    say(&format!(
        "fly-through: {frames} frames from one photon cache, set-up {setup_seconds:.3} s once ({}), render {per_frame:.3} s per frame",
        match &args.load_cache {
            Some(_) => "cache file loaded",
            None => "trace, build and precompute",
        }
    ));
    if let Some(path) = &args.stats_json {
        let text = format!(
            "{{\"setup\": {}, \"setup_seconds\": {}, \"render_seconds_per_frame\": {}, \"frames\": [\n{}\n]}}\n",
            first.unwrap_or_default(),
            json_number(setup_seconds),
            json_number(per_frame),
            frame_json.join(",\n")
        );
        write_atomically(path, |w| w.write_all(text.as_bytes()))
            .map_err(|e| format!("{}: {e}", path.display()))?;
        say(&format!("wrote {}", path.display()));
    }
    Ok(())
}
