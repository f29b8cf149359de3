//! The path-traced reference of each scene: two independent halves rendered for a wall-time
//! budget, their mean the reference and their difference its own noise; cached as EXR files
//! so that later runs of the study reuse them. Where the `results` example has rendered a
//! reference of the same scene at a whole multiple of the size (500×500 for 125×125), that one
//! is box-filtered down instead: the same two halves, many more samples per pixel.

use photon_maps::render::glam::DVec3;
use photon_maps::render::image::write_atomically;
use photon_maps::render::{EstimatorKind, Image, Mode, RenderSettings, Renderer};
use photon_maps::trace::{Scene, SingleMap};
use std::io::Write as _;
use std::path::Path;
use std::time::Instant;

/// The reference's pixel streams start here, far from any seed the study renders with.
const REFERENCE_SEED: u64 = 1 << 40;

/// A reference image and how good it is.
pub struct Reference {
    pub image: Image,
    /// Samples per pixel in all.
    pub spp: u64,
    /// The mean of its first half alone: with independent halves A and B of equal size,
    /// each of noise σ, the mean M = (A + B)/2 has noise σ/√2, and A − M = (A − B)/2 has RMS
    /// σ/√2 too, so the error of this half against the reference is the reference's own.
    pub half: Image,
}

/// The reference for `scene` (named `name`) at `base`'s size, read from `cache` when a file
/// for this scene and size is there; otherwise box-filtered down from a `results` reference in
/// `larger` (files `{name}-{W}x{H}-{spp}-v2.exr` and `…-v2-half.exr`, `W` and `H` the same
/// whole multiple of the size), or else path traced for `seconds`; written to `cache`.
pub fn reference(
    name: &str,
    scene: &Scene,
    base: RenderSettings,
    seconds: f64,
    (cache, larger): (&Path, &Path),
) -> Result<Reference, String> {
    let stem = cache.join(format!("{name}-{}x{}", base.width, base.height));
    let (exr, half, meta) = (
        stem.with_extension("exr"),
        stem.with_extension("half.exr"),
        stem.with_extension("txt"),
    );
    if let (Ok(image), Ok(first), Ok(text)) = (
        Image::read_exr(&exr),
        Image::read_exr(&half),
        std::fs::read_to_string(&meta),
    ) && let Some(spp) = text.split_whitespace().next().and_then(|t| t.parse().ok())
    {
        return Ok(Reference {
            image,
            spp,
            half: first,
        });
    }
    if let Some((image, first, spp)) = downsampled(name, base.width, base.height, larger)? {
        std::fs::create_dir_all(cache).map_err(|e| format!("{}: {e}", cache.display()))?;
        image.write_exr(&exr).map_err(|e| e.to_string())?;
        first.write_exr(&half).map_err(|e| e.to_string())?;
        write_atomically(&meta, |w| writeln!(w, "{spp} samples per pixel"))
            .map_err(|e| format!("{}: {e}", meta.display()))?;
        return Ok(Reference {
            image,
            spp,
            half: first,
        });
    }
    let start = Instant::now();
    let mut halves = [
        vec![DVec3::ZERO; (base.width * base.height) as usize],
        vec![DVec3::ZERO; (base.width * base.height) as usize],
    ];
    let mut batches = 0u64;
    let batch_spp = 4u32;
    // Batches alternate between the halves; stop on an even count so that they are equal.
    while batches < 2 || batches % 2 == 1 || start.elapsed().as_secs_f64() < seconds {
        let settings = RenderSettings {
            mode: Mode::PathTrace,
            samples_per_pixel: batch_spp,
            seed: REFERENCE_SEED + batches,
            ..base
        };
        let image = Renderer::new(EstimatorKind::Disc, settings)
            .render(scene, &SingleMap, &())
            .map_err(|e| e.to_string())?
            .image;
        for (s, p) in halves[(batches % 2) as usize].iter_mut().zip(image.pixels()) {
            *s += p.as_dvec3();
        }
        batches += 1;
    }
    let mean_of = |sum: &[DVec3], n: f64| sum.iter().map(|s| (*s / n).as_vec3()).collect::<Vec<_>>();
    let first = Image::from_pixels(base.width, base.height, mean_of(&halves[0], (batches / 2) as f64))
        .map_err(|e| e.to_string())?;
    let total: Vec<DVec3> = halves[0].iter().zip(&halves[1]).map(|(a, b)| *a + *b).collect();
    let image = Image::from_pixels(base.width, base.height, mean_of(&total, batches as f64))
        .map_err(|e| e.to_string())?;
    let spp = batches * u64::from(batch_spp);
    std::fs::create_dir_all(cache).map_err(|e| format!("{}: {e}", cache.display()))?;
    image.write_exr(&exr).map_err(|e| e.to_string())?;
    first.write_exr(&half).map_err(|e| e.to_string())?;
    write_atomically(&meta, |w| writeln!(w, "{spp} samples per pixel"))
        .map_err(|e| format!("{}: {e}", meta.display()))?;
    Ok(Reference {
        image,
        spp,
        half: first,
    })
}

/// A `results` reference of scene `name` in `dir` whose size is a whole multiple `f` ≥ 2 of
/// `width × height`, with its half, each averaged over `f × f` blocks (a box filter: a pixel
/// of the small image is the mean of the large pixels that tile it, as a render at the small
/// size with jittered samples estimates it), and the samples per small pixel (`spp · f²`).
fn downsampled(
    name: &str,
    width: u32,
    height: u32,
    dir: &Path,
) -> Result<Option<(Image, Image, u64)>, String> {
    let Ok(entries) = std::fs::read_dir(dir) else {
        return Ok(None);
    };
    for entry in entries.flatten() {
        let file = entry.file_name().to_string_lossy().into_owned();
        let Some(rest) = file
            .strip_prefix(&format!("{name}-"))
            .and_then(|r| r.strip_suffix("-v2.exr"))
        else {
            continue;
        };
        // `{W}x{H}-{spp}`
        let Some((size, spp)) = rest.split_once('-') else {
            continue;
        };
        let Some((w, h)) = size.split_once('x') else {
            continue;
        };
        let (Ok(w), Ok(h), Ok(spp)) = (w.parse::<u32>(), h.parse::<u32>(), spp.parse::<u64>()) else {
            continue;
        };
        let f = w / width;
        if f < 2 || w != f * width || h != f * height {
            continue;
        }
        let half_path = dir.join(format!("{name}-{size}-{spp}-v2-half.exr"));
        let read = |p: &Path| Image::read_exr(p).map_err(|e| format!("{}: {e}", p.display()));
        let (full, half) = (read(&entry.path())?, read(&half_path)?);
        let down = |large: &Image| {
            Image::from_fn(width, height, |x, y| {
                let mut sum = DVec3::ZERO;
                for j in 0..f {
                    for i in 0..f {
                        sum += large.get(x * f + i, y * f + j).unwrap_or_default().as_dvec3();
                    }
                }
                (sum / f64::from(f * f)).as_vec3()
            })
            .map_err(|e| e.to_string())
        };
        return Ok(Some((down(&full)?, down(&half)?, spp * u64::from(f * f))));
    }
    Ok(None)
}
