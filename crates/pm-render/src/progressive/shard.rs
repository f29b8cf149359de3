//! Shards: the mean of a contiguous range of progressive passes with what it belongs to (the
//! scene, the settings), so that shards rendered apart merge into the image one run of all
//! their passes gives — or are refused.

use crate::{Image, RenderError};
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
    /// An EXR file without the shard header attributes.
    #[error("{path}: not a progressive shard (no '{attribute}' attribute in its header)")]
    NotAShard {
        /// The file.
        path: String,
        /// The missing or unreadable attribute.
        attribute: &'static str,
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
    #[error("shards overlap: passes {a:?} and {b:?}")]
    Overlap {
        /// One pass range.
        a: Range<u64>,
        /// The other.
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

/// The mean of passes `first_pass .. first_pass + passes` of a progressive render, with the
/// identities of its scene and settings.
#[derive(Clone, Debug, PartialEq)]
pub struct Shard {
    mean: Image,
    first_pass: u64,
    passes: u64,
    scene: String,
    settings: String,
}

/// Keeps identities to characters an EXR text attribute holds (Latin-1), so that a shard
/// reads back as written.
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
    /// A shard of `passes` passes from `first_pass` whose mean is `mean`; `scene` and
    /// `settings` identify what was rendered (characters outside Latin-1 become `?`).
    pub fn new(
        mean: Image,
        first_pass: u64,
        passes: u64,
        scene: &str,
        settings: &str,
    ) -> Result<Self, ShardError> {
        if passes == 0 {
            return Err(ShardError::NoPasses);
        }
        Ok(Shard {
            mean,
            first_pass,
            passes,
            scene: latin1(scene),
            settings: latin1(settings),
        })
    }

    /// The mean of the shard's passes.
    pub fn mean(&self) -> &Image {
        &self.mean
    }

    /// The passes it holds.
    pub fn pass_range(&self) -> Range<u64> {
        self.first_pass..self.first_pass.saturating_add(self.passes)
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

    /// The shard one run of all the shards' passes gives: the pass-weighted mean (summed in
    /// f64, so it differs from the single run by rounding only). Refuses shards of different
    /// scenes, settings or sizes, overlapping pass ranges, and ranges that leave a gap.
    pub fn merge(shards: &[Shard]) -> Result<Shard, ShardError> {
        let first = shards.first().ok_or(ShardError::Empty)?;
        let size = |s: &Shard| (s.mean.width(), s.mean.height());
        for s in shards {
            if s.scene != first.scene {
                return Err(ShardError::SceneMismatch {
                    a: first.scene.clone(),
                    b: s.scene.clone(),
                });
            }
            if s.settings != first.settings {
                return Err(ShardError::SettingsMismatch {
                    a: first.settings.clone(),
                    b: s.settings.clone(),
                });
            }
            if size(s) != size(first) {
                return Err(ShardError::SizeMismatch {
                    a: size(first),
                    b: size(s),
                });
            }
        }
        let mut order: Vec<&Shard> = shards.iter().collect();
        order.sort_by_key(|s| s.first_pass);
        for pair in order.windows(2) {
            let (a, b) = (pair[0].pass_range(), pair[1].pass_range());
            if b.start < a.end {
                return Err(ShardError::Overlap { a, b });
            }
            if b.start > a.end {
                return Err(ShardError::Gap {
                    missing: a.end..b.start,
                });
            }
        }
        let mut sum = vec![DVec3::ZERO; first.mean.pixels().len()];
        let mut passes = 0u64;
        for s in &order {
            let n = s.passes as f64;
            for (acc, p) in sum.iter_mut().zip(s.mean.pixels()) {
                *acc += p.as_dvec3() * n;
            }
            passes += s.passes;
        }
        let pixels = sum.iter().map(|s| (*s / passes as f64).as_vec3()).collect();
        let mean = Image::from_pixels(first.mean.width(), first.mean.height(), pixels)?;
        Ok(Shard {
            mean,
            first_pass: order[0].first_pass,
            passes,
            scene: first.scene.clone(),
            settings: first.settings.clone(),
        })
    }
}

#[cfg(feature = "exr")]
mod exr_io {
    use super::{Shard, ShardError};
    use crate::{Image, RenderError};
    use exr::meta::attribute::{AttributeValue, Text};
    use exr::prelude::{Encoding, SpecificChannels, Vec2, WritableImage};
    use std::path::Path;

    const FIRST_PASS: &str = "photonMapsFirstPass";
    const PASSES: &str = "photonMapsPasses";
    const SCENE: &str = "photonMapsScene";
    const SETTINGS: &str = "photonMapsSettings";

    fn io_error(path: &Path, e: impl std::fmt::Display) -> RenderError {
        RenderError::ImageIo {
            path: path.to_path_buf(),
            message: e.to_string(),
        }
    }

    impl Shard {
        /// Writes the shard's mean as a lossless 32-bit float RGB EXR (viewable as an image)
        /// with its pass range, scene and settings as text attributes of the header.
        pub fn write_exr(&self, path: impl AsRef<Path>) -> Result<(), ShardError> {
            let path = path.as_ref();
            let w = self.mean.width() as usize;
            let pixels = self.mean.pixels();
            let channels = SpecificChannels::rgb(|Vec2(x, y): Vec2<usize>| {
                let p = pixels[y * w + x];
                (p.x, p.y, p.z)
            });
            let mut image = exr::prelude::Image::from_encoded_channels(
                (w, self.mean.height() as usize),
                Encoding::SMALL_LOSSLESS,
                channels,
            );
            let text = |s: &str| AttributeValue::Text(Text::new_or_none(s).unwrap_or_default());
            let other = &mut image.attributes.other;
            other.insert(Text::from(FIRST_PASS), text(&self.first_pass.to_string()));
            other.insert(Text::from(PASSES), text(&self.passes.to_string()));
            other.insert(Text::from(SCENE), text(&self.scene));
            other.insert(Text::from(SETTINGS), text(&self.settings));
            // Atomically: the exr crate's `to_file` deletes the target when a write fails.
            crate::image::write_atomically(path, |writer| {
                image
                    .write()
                    .to_buffered(writer)
                    .map_err(|e| std::io::Error::other(e.to_string()))
            })
            .map_err(|e| io_error(path, e).into())
        }

        /// Reads a shard written by [`Shard::write_exr`]; a plain EXR is
        /// [`ShardError::NotAShard`].
        pub fn read_exr(path: impl AsRef<Path>) -> Result<Shard, ShardError> {
            let path = path.as_ref();
            let meta = exr::meta::MetaData::read_from_file(path, false).map_err(|e| io_error(path, e))?;
            // The reader files unknown text attributes under the layer, whichever part of the
            // header they were written to: look in both.
            let attributes: std::collections::HashMap<Text, AttributeValue> = meta
                .headers
                .first()
                .map(|h| {
                    let shared = h.shared_attributes.other.iter();
                    shared
                        .chain(h.own_attributes.other.iter())
                        .map(|(k, v)| (k.clone(), v.clone()))
                        .collect()
                })
                .unwrap_or_default();
            let get = |name: &'static str| -> Result<String, ShardError> {
                match attributes.get(&Text::from(name)) {
                    Some(AttributeValue::Text(t)) => Ok(t.to_string()),
                    _ => Err(ShardError::NotAShard {
                        path: path.display().to_string(),
                        attribute: name,
                    }),
                }
            };
            let number = |name: &'static str| -> Result<u64, ShardError> {
                get(name)?.parse().map_err(|_| ShardError::NotAShard {
                    path: path.display().to_string(),
                    attribute: name,
                })
            };
            let (first_pass, passes) = (number(FIRST_PASS)?, number(PASSES)?);
            let (scene, settings) = (get(SCENE)?, get(SETTINGS)?);
            let mean = Image::read_exr(path)?;
            Shard::new(mean, first_pass, passes, &scene, &settings)
        }
    }
}
