//! Shards: the exact sums of a contiguous range of progressive passes with what they belong to
//! (the scene, the settings), so that shards rendered apart merge into the bits one run of all
//! their passes gives — or are refused, naming the shard at fault.

use crate::error::RenderError;
use crate::image::Image;
use crate::limits::MAX_PASS;
use crate::progressive::accumulation::{Accumulation, ProgressiveRendered};
use crate::progressive::pass_sum::PassSums;
use glam::DVec3;
use std::ops::Range;
use thiserror::Error;

/// Why shards cannot be merged or read.
#[derive(Debug, Error)]
#[non_exhaustive]
pub enum ShardError {
    /// Nothing to merge.
    #[error("no shards to merge")]
    Empty,
    /// A shard of no passes.
    #[error("a shard must hold at least one pass")]
    NoPasses,
    /// A pass range that runs past the last pass ([`MAX_PASS`]) or wraps past `u64::MAX`.
    #[error("{shard}: passes from {first_pass} ({passes} of them) run past the last pass, {max}", max = MAX_PASS)]
    BadPassRange {
        /// The shard (its file, or its place in the list).
        shard: String,
        /// Its first pass.
        first_pass: u64,
        /// Its pass count.
        passes: u64,
    },
    /// A path that is not a regular file (a folder, a FIFO, a device).
    #[error("{path}: not a regular file; a shard is an EXR file")]
    NotAFile {
        /// The path.
        path: String,
    },
    /// An EXR file without the shard header attribute or sum channels.
    #[error("{path}: not a progressive shard (no valid '{attribute}' in it)")]
    NotAShard {
        /// The file.
        path: String,
        /// The missing or unreadable attribute or channel.
        attribute: &'static str,
    },
    /// A pixel that is NaN or infinite, or whose mean is.
    #[error("{shard}: pixel ({x}, {y}) is not finite")]
    NonFinite {
        /// The shard (its file, or its place in the list).
        shard: String,
        /// Column.
        x: u32,
        /// Row.
        y: u32,
    },
    /// One shard given twice.
    #[error("{shard} is given twice")]
    Duplicate {
        /// The shard.
        shard: String,
    },
    /// Shards of different scenes.
    #[error("shards of different scenes: '{a}' and '{b}'")]
    SceneMismatch {
        /// One scene identity.
        a: String,
        /// The other.
        b: String,
    },
    /// Shards rendered with different settings.
    #[error("shards with different settings: '{a}' and '{b}'")]
    SettingsMismatch {
        /// One settings identity.
        a: String,
        /// The other.
        b: String,
    },
    /// Shards of different image sizes.
    #[error("shards of different sizes: {a:?} and {b:?}")]
    SizeMismatch {
        /// One size (width, height).
        a: (u32, u32),
        /// The other.
        b: (u32, u32),
    },
    /// Two shards hold the same pass.
    #[error("shards overlap: {a_shard} holds passes {a:?} and {b_shard} passes {b:?}")]
    Overlap {
        /// One shard.
        a_shard: String,
        /// Its pass range.
        a: Range<u64>,
        /// The other shard.
        b_shard: String,
        /// Its pass range.
        b: Range<u64>,
    },
    /// The shards leave passes out: no single run gives their merge.
    #[error("shards leave passes {missing:?} out")]
    Gap {
        /// The passes missing between two shards.
        missing: Range<u64>,
    },
    /// Reading or writing the image.
    #[error(transparent)]
    Image(#[from] RenderError),
}

/// What a shard says about itself, checked before any of its pixels are read.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct ShardHeader {
    /// The shard's name in messages: its file, or its place in a list.
    pub name: String,
    /// Its first pass.
    pub first_pass: u64,
    /// Its pass count (at least 1).
    pub passes: u64,
    /// The scene identity.
    pub scene: String,
    /// The settings identity.
    pub settings: String,
    /// Image width.
    pub width: u32,
    /// Image height.
    pub height: u32,
}

impl ShardHeader {
    /// The passes it holds, refused when empty or running past [`MAX_PASS`].
    pub fn pass_range(&self) -> Result<Range<u64>, ShardError> {
        if self.passes == 0 {
            return Err(ShardError::NoPasses);
        }
        let bad = || ShardError::BadPassRange {
            shard: self.name.clone(),
            first_pass: self.first_pass,
            passes: self.passes,
        };
        let last = self.first_pass.checked_add(self.passes - 1).ok_or_else(bad)?;
        if last > MAX_PASS {
            return Err(bad());
        }
        Ok(self.first_pass..last + 1)
    }
}

