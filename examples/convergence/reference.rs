//! The path-traced reference of each scene: two independent halves, their mean the reference
//! and their difference its own noise; cached as EXR files so that later runs of the study
//! reuse them, and extendable: a later run asked for more seconds renders further batches
//! (new seeds) into the same two halves. Where the `results` example has rendered a reference
//! of the same scene at a whole multiple of the size (500×500 for 125×125) and nothing is
//! cached, that one is box-filtered down instead.

use photon_maps::render::glam::DVec3;
use photon_maps::render::image::{read_text_file, write_atomically};
use photon_maps::render::{EstimatorKind, Image, Mode, RenderSettings, Renderer};
use photon_maps::trace::{Partitioner, Scene, SingleMap};
use std::io::Write as _;
use std::path::Path;
use std::time::Instant;

/// The reference's pixel streams start here, far from any seed the study renders with; batch
/// `b` renders with seed `REFERENCE_SEED + b`.
const REFERENCE_SEED: u64 = 1 << 40;

/// A reference's note (its samples per pixel and how it was made: a line or two) larger
/// than this is refused before it is read.
const MAX_NOTE_BYTES: u64 = 64 << 10;

/// A long reference render is written out this often (seconds).
const CHECKPOINT_SECONDS: f64 = 120.0;

/// Samples per pixel of one batch.
const BATCH_SPP: u32 = 4;

/// What the cache's text file says of a reference path traced here (and so extendable).
const PATH_TRACED: &str = "path traced by the convergence example in batches of 4 samples per pixel, batch b with seed 2^40 + b, even batches in the first half";

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

/// How long to render a reference.
#[derive(Clone, Copy, Debug)]
pub struct Budget {
    /// Seconds of path tracing when nothing is cached.
    pub seconds: f64,
    /// Seconds to add to a cached reference path traced here (0: use it as it is).
    pub extend: f64,
}

/// The reference for `scene` (named `name`) at `base`'s size, read from `cache` when a file
/// for this scene and size is there (and extended by `budget.extend` seconds when that one
/// was path traced here); otherwise box-filtered down from a `results` reference in `larger`
/// (files `{name}-{W}x{H}-{spp}-v2.exr` and `…-v2-half.exr`, `W` and `H` the same whole
/// multiple of the size), or else path traced for `budget.seconds`; written to `cache`.
pub fn reference(
    name: &str,
    scene: &Scene,
    base: RenderSettings,
    budget: Budget,
    (cache, larger): (&Path, &Path),
) -> Result<Reference, String> {
    let files = Files::new(cache, name, base.width, base.height);
    if let Ok((cached, text)) = files.read() {
        let spp = cached.spp;
        let batches = spp / u64::from(BATCH_SPP);
        if budget.extend <= 0.0 {
            return Ok(cached);
        }
        if !text.contains(PATH_TRACED) || batches % 2 == 1 || batches == 0 {
            return Err(format!(
                "{}: not a reference this example path traced, so it cannot be extended",
                files.meta.display()
            ));
        }
        // Back to the halves' sums of batch means: A = 2·sum_A/n, M = (sum_A + sum_B)/n.
        let n = batches as f64;
        let sums = [
            cached
                .half
                .pixels()
                .iter()
                .map(|a| a.as_dvec3() * (n / 2.0))
                .collect(),
            cached
                .image
                .pixels()
                .iter()
                .zip(cached.half.pixels())
                .map(|(m, a)| m.as_dvec3() * n - a.as_dvec3() * (n / 2.0))
                .collect(),
        ];
        return path_trace(scene, base, budget.extend, (sums, batches), &files);
    }
    if let Some((image, first, spp)) = downsampled(name, base.width, base.height, larger)? {
        let reference = Reference {
            image,
            spp,
            half: first,
        };
        files.write(
            &reference,
            "box-filtered from the results example's larger reference",
        )?;
        return Ok(reference);
    }
    let zero = vec![DVec3::ZERO; (base.width * base.height) as usize];
    path_trace(scene, base, budget.seconds, ([zero.clone(), zero], 0), &files)
}

/// The reference for scene `name` at `width × height` as cached in `cache`, neither extended
/// nor made anew (an error naming the file that is missing or unreadable).
pub fn cached(name: &str, width: u32, height: u32, cache: &Path) -> Result<Reference, String> {
    let files = Files::new(cache, name, width, height);
    let (reference, _) = files.read()?;
    for (image, path) in [(&reference.image, &files.exr), (&reference.half, &files.half)] {
        if (image.width(), image.height()) != (width, height) {
            return Err(format!("{}: not {width}×{height} pixels", path.display()));
        }
    }
    Ok(reference)
}

