//! Shard files of the mutation test written by hand, in the format the library documents,
//! and the header lines read back from a real shard.

use exr::meta::attribute::{AttributeValue, Text};
use exr::prelude::{Encoding, LayerAttributes, SpecificChannels, Vec2, WritableImage};
use std::path::Path;

fn words(x: f64) -> (u32, u32) {
    ((x.to_bits() >> 32) as u32, x.to_bits() as u32)
}

/// A shard file written by hand (the format the library documents), every pixel's sums
/// `(hi, lo)`; the header's five lines as given.
pub fn write_shard(path: &Path, lines: &[String], hi: f64, lo: f64) {
    let (h, l) = (words(hi), words(lo));
    let mean = hi as f32;
    let channels = SpecificChannels::build()
        .with_channel::<f32>("R")
        .with_channel::<f32>("G")
        .with_channel::<f32>("B")
        .with_channel::<u32>("pmSumHi0R")
        .with_channel::<u32>("pmSumHi1R")
        .with_channel::<u32>("pmSumLo0R")
        .with_channel::<u32>("pmSumLo1R")
        .with_channel::<u32>("pmSumHi0G")
        .with_channel::<u32>("pmSumHi1G")
        .with_channel::<u32>("pmSumLo0G")
        .with_channel::<u32>("pmSumLo1G")
        .with_channel::<u32>("pmSumHi0B")
        .with_channel::<u32>("pmSumHi1B")
        .with_channel::<u32>("pmSumLo0B")
        .with_channel::<u32>("pmSumLo1B")
        .with_pixel_fn(|_: Vec2<usize>| {
            (
                mean, mean, mean, h.0, h.1, l.0, l.1, h.0, h.1, l.0, l.1, h.0, h.1, l.0, l.1,
            )
        });
    let mut attributes = LayerAttributes::default();
    let text = Text::new_or_none(lines.join("\n").as_str()).unwrap_or_default();
    attributes
        .other
        .insert(Text::from("photonMapsShard"), AttributeValue::Text(text));
    let layer = exr::prelude::Layer::new((8, 6), attributes, Encoding::SMALL_LOSSLESS, channels);
    exr::prelude::Image::from_layer(layer)
        .write()
        .to_file(path)
        .unwrap();
}

/// The header of a shard: its scene and settings lines read from a real one.
pub fn header_of(path: &Path) -> (String, String) {
    let meta = exr::meta::MetaData::read_from_file(path, false).unwrap();
    let h = &meta.headers[0];
    let text = h
        .own_attributes
        .other
        .get(&Text::from("photonMapsShard"))
        .or_else(|| h.shared_attributes.other.get(&Text::from("photonMapsShard")));
    let Some(AttributeValue::Text(t)) = text else {
        panic!("no shard header")
    };
    let t = t.to_string();
    let lines: Vec<&str> = t.split('\n').collect();
    (lines[3].to_owned(), lines[4].to_owned())
}
