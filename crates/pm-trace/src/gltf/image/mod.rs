//! glTF images to [`Texture`]s: bytes from a buffer view, a `data:` URI or a file confined to
//! the scene's folder (the buffers' resolver), PNG and JPEG decoded with sizes bounded from
//! the header before any pixel buffer is allocated.

use std::io::Cursor;
use std::path::Path;

use gltf::json;

use super::buffers::{Buffer, confined_target, decode_data_uri, has_prefix_ignore_case, read_regular};
use super::error::GltfError;
use super::options::GltfOptions;
use crate::sampler::{Sampler, Wrap};
use crate::texture::{TexelEncoding, Texture};

/// Texture `texture` of `root`: the index of its image (checked to exist) and its sampler.
pub(super) fn texture_source(
    file: &Path,
    root: &json::Root,
    texture: usize,
) -> Result<(usize, Sampler), GltfError> {
    let fail = |image: usize, reason: String| GltfError::Image {
        file: file.to_path_buf(),
        image,
        reason,
    };
    let t = root
        .textures
        .get(texture)
        .ok_or_else(|| fail(texture, format!("texture {texture} does not exist")))?;
    let image = t.source.value();
    if image >= root.images.len() {
        return Err(fail(
            image,
            format!("does not exist (the file has {})", root.images.len()),
        ));
    }
    let sampler = t
        .sampler
        .and_then(|s| root.samplers.get(s.value()))
        .map_or_else(Sampler::default, map_sampler);
    Ok((image, sampler))
}

/// Bytes a decode of a `width × height` image may hold at its peak: the decoder's output (up
/// to 8 bytes a texel before 16-bit samples are stripped), the sRGB texels (3) and their
/// mip levels (1).
pub(super) fn decode_bytes(width: u32, height: u32) -> u64 {
    u64::from(width) * u64::from(height) * 12
}

/// Which of an image's channels a texture reads.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub(super) enum ImageChannels {
    /// Red, green and blue (a grey image's grey in all three).
    Rgb,
    /// Alpha, copied into all three channels (opaque, 255, where the image has none: every
    /// JPEG, and PNGs without alpha or transparency): `KHR_materials_specular`'s
    /// `specularTexture` keeps its strength there.
    Alpha,
}

/// How a material reads a texture's image: which channels, and what their codes encode.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub(super) struct ImageRead {
    /// The channels read.
    pub(super) channels: ImageChannels,
    /// sRGB for colour, linear for data.
    pub(super) encoding: TexelEncoding,
}

impl ImageRead {
    /// Colour: the RGB channels, sRGB-encoded (base colour, emission, specular colour).
    pub(super) const COLOUR: ImageRead = ImageRead {
        channels: ImageChannels::Rgb,
        encoding: TexelEncoding::Srgb,
    };
    /// Data in the RGB channels, linear (metallic-roughness, normals).
    pub(super) const DATA: ImageRead = ImageRead {
        channels: ImageChannels::Rgb,
        encoding: TexelEncoding::Linear,
    };
    /// Data in the alpha channel, linear (specular strength).
    pub(super) const ALPHA_DATA: ImageRead = ImageRead {
        channels: ImageChannels::Alpha,
        encoding: TexelEncoding::Linear,
    };
}

/// Reads image `image` of `root` and decodes `channels` of it, after checking from its header
/// that the decode fits in `budget` bytes (see [`decode_bytes`]): a broken, missing or too
/// large image is [`GltfError::Image`].
pub(super) fn load_image(
    file: &Path,
    root: &json::Root,
    buffers: &[Buffer],
    (image, channels): (usize, ImageChannels),
    options: &GltfOptions,
    budget: u64,
) -> Result<Texture, GltfError> {
    let fail = |reason: String| GltfError::Image {
        file: file.to_path_buf(),
        image,
        reason,
    };
    let i = root
        .images
        .get(image)
        .ok_or_else(|| fail(format!("does not exist (the file has {})", root.images.len())))?;
    let bytes = image_bytes(file, root, buffers, i, options).map_err(fail)?;
    let (width, height) = image_size(&bytes).map_err(fail)?;
    let needed = decode_bytes(width, height);
    if needed > budget {
        return Err(fail(format!(
            "{width}×{height} texels take {needed} bytes to decode, past the {budget} bytes left of GltfOptions::max_scene_bytes"
        )));
    }
    decode_image(&bytes, options.max_texture_pixels, channels).map_err(fail)
}