/// Checks that shards can merge (one scene, one settings, one size, pass ranges that neither
/// overlap, repeat nor leave a gap) and returns their indices in pass order and the merged
/// header.
pub fn plan_merge(headers: &[ShardHeader]) -> Result<(Vec<usize>, ShardHeader), ShardError> {
    let first = headers.first().ok_or(ShardError::Empty)?;
    let size = |h: &ShardHeader| (h.width, h.height);
    for h in headers {
        h.pass_range()?;
        if h.scene != first.scene {
            return Err(ShardError::SceneMismatch {
                a: first.scene.clone(),
                b: h.scene.clone(),
            });
        }
        if h.settings != first.settings {
            return Err(ShardError::SettingsMismatch {
                a: first.settings.clone(),
                b: h.settings.clone(),
            });
        }
        if size(h) != size(first) {
            return Err(ShardError::SizeMismatch {
                a: size(first),
                b: size(h),
            });
        }
    }
    let mut order: Vec<usize> = (0..headers.len()).collect();
    order.sort_by_key(|&i| (headers[i].first_pass, headers[i].passes));
    let range = |i: usize| headers[i].pass_range();
    // Every overlap before any gap: a shard given twice is named as such, not as a gap
    // between the others.
    for pair in order.windows(2) {
        let (a, b) = (&headers[pair[0]], &headers[pair[1]]);
        let (ra, rb) = (range(pair[0])?, range(pair[1])?);
        if rb.start < ra.end {
            if a.name == b.name {
                return Err(ShardError::Duplicate {
                    shard: a.name.clone(),
                });
            }
            return Err(ShardError::Overlap {
                a_shard: a.name.clone(),
                a: ra,
                b_shard: b.name.clone(),
                b: rb,
            });
        }
    }
    let mut passes = 0u64;
    for pair in order.windows(2) {
        let (ra, rb) = (range(pair[0])?, range(pair[1])?);
        if rb.start > ra.end {
            return Err(ShardError::Gap {
                missing: ra.end..rb.start,
            });
        }
    }
    for &i in &order {
        // Contiguous ranges below u64::MAX cannot overflow; checked all the same.
        passes = passes
            .checked_add(headers[i].passes)
            .ok_or(ShardError::BadPassRange {
                shard: headers[i].name.clone(),
                first_pass: headers[i].first_pass,
                passes: headers[i].passes,
            })?;
    }
    let merged = ShardHeader {
        name: "the merge".into(),
        first_pass: headers[order[0]].first_pass,
        passes,
        ..first.clone()
    };
    merged.pass_range()?;
    Ok((order, merged))
}

/// Refuses a shard's sums that are not finite or whose mean is not (f32 overflow), naming
/// the first such pixel.
pub(crate) fn check_finite(name: &str, sums: &PassSums, passes: u64) -> Result<(), ShardError> {
    let (hi, lo) = sums.parts();
    let n = passes.max(1) as f64;
    for (i, (h, l)) in hi.iter().zip(lo).enumerate() {
        if !h.is_finite() || !l.is_finite() || !(*h / n).as_vec3().is_finite() {
            let w = sums.width() as usize;
            return Err(ShardError::NonFinite {
                shard: name.to_owned(),
                x: (i % w) as u32,
                y: (i / w) as u32,
            });
        }
    }
    Ok(())
}

/// The exact sums of passes `first_pass .. first_pass + passes` of a progressive render, with
/// the identities of its scene and settings.
#[derive(Clone, Debug, PartialEq)]
pub struct Shard {
    sums: PassSums,
    first_pass: u64,
    passes: u64,
    scene: String,
    settings: String,
}

/// Keeps identities to characters an EXR text attribute holds (Latin-1, no control
/// characters: the header separates its fields by line), so that a shard reads back as
/// written.
fn latin1(text: &str) -> String {
    text.chars()
        .map(|c| {
            if (c as u32) < 0x100 && !c.is_control() {
                c
            } else {
                '?'
            }
        })
        .collect()
}

