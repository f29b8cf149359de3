//! The path-traced reference of each scene: rendered once as two half-sample images with
//! independent seeds (their difference is its own noise) and cached.

use super::*;

/// Part of every cached reference's file name: bump it when a built-in scene or the path
/// tracer changes, so that no result is measured against a stale reference (v2: independent,
/// hashed random streams).
pub const REFERENCE_VERSION: &str = "v2";

/// Loads the cached reference, or renders it as two half-sample images with independent seeds
/// (their difference gives the reference's own noise) and caches both.
pub fn reference(spec: &SceneSpec, scene: &Scene, config: &Config) -> Result<Reference, String> {
    let spp = ((spec.reference_spp as f32 * config.ref_spp_scale).round() as u32 / 2).max(1) * 2;
    let stem = format!(
        "{}-{}x{}-{spp}-{REFERENCE_VERSION}",
        spec.name, config.width, config.height
    );
    let full_path = config.cache_dir.join(format!("{stem}.exr"));
    let half_path = config.cache_dir.join(format!("{stem}-half.exr"));
    if let (Ok(full), Ok(half)) = (Image::read_exr(&full_path), Image::read_exr(&half_path)) {
        println!(
            "{}: reference {} (cached; delete it, or bump REFERENCE_VERSION, after changing a scene or the path tracer)",
            spec.name,
            full_path.display()
        );
        return Ok(Reference {
            image: full,
            half,
            spp,
            sigma: f32::NAN,
            seconds: None,
        });
    }
    let partitioned = SingleMap.partition(scene.clone()).map_err(|e| e.to_string())?;
    let start = Instant::now();
    let render_half = |seed| {
        Renderer::new(
            EstimatorKind::Disc,
            settings(config, Mode::PathTrace, spp / 2, seed),
        )
        .render(&partitioned, &())
        .map(|out| out.image)
        .map_err(|e| e.to_string())
    };
    let a = render_half(1001)?;
    let b = render_half(2002)?;
    let full = Image::from_fn(a.width(), a.height(), |x, y| {
        0.5 * (a.get(x, y).unwrap_or_default() + b.get(x, y).unwrap_or_default())
    })
    .map_err(|e| e.to_string())?;
    let seconds = start.elapsed().as_secs_f64();
    full.write_exr(&full_path).map_err(|e| e.to_string())?;
    a.write_exr(&half_path).map_err(|e| e.to_string())?;
    println!(
        "{}: reference {} ({spp} spp, {seconds:.0} s)",
        spec.name,
        full_path.display()
    );
    Ok(Reference {
        image: full,
        half: a,
        spp,
        sigma: f32::NAN,
        seconds: Some(seconds),
    })
}