fn map_sampler(s: &json::texture::Sampler) -> Sampler {
    use json::texture::{MagFilter, WrappingMode};
    use json::validation::Checked;
    let wrap = |w: &Checked<WrappingMode>| match w {
        Checked::Valid(WrappingMode::ClampToEdge) => Wrap::ClampToEdge,
        Checked::Valid(WrappingMode::MirroredRepeat) => Wrap::MirroredRepeat,
        _ => Wrap::Repeat,
    };
    Sampler {
        wrap_u: wrap(&s.wrap_s),
        wrap_v: wrap(&s.wrap_t),
        nearest: matches!(s.mag_filter, Some(Checked::Valid(MagFilter::Nearest))),
    }
}

/// The encoded bytes of an image, at most [`GltfOptions::max_file_bytes`].
fn image_bytes(
    file: &Path,
    root: &json::Root,
    buffers: &[Buffer],
    image: &json::Image,
    options: &GltfOptions,
) -> Result<Vec<u8>, String> {
    if let Some(view) = image.buffer_view {
        let v = root
            .buffer_views
            .get(view.value())
            .ok_or_else(|| format!("buffer view {} does not exist", view.value()))?;
        let buffer = buffers
            .get(v.buffer.value())
            .ok_or_else(|| format!("buffer {} does not exist", v.buffer.value()))?
            .as_slice();
        let start = v.byte_offset.map_or(0, |o| o.0);
        let end = start
            .checked_add(v.byte_length.0)
            .filter(|&e| e <= buffer.len() as u64)
            .ok_or_else(|| format!("buffer view {} overruns its buffer", view.value()))?;
        return Ok(buffer[start as usize..end as usize].to_vec());
    }
    let uri = image.uri.as_deref().ok_or("neither a URI nor a buffer view")?;
    if has_prefix_ignore_case(uri, "data:") {
        if uri.len() as u64 > options.max_file_bytes {
            return Err("data: URI longer than the file limit".into());
        }
        return decode_data_uri(uri).map_err(|e| e.to_string());
    }
    let folder = file
        .parent()
        .filter(|p| !p.as_os_str().is_empty())
        .unwrap_or(Path::new("."));
    let target = confined_target(folder, uri).map_err(|e| e.to_string())?;
    read_regular(&target, uri, options.max_file_bytes).map_err(|e| e.to_string())
}

const PNG_MAGIC: &[u8] = b"\x89PNG\r\n\x1a\n";
const JPEG_MAGIC: &[u8] = &[0xFF, 0xD8, 0xFF];

/// The width and height a PNG or JPEG declares in its header, read without decoding pixels.
pub(super) fn image_size(bytes: &[u8]) -> Result<(u32, u32), String> {
    if bytes.starts_with(JPEG_MAGIC) {
        use zune_jpeg::JpegDecoder;
        use zune_jpeg::zune_core::bytestream::ZCursor;
        let mut decoder = JpegDecoder::new(ZCursor::new(bytes));
        decoder.decode_headers().map_err(|e| format!("JPEG: {e:?}"))?;
        let info = decoder.info().ok_or("JPEG: no frame header")?;
        return Ok((u32::from(info.width), u32::from(info.height)));
    }
    if !bytes.starts_with(PNG_MAGIC) {
        return Err("not a PNG image".into());
    }
    let reader = png::Decoder::new(Cursor::new(bytes))
        .read_info()
        .map_err(|e| format!("PNG: {e}"))?;
    Ok((reader.info().width, reader.info().height))
}

