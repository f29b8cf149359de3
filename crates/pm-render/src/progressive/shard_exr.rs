//! Shards as EXR files: the mean as R, G, B (any viewer shows it), the exact sums as the bits
//! of their f64 parts in twelve u32 channels, and one text attribute with the pass range and
//! identities (one attribute, so the header's bytes do not depend on a hash map's order).
//! Merging files streams them: one shard's pixels at a time are added to one running sum.

use super::shard::{ShardHeader, plan_merge};
use crate::error::RenderError;
use crate::progressive::pass_sum::PassSums;
use crate::progressive::shard::Shard;
use crate::progressive::shard::ShardError;
use exr::meta::attribute::{AttributeValue, Text};
use exr::prelude::{
    Encoding, LayerAttributes, ReadChannels, ReadLayers, ReadSpecificChannel, Vec2, WritableImage,
};
use std::cell::RefCell;
use std::path::{Path, PathBuf};
use std::rc::Rc;

/// The header attribute: its first line names the format, then first pass, pass count,
/// scene and settings, one a line.
const ATTRIBUTE: &str = "photonMapsShard";
const FORMAT: &str = "photon-maps shard v2";

/// The sum channels of one colour channel: the high and low words of `hi`, then of `lo`.
fn sum_channels(colour: char) -> [String; 4] {
    ["Hi0", "Hi1", "Lo0", "Lo1"].map(|part| format!("pmSum{part}{colour}"))
}

fn io_error(path: &Path, e: impl std::fmt::Display) -> RenderError {
    RenderError::ImageIo {
        path: path.to_path_buf(),
        message: e.to_string(),
    }
}

fn words(x: f64) -> (u32, u32) {
    let bits = x.to_bits();
    ((bits >> 32) as u32, bits as u32)
}

fn from_words(high: u32, low: u32) -> f64 {
    f64::from_bits(u64::from(high) << 32 | u64::from(low))
}

/// Refuses anything but a regular file (following links) before it is opened: a FIFO would
/// block the reader for ever. The check every input file gets
/// ([`crate::image::check_input_file`]), named as a shard's.
fn check_regular_file(path: &Path) -> Result<(), ShardError> {
    match crate::image::input::check_input_file(path, u64::MAX) {
        Ok(_) => Ok(()),
        Err(RenderError::NotARegularFile { .. }) => Err(ShardError::NotAFile {
            path: path.display().to_string(),
        }),
        Err(e) => Err(e.into()),
    }
}

