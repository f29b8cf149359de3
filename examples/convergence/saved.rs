//! A study kept for re-scoring: `--save-run DIR` writes what the study measured
//! (`study.json`) and, per scene and method, the image each budget's error was read from
//! (`<scene>/<method>-<passes>.exr`: the last pass that ended within the budget); `--rescore
//! DIR` reads them back, measures those images against the references as they are now (say,
//! after `--extend-references`) and writes the Markdown and charts again, rendering nothing.

use super::mask::Mask;
use super::methods::Sample;
use super::report::{SceneResult, Study};
use super::{chart, reference, study_scene};
use photon_maps::render::Image;
use photon_maps::render::image::{read_text_file, write_atomically};
use photon_maps::trace::scenes;
use std::io::Write as _;
use std::path::{Path, PathBuf};

/// The record's file name in the folder.
const RECORD: &str = "study.json";

/// A record larger than this is refused before it is read (a full study's is about 1 MB).
const MAX_RECORD_BYTES: u64 = 256 << 20;

/// Keeps, during one run, the image of every pass that is the last to end within one of the
/// budgets: a pass's image waits until the next pass says when that one ended.
pub struct Keeper<'a> {
    /// Files go to `{dir}/{prefix}{passes}.exr`.
    dir: PathBuf,
    prefix: String,
    budgets: &'a [f64],
    pending: Option<(Sample, Image)>,
}

impl<'a> Keeper<'a> {
    /// Keeps the images of scene `scene`'s run of method `method` under `root`.
    pub fn new(root: &Path, scene: &str, method: &str, budgets: &'a [f64]) -> Result<Self, String> {
        let dir = root.join(scene);
        std::fs::create_dir_all(&dir).map_err(|e| format!("{}: {e}", dir.display()))?;
        Ok(Keeper {
            dir,
            prefix: format!("{method}-"),
            budgets,
            pending: None,
        })
    }

    /// The pass that produced `image` ended as `sample` says; writes the one before it when
    /// a budget falls between the two.
    pub fn push(&mut self, sample: Sample, image: Image) -> Result<(), String> {
        if let Some((before, kept)) = self.pending.take()
            && self
                .budgets
                .iter()
                .any(|&b| before.seconds <= b && b < sample.seconds)
        {
            self.write(&before, &kept)?;
        }
        self.pending = Some((sample, image));
        Ok(())
    }

    /// The run has ended: writes its last pass when a budget lies at or past its end.
    pub fn finish(mut self) -> Result<(), String> {
        match self.pending.take() {
            Some((last, image)) if self.budgets.iter().any(|&b| last.seconds <= b) => {
                self.write(&last, &image)
            }
            _ => Ok(()),
        }
    }

    fn write(&self, sample: &Sample, image: &Image) -> Result<(), String> {
        let path = self.dir.join(format!("{}{}.exr", self.prefix, sample.passes));
        image
            .write_exr(&path)
            .map_err(|e| format!("{}: {e}", path.display()))
    }
}

/// Writes the study's record into `dir` (atomically).
pub fn save(dir: &Path, study: &Study) -> Result<(), String> {
    let path = dir.join(RECORD);
    let text = serde_json::to_string(study).map_err(|e| format!("{}: {e}", path.display()))?;
    write_atomically(&path, |w| w.write_all(text.as_bytes())).map_err(|e| format!("{}: {e}", path.display()))
}

/// Where `--rescore` reads and writes.
pub struct Rescore<'a> {
    /// The folder `--save-run` wrote.
    pub record: &'a Path,
    /// The references to measure against.
    pub references: &'a Path,
    /// Where the Markdown and the charts go.
    pub out_dir: &'a Path,
    /// Whether the charts can be drawn (a font was registered).
    pub charts: bool,
}