/// The cache's three files for one scene and size.
struct Files {
    exr: std::path::PathBuf,
    half: std::path::PathBuf,
    meta: std::path::PathBuf,
}

impl Files {
    fn new(cache: &Path, name: &str, width: u32, height: u32) -> Self {
        let stem = cache.join(format!("{name}-{width}x{height}"));
        Files {
            exr: stem.with_extension("exr"),
            half: stem.with_extension("half.exr"),
            meta: stem.with_extension("txt"),
        }
    }

    /// The cached reference and its note, or what is missing or unreadable.
    fn read(&self) -> Result<(Reference, String), String> {
        let exr = |path: &Path| Image::read_exr(path).map_err(|e| format!("{}: {e}", path.display()));
        let (image, half) = (exr(&self.exr)?, exr(&self.half)?);
        let text = read_text_file(&self.meta, MAX_NOTE_BYTES).map_err(|e| e.to_string())?;
        let spp = text
            .split_whitespace()
            .next()
            .and_then(|t| t.parse::<u64>().ok())
            .ok_or_else(|| {
                format!(
                    "{}: does not begin with the samples per pixel",
                    self.meta.display()
                )
            })?;
        Ok((Reference { image, spp, half }, text))
    }

    fn write(&self, reference: &Reference, how: &str) -> Result<(), String> {
        if let Some(dir) = self.exr.parent() {
            std::fs::create_dir_all(dir).map_err(|e| format!("{}: {e}", dir.display()))?;
        }
        reference.image.write_exr(&self.exr).map_err(|e| e.to_string())?;
        reference.half.write_exr(&self.half).map_err(|e| e.to_string())?;
        write_atomically(&self.meta, |w| {
            writeln!(w, "{} samples per pixel, {how}", reference.spp)
        })
        .map_err(|e| format!("{}: {e}", self.meta.display()))
    }
}

/// Path traces batches from `start` on for `seconds` (and to an even count), adding batch `b`
/// to half `b mod 2` of `sums`, then writes and returns the reference.
fn path_trace(
    scene: &Scene,
    base: RenderSettings,
    seconds: f64,
    (mut halves, start): ([Vec<DVec3>; 2], u64),
    files: &Files,
) -> Result<Reference, String> {
    let partitioned = SingleMap.partition(scene.clone()).map_err(|e| e.to_string())?;
    let clock = Instant::now();
    let mut saved = Instant::now();
    let mut batches = start;
    let finish = |halves: &[Vec<DVec3>; 2], batches: u64| -> Result<Reference, String> {
        let mean_of = |sum: &[DVec3], n: f64| sum.iter().map(|s| (*s / n).as_vec3()).collect::<Vec<_>>();
        let first = Image::from_pixels(base.width, base.height, mean_of(&halves[0], (batches / 2) as f64))
            .map_err(|e| e.to_string())?;
        let total: Vec<DVec3> = halves[0].iter().zip(&halves[1]).map(|(a, b)| *a + *b).collect();
        let image = Image::from_pixels(base.width, base.height, mean_of(&total, batches as f64))
            .map_err(|e| e.to_string())?;
        let reference = Reference {
            image,
            spp: batches * u64::from(BATCH_SPP),
            half: first,
        };
        files.write(&reference, PATH_TRACED)?;
        Ok(reference)
    };
    // Batches alternate between the halves; stop on an even count so that they are equal.
    while batches < start + 2 || batches % 2 == 1 || clock.elapsed().as_secs_f64() < seconds {
        // Long renders are saved every few minutes, so that stopping one loses little.
        if batches % 2 == 0 && batches > start && saved.elapsed().as_secs_f64() > CHECKPOINT_SECONDS {
            finish(&halves, batches)?;
            saved = Instant::now();
        }
        let settings = RenderSettings {
            mode: Mode::PathTrace,
            samples_per_pixel: BATCH_SPP,
            seed: REFERENCE_SEED + batches,
            ..base
        };
        let image = Renderer::new(EstimatorKind::Disc, settings)
            .render(&partitioned, &())
            .map_err(|e| e.to_string())?
            .image;
        for (s, p) in halves[(batches % 2) as usize].iter_mut().zip(image.pixels()) {
            *s += p.as_dvec3();
        }
        batches += 1;
    }
    finish(&halves, batches)
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