impl Shard {
    /// Writes the shard as a lossless EXR: the mean as 32-bit float R, G, B (viewable as an
    /// image), the exact sums in further channels, and the pass range, scene and settings in
    /// the header. The same shard always gives the same bytes.
    pub fn write_exr(&self, path: impl AsRef<Path>) -> Result<(), ShardError> {
        let path = path.as_ref();
        let mean = self.mean();
        let (w, h) = (self.sums().width() as usize, self.sums().height() as usize);
        let (hi, lo) = self.sums().parts();
        let mean = mean.pixels();
        let pixel = |Vec2(x, y): Vec2<usize>| {
            let i = y * w + x;
            let p = mean[i];
            let (h, l) = (hi[i], lo[i]);
            let (rh, gh, bh) = (words(h.x), words(h.y), words(h.z));
            let (rl, gl, bl) = (words(l.x), words(l.y), words(l.z));
            (
                p.x, p.y, p.z, rh.0, rh.1, rl.0, rl.1, gh.0, gh.1, gl.0, gl.1, bh.0, bh.1, bl.0, bl.1,
            )
        };
        let [r0, r1, r2, r3] = sum_channels('R');
        let [g0, g1, g2, g3] = sum_channels('G');
        let [b0, b1, b2, b3] = sum_channels('B');
        let channels = exr::prelude::SpecificChannels::build()
            .with_channel::<f32>("R")
            .with_channel::<f32>("G")
            .with_channel::<f32>("B")
            .with_channel::<u32>(r0.as_str())
            .with_channel::<u32>(r1.as_str())
            .with_channel::<u32>(r2.as_str())
            .with_channel::<u32>(r3.as_str())
            .with_channel::<u32>(g0.as_str())
            .with_channel::<u32>(g1.as_str())
            .with_channel::<u32>(g2.as_str())
            .with_channel::<u32>(g3.as_str())
            .with_channel::<u32>(b0.as_str())
            .with_channel::<u32>(b1.as_str())
            .with_channel::<u32>(b2.as_str())
            .with_channel::<u32>(b3.as_str())
            .with_pixel_fn(pixel);
        let text = format!(
            "{FORMAT}\n{}\n{}\n{}\n{}",
            self.pass_range().start,
            self.passes(),
            self.scene(),
            self.settings()
        );
        let mut attributes = LayerAttributes::default();
        let value =
            Text::new_or_none(text.as_str()).ok_or_else(|| io_error(path, "identity not storable"))?;
        attributes
            .other
            .insert(Text::from(ATTRIBUTE), AttributeValue::Text(value));
        let layer = exr::prelude::Layer::new((w, h), attributes, Encoding::SMALL_LOSSLESS, channels);
        let image = exr::prelude::Image::from_layer(layer);
        // Atomically: the exr crate's `to_file` deletes the target when a write fails.
        crate::image::atomic::write_atomically(path, |writer| {
            image
                .write()
                .to_buffered(writer)
                .map_err(|e| std::io::Error::other(e.to_string()))
        })
        .map_err(|e| io_error(path, e).into())
    }

    /// Reads what a shard file says about itself (a regular file only; its declared size
    /// within the image limit) without reading its pixels. The header is named by `path`.
    pub fn read_header(path: impl AsRef<Path>) -> Result<ShardHeader, ShardError> {
        let path = path.as_ref();
        check_regular_file(path)?;
        let not_a_shard = |attribute| ShardError::NotAShard {
            path: path.display().to_string(),
            attribute,
        };
        let meta = exr::meta::MetaData::read_from_file(path, false).map_err(|e| io_error(path, e))?;
        let header = meta.headers.first().ok_or_else(|| not_a_shard(ATTRIBUTE))?;
        let size = header.layer_size;
        let (width, height) = match (u32::try_from(size.width()), u32::try_from(size.height())) {
            (Ok(w), Ok(h)) => (w, h),
            _ => {
                return Err(RenderError::ImageTooLarge {
                    width: size.width() as u64,
                    height: size.height() as u64,
                }
                .into());
            }
        };
        crate::image::check_image_size(width, height)?;
        // The reader files unknown attributes under the layer or the image: look in both.
        let text = header
            .own_attributes
            .other
            .get(&Text::from(ATTRIBUTE))
            .or_else(|| header.shared_attributes.other.get(&Text::from(ATTRIBUTE)));
        let Some(AttributeValue::Text(text)) = text else {
            return Err(not_a_shard(ATTRIBUTE));
        };
        let text = text.to_string();
        let fields: Vec<&str> = text.split('\n').collect();
        let [format, first_pass, passes, scene, settings] = fields[..] else {
            return Err(not_a_shard(ATTRIBUTE));
        };
        let (Ok(first_pass), Ok(passes)) = (first_pass.parse(), passes.parse()) else {
            return Err(not_a_shard(ATTRIBUTE));
        };
        if format != FORMAT {
            return Err(not_a_shard(ATTRIBUTE));
        }
        let header = ShardHeader {
            name: path.display().to_string(),
            first_pass,
            passes,
            scene: scene.to_owned(),
            settings: settings.to_owned(),
            width,
            height,
        };
        header.pass_range()?;
        Ok(header)
    }