/// Re-measures the kept run against the current references and writes the study again.
pub fn rescore(to: &Rescore<'_>) -> Result<(), String> {
    let path = to.record.join(RECORD);
    // The record is read as every input is: a regular file within its bound, checked before it
    // is opened (a FIFO or /dev/zero is refused, never read).
    let text = read_text_file(&path, MAX_RECORD_BYTES).map_err(|e| e.to_string())?;
    let mut study: Study = serde_json::from_str(&text).map_err(|e| format!("{}: {e}", path.display()))?;
    // Every name the record gives becomes part of a path: each must be a built-in scene's, or
    // a glTF source's plain file stem, before anything is opened (an absolute name would reach
    // outside the folders).
    if let Some(scene) = study.scenes.iter().find(|s| !is_safe_name(s)) {
        return Err(format!(
            "{}: scene {:?} is neither a built-in scene ({}) nor the plain file stem of its glTF source",
            path.display(),
            scene.name,
            scenes::NAMES.join(", ")
        ));
    }
    let images = to.out_dir.join("images");
    std::fs::create_dir_all(&images).map_err(|e| format!("{}: {e}", images.display()))?;
    let mut before = Vec::new();
    for scene in &mut study.scenes {
        // The reference first: its files bound the size the record claims.
        let reference = reference::cached(&scene.name, study.size, study.size, to.references)?;
        let (built, _) = study_scene::load(scene.source.as_deref().unwrap_or(&scene.name))?;
        let mask = if study.all_pixels {
            Mask::all(study.size, study.size)
        } else {
            Mask::new(&built, study.size, study.size)
        };
        let noise = mask.relative_rmse(&reference.half, &reference.image);
        for run in &mut scene.runs {
            // The pass each budget's error is read from (the last that ended within it),
            // each measured once however many budgets share it.
            let mut kept: Vec<usize> = study
                .budgets
                .iter()
                .filter_map(|&b| run.samples.iter().rposition(|s| s.seconds <= b))
                .collect();
            kept.sort_unstable();
            kept.dedup();
            for i in kept {
                let sample = &mut run.samples[i];
                let file =
                    to.record
                        .join(&scene.name)
                        .join(format!("{}-{}.exr", run.method.name(), sample.passes));
                let image = Image::read_exr(&file).map_err(|e| format!("{}: {e}", file.display()))?;
                if (image.width(), image.height()) != (study.size, study.size) {
                    return Err(format!("{}: not {s}×{s} pixels", file.display(), s = study.size));
                }
                let measured = mask.relative_rmse(&image, &reference.image);
                sample.rel_rmse = (measured * measured - noise * noise).max(0.0).sqrt();
            }
        }
        before.push(format!(
            "{} samples per pixel on {}",
            scene.reference_spp, scene.name
        ));
        scene.reference_spp = reference.spp;
        scene.reference_noise = noise;
        if to.charts && scene.chart.is_some() {
            let axis = chart::seconds_axis(&study.clock, study.threads);
            let png = images.join(format!("convergence-{}.png", scene.name));
            chart::draw(&png, &scene.name, &scene.runs, noise, &axis)?;
        }
    }
    study.rescored = Some(format!(
        "Re-scored by `cargo run --release --example convergence -- --rescore {} --reference-dir {}`: the errors at the budgets are those of the images the run kept, measured again against the references below (the run had measured them against {}; the charts' points between budgets keep those first errors, and the tables per pass count are the run's as it measured them).",
        to.record.display(),
        to.references.display(),
        before.join(", ")
    ));
    super::report::write(&to.out_dir.join("convergence.md"), &study)
}

/// True when `scene`'s name may become part of a path: a built-in scene's name, or the stem of
/// its glTF source made of letters, digits, `-` and `_` only.
fn is_safe_name(scene: &SceneResult) -> bool {
    let name = scene.name.as_str();
    match &scene.source {
        None => scenes::NAMES.contains(&name),
        Some(source) => {
            Path::new(source).file_stem().and_then(|s| s.to_str()) == Some(name)
                && !name.is_empty()
                && name
                    .chars()
                    .all(|c| c.is_ascii_alphanumeric() || c == '-' || c == '_')
        }
    }
}