/// Decodes `channels` of PNG or JPEG bytes into a texture, refusing images of more than
/// `max_pixels` texels from their header, before the pixel buffer is allocated.
pub(super) fn decode_image(
    bytes: &[u8],
    max_pixels: u64,
    channels: ImageChannels,
) -> Result<Texture, String> {
    if bytes.starts_with(JPEG_MAGIC) {
        return decode_jpeg(bytes, max_pixels, channels);
    }
    if !bytes.starts_with(PNG_MAGIC) {
        return Err("not a PNG image".into());
    }
    let mut decoder = png::Decoder::new(Cursor::new(bytes));
    decoder.set_transformations(png::Transformations::EXPAND | png::Transformations::STRIP_16);
    // The decoder's own allocation limit, on top of our check of the header.
    decoder.set_limits(png::Limits {
        bytes: max_pixels.saturating_mul(8).min(usize::MAX as u64) as usize,
    });
    let mut reader = decoder.read_info().map_err(|e| format!("PNG: {e}"))?;
    let (width, height) = (reader.info().width, reader.info().height);
    let pixels = width as u64 * height as u64;
    if pixels > max_pixels {
        return Err(too_large(width, height, max_pixels));
    }
    let size = reader
        .output_buffer_size()
        .filter(|&s| s as u64 <= pixels.saturating_mul(8))
        .ok_or("PNG: output size out of range")?;
    let mut buf = vec![0u8; size];
    let frame = reader.next_frame(&mut buf).map_err(|e| format!("PNG: {e}"))?;
    let samples = frame.color_type.samples();
    if frame.bit_depth != png::BitDepth::Eight || !(1..=4).contains(&samples) {
        return Err(format!(
            "PNG: unsupported layout {:?} {:?}",
            frame.color_type, frame.bit_depth
        ));
    }
    // The frame's layout is checked against the buffer, not trusted: no slice can panic.
    let row_bytes = width as usize * samples;
    let rows = frame
        .line_size
        .checked_mul(height as usize)
        .filter(|&n| frame.line_size >= row_bytes && n <= buf.len())
        .map(|n| &buf[..n])
        .ok_or("PNG: frame layout out of range")?;
    let mut texels = Vec::with_capacity(pixels as usize);
    for row in rows.chunks_exact(frame.line_size) {
        for px in row[..row_bytes].chunks_exact(samples) {
            texels.push(match (channels, samples) {
                (ImageChannels::Rgb, 1 | 2) => [px[0]; 3],
                (ImageChannels::Rgb, _) => [px[0], px[1], px[2]],
                (ImageChannels::Alpha, 2) => [px[1]; 3],
                (ImageChannels::Alpha, 4) => [px[3]; 3],
                (ImageChannels::Alpha, _) => [u8::MAX; 3],
            });
        }
    }
    Texture::from_srgb8(width, height, texels).ok_or_else(|| "PNG: empty image".into())
}

fn too_large(width: u32, height: u32, max_pixels: u64) -> String {
    format!("{width}×{height} texels, more than the limit of {max_pixels} (GltfOptions::max_texture_pixels)")
}

/// Decodes a JPEG (baseline or progressive) to RGB (its alpha, for [`ImageChannels::Alpha`],
/// is opaque): the header is read first and a declared size past `max_pixels` is refused
/// before the pixel buffer is allocated; the decoder's own width and height limits are set
/// too.
fn decode_jpeg(bytes: &[u8], max_pixels: u64, channels: ImageChannels) -> Result<Texture, String> {
    use zune_jpeg::JpegDecoder;
    use zune_jpeg::zune_core::bytestream::ZCursor;
    use zune_jpeg::zune_core::colorspace::ColorSpace;
    use zune_jpeg::zune_core::options::DecoderOptions;

    let side = max_pixels.clamp(1, u16::MAX as u64) as usize;
    let options = DecoderOptions::new_safe()
        .set_max_width(side)
        .set_max_height(side)
        .set_strict_mode(true)
        .jpeg_set_out_colorspace(ColorSpace::RGB);
    let mut decoder = JpegDecoder::new_with_options(ZCursor::new(bytes), options);
    decoder.decode_headers().map_err(|e| format!("JPEG: {e:?}"))?;
    let info = decoder.info().ok_or("JPEG: no frame header")?;
    let (width, height) = (u32::from(info.width), u32::from(info.height));
    let pixels = width as u64 * height as u64;
    if pixels > max_pixels {
        return Err(too_large(width, height, max_pixels));
    }
    let size = decoder
        .output_buffer_size()
        .filter(|&s| s as u64 == pixels * 3)
        .ok_or("JPEG: output size out of range")?;
    let mut buf = vec![0u8; size];
    decoder
        .decode_into(&mut buf)
        .map_err(|e| format!("JPEG: {e:?}"))?;
    let texels = match channels {
        ImageChannels::Rgb => buf.chunks_exact(3).map(|p| [p[0], p[1], p[2]]).collect(),
        ImageChannels::Alpha => vec![[u8::MAX; 3]; pixels as usize],
    };
    Texture::from_srgb8(width, height, texels).ok_or_else(|| "JPEG: empty image".into())
}

#[cfg(test)]
mod tests;