    /// Reads a shard written by [`Shard::write_exr`]; a plain EXR is
    /// [`ShardError::NotAShard`], a non-finite pixel [`ShardError::NonFinite`] naming the file.
    pub fn read_exr(path: impl AsRef<Path>) -> Result<Shard, ShardError> {
        let path = path.as_ref();
        let header = Self::read_header(path)?;
        let sums = add_file_sums(path, &header, PassSums::new(header.width, header.height)?)?;
        Shard::from_sums(
            sums,
            header.first_pass,
            header.passes,
            &header.scene,
            &header.settings,
        )
    }

    /// Merges shard files as [`Shard::merge`] does, holding one running sum and one shard's
    /// pixels at a time: every header is checked first (a file named twice, by any path, is
    /// [`ShardError::Duplicate`]), then the files are added in pass order.
    pub fn merge_files<P: AsRef<Path>>(paths: &[P]) -> Result<Shard, ShardError> {
        let mut seen: Vec<(PathBuf, &Path)> = Vec::new();
        let mut headers = Vec::new();
        for path in paths {
            let path = path.as_ref();
            headers.push(Self::read_header(path)?);
            let identity = std::fs::canonicalize(path).map_err(|e| io_error(path, e))?;
            if seen.iter().any(|(id, _)| *id == identity) {
                return Err(ShardError::Duplicate {
                    shard: path.display().to_string(),
                });
            }
            seen.push((identity, path));
        }
        let (order, merged) = plan_merge(&headers)?;
        let mut sums = PassSums::new(merged.width, merged.height)?;
        for i in order {
            sums = add_file_sums(paths[i].as_ref(), &headers[i], sums)?;
        }
        Shard::from_sums(
            sums,
            merged.first_pass,
            merged.passes,
            &merged.scene,
            &merged.settings,
        )
    }
}

/// Adds the sums stored in shard file `path` (described by `header`) to `sums`, one colour
/// channel at a time as the decoder yields pixels, so no second image is held; refuses a
/// non-finite value or mean, naming the file and pixel.
fn add_file_sums(path: &Path, header: &ShardHeader, sums: PassSums) -> Result<PassSums, ShardError> {
    let (width, height) = (header.width as usize, header.height as usize);
    let passes = header.passes as f64;
    // The decoder wants closures that own what they hold.
    let target = Rc::new(RefCell::new((sums, None::<(usize, usize)>)));
    for (c, colour) in ['R', 'G', 'B'].into_iter().enumerate() {
        let [n0, n1, n2, n3] = sum_channels(colour);
        let storage = Rc::clone(&target);
        exr::prelude::read()
            .no_deep_data()
            .largest_resolution_level()
            .specific_channels()
            .required::<u32>(n0.as_str())
            .required::<u32>(n1.as_str())
            .required::<u32>(n2.as_str())
            .required::<u32>(n3.as_str())
            .collect_pixels(
                move |_, _| Rc::clone(&storage),
                move |target, Vec2(x, y), (h0, h1, l0, l1): (u32, u32, u32, u32)| {
                    let mut t = target.borrow_mut();
                    if x >= width || y >= height {
                        return;
                    }
                    let (hi, lo) = (from_words(h0, h1), from_words(l0, l1));
                    if !hi.is_finite() || !lo.is_finite() || !((hi / passes) as f32).is_finite() {
                        t.1.get_or_insert((x, y));
                        return;
                    }
                    t.0.add_channel(y * width + x, c, hi, lo);
                },
            )
            .first_valid_layer()
            .all_attributes()
            .non_parallel()
            .from_file(path)
            .map_err(|e| match e {
                exr::error::Error::Invalid(_) => ShardError::NotAShard {
                    path: path.display().to_string(),
                    attribute: "pmSum channels",
                },
                e => ShardError::from(io_error(path, e)),
            })?;
        if let Some((x, y)) = target.borrow().1 {
            return Err(ShardError::NonFinite {
                shard: path.display().to_string(),
                x: x as u32,
                y: y as u32,
            });
        }
    }
    let (sums, _) = Rc::try_unwrap(target)
        .map_err(|_| io_error(path, "the decoder kept the sums"))?
        .into_inner();
    Ok(sums)
}