impl Shard {
    /// The shard of a progressive run's sums, exact: shards made this way merge into the bits
    /// of one run. `scene` and `settings` identify what was rendered (characters outside
    /// Latin-1 become `?`).
    pub fn from_accumulation(
        accumulation: &Accumulation,
        scene: &str,
        settings: &str,
    ) -> Result<Self, ShardError> {
        Self::from_sums(
            accumulation.sums().clone(),
            accumulation.pass_range().start,
            accumulation.passes(),
            scene,
            settings,
        )
    }

    /// A shard from the mean of `passes` passes from `first_pass`: its sums are the mean times
    /// the pass count, rounded, so a merge of such shards is within rounding of one run (use
    /// [`Shard::from_accumulation`] for the exact sums).
    pub fn new(
        mean: Image,
        first_pass: u64,
        passes: u64,
        scene: &str,
        settings: &str,
    ) -> Result<Self, ShardError> {
        let n = passes as f64;
        let hi: Vec<DVec3> = mean.pixels().iter().map(|p| p.as_dvec3() * n).collect();
        let lo = vec![DVec3::ZERO; hi.len()];
        let sums = PassSums::from_parts(mean.width(), mean.height(), hi, lo)?;
        Self::from_sums(sums, first_pass, passes, scene, settings)
    }

    /// A shard of these sums, its pass range and finiteness checked.
    pub(crate) fn from_sums(
        sums: PassSums,
        first_pass: u64,
        passes: u64,
        scene: &str,
        settings: &str,
    ) -> Result<Self, ShardError> {
        let shard = Shard {
            sums,
            first_pass,
            passes,
            scene: latin1(scene),
            settings: latin1(settings),
        };
        shard.header("the shard").pass_range()?;
        check_finite("the shard", &shard.sums, passes)?;
        Ok(shard)
    }

    /// What the shard says about itself, under `name` in messages.
    pub fn header(&self, name: &str) -> ShardHeader {
        ShardHeader {
            name: name.to_owned(),
            first_pass: self.first_pass,
            passes: self.passes,
            scene: self.scene.clone(),
            settings: self.settings.clone(),
            width: self.sums.width(),
            height: self.sums.height(),
        }
    }

    /// The mean of the shard's passes (computed from the exact sums).
    pub fn mean(&self) -> Image {
        self.sums.mean(self.passes)
    }

    /// The exact per-pixel sums of its passes.
    pub fn sums(&self) -> &PassSums {
        &self.sums
    }

    /// The passes it holds.
    pub fn pass_range(&self) -> Range<u64> {
        self.first_pass..self.first_pass + self.passes
    }

    /// Number of passes.
    pub fn passes(&self) -> u64 {
        self.passes
    }

    /// The scene identity.
    pub fn scene(&self) -> &str {
        &self.scene
    }

    /// The settings identity.
    pub fn settings(&self) -> &str {
        &self.settings
    }

    /// The shard one run of all the shards' passes gives: their exact sums added, so its mean
    /// has the bits of one run's when every shard came from [`Shard::from_accumulation`]
    /// (exact while each pixel's sum spans at most 106 significant bits: pass values within a
    /// ratio of about 2⁵⁰ over up to 2³⁰ passes; see [`PassSums`]).
    /// Refuses shards of different scenes, settings or sizes, a shard given twice,
    /// overlapping pass ranges and ranges that leave a gap (shards are named by their place
    /// in the list, from 1).
    pub fn merge(shards: &[Shard]) -> Result<Shard, ShardError> {
        let headers: Vec<ShardHeader> = shards
            .iter()
            .enumerate()
            .map(|(i, s)| s.header(&format!("shard {}", i + 1)))
            .collect();
        let (order, merged) = plan_merge(&headers)?;
        let mut sums = PassSums::new(merged.width, merged.height)?;
        for i in order {
            sums.add_sums(&shards[i].sums)?;
        }
        Self::from_sums(
            sums,
            merged.first_pass,
            merged.passes,
            &merged.scene,
            &merged.settings,
        )
    }
}

impl ProgressiveRendered {
    /// The exact shard of this run's passes, for `scene` (a name or fingerprint of the scene
    /// file; the settings, estimator and partition come from [`ProgressiveRendered::identity`]).
    pub fn shard(&self, scene: &str) -> Result<Shard, ShardError> {
        Shard::from_accumulation(&self.accumulation, scene, &self.identity)
    }
}
