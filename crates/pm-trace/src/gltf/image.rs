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
mod tests {
    use super::*;

    fn png_bytes(width: u32, height: u32, rgb: &[u8]) -> Vec<u8> {
        let mut out = Vec::new();
        let mut e = png::Encoder::new(&mut out, width, height);
        e.set_color(png::ColorType::Rgb);
        e.set_depth(png::BitDepth::Eight);
        let mut w = e.write_header().unwrap();
        w.write_image_data(rgb).unwrap();
        w.finish().unwrap();
        out
    }

    /// Rewrites the IHDR width and height (and its CRC) of a PNG.
    fn lie_about_size(mut png: Vec<u8>, width: u32, height: u32) -> Vec<u8> {
        png[16..20].copy_from_slice(&width.to_be_bytes());
        png[20..24].copy_from_slice(&height.to_be_bytes());
        let crc = crc32(&png[12..29]);
        png[29..33].copy_from_slice(&crc.to_be_bytes());
        png
    }

    fn crc32(bytes: &[u8]) -> u32 {
        let mut crc = !0u32;
        for &b in bytes {
            crc ^= b as u32;
            for _ in 0..8 {
                crc = if crc & 1 != 0 {
                    (crc >> 1) ^ 0xEDB8_8320
                } else {
                    crc >> 1
                };
            }
        }
        !crc
    }

    #[test]
    fn png_round_trips_to_linear_texels() {
        let t = decode_image(&png_bytes(2, 1, &[255, 0, 0, 0, 0, 188]), 100, ImageChannels::Rgb).unwrap();
        assert_eq!((t.width(), t.height()), (2, 1));
        assert_eq!(t.texel(0, 0), glam::Vec3::X);
        assert!((t.texel(1, 0).z - 0.5029).abs() < 1e-3);
    }

    #[test]
    fn an_image_without_alpha_reads_as_opaque_alpha() {
        let png = png_bytes(2, 1, &[255, 0, 0, 0, 0, 188]);
        let t = decode_image(&png, 100, ImageChannels::Alpha).unwrap();
        assert_eq!((t.texel(0, 0), t.texel(1, 0)), (glam::Vec3::ONE, glam::Vec3::ONE));
        let t = decode_image(&flat_jpeg(2, [150, 100, 170]), 1000, ImageChannels::Alpha).unwrap();
        assert_eq!(t.texel(3, 3), glam::Vec3::ONE);
    }

    #[test]
    fn one_texel_png_claiming_65535_squared_is_refused_before_allocation() {
        let png = lie_about_size(png_bytes(1, 1, &[1, 2, 3]), 65535, 65535);
        let err =
            decode_image(&png, GltfOptions::DEFAULT.max_texture_pixels, ImageChannels::Rgb).unwrap_err();
        assert!(err.contains("65535×65535"), "{err}");
    }

    #[test]
    fn lying_or_truncated_pngs_are_errors() {
        // Claims 4×4 within the limit but holds one texel's data.
        let png = lie_about_size(png_bytes(1, 1, &[1, 2, 3]), 4, 4);
        assert!(decode_image(&png, 100, ImageChannels::Rgb).is_err());
        let whole = png_bytes(4, 4, &[7; 48]);
        for cut in [8, 20, 33, whole.len() / 2, whole.len() - 13] {
            assert!(
                decode_image(&whole[..cut], 100, ImageChannels::Rgb).is_err(),
                "cut at {cut}"
            );
        }
        assert!(decode_image(b"GIF89a", 100, ImageChannels::Rgb).is_err());
        assert!(decode_image(&[0xFF, 0xD8, 0xFF, 0xE0], 100, ImageChannels::Rgb).is_err());
    }

    /// A baseline JPEG of `blocks_x`×1 flat 8×8 blocks of one YCbCr colour, written by hand:
    /// quantisation 1, a DC table with 4-bit codes for categories 0-11 and an AC table holding
    /// only end-of-block (all AC coefficients zero).
    fn flat_jpeg(blocks_x: u16, ycbcr: [u8; 3]) -> Vec<u8> {
        let mut out = vec![0xFF, 0xD8];
        out.extend([0xFF, 0xDB, 0, 67, 0x00]);
        out.extend([1u8; 64]);
        let width = blocks_x * 8;
        out.extend([0xFF, 0xC0, 0, 17, 8, 0, 8]);
        out.extend(width.to_be_bytes());
        out.extend([3, 1, 0x11, 0, 2, 0x11, 0, 3, 0x11, 0]);
        // DC table 0: twelve 4-bit codes, symbol k has code k.
        out.extend([0xFF, 0xC4, 0, 2 + 1 + 16 + 12, 0x00, 0, 0, 0, 12]);
        out.extend([0u8; 12]);
        out.extend(0u8..12);
        // AC table 0: end-of-block only, code `0`.
        out.extend([0xFF, 0xC4, 0, 2 + 1 + 16 + 1, 0x10, 1]);
        out.extend([0u8; 15]);
        out.push(0x00);
        out.extend([0xFF, 0xDA, 0, 12, 3, 1, 0x00, 2, 0x00, 3, 0x00, 0, 63, 0]);
        // Entropy-coded data: per block and component, the DC difference then EOB.
        let mut bits: Vec<bool> = Vec::new();
        let push = |value: u32, n: u32, bits: &mut Vec<bool>| {
            for i in (0..n).rev() {
                bits.push(value >> i & 1 == 1);
            }
        };
        let mut previous = [0i32; 3];
        for _ in 0..blocks_x {
            for c in 0..3 {
                // A flat block of level-shifted value v has DC coefficient 8v.
                let dc = 8 * (i32::from(ycbcr[c]) - 128);
                let diff = dc - previous[c];
                previous[c] = dc;
                let category = 32 - diff.unsigned_abs().leading_zeros();
                push(category, 4, &mut bits);
                let magnitude = if diff < 0 { diff - 1 } else { diff } as u32;
                push(magnitude & ((1 << category) - 1), category, &mut bits);
                bits.push(false);
            }
        }
        while !bits.len().is_multiple_of(8) {
            bits.push(true);
        }
        for byte in bits.chunks(8) {
            let b = byte.iter().fold(0u8, |acc, &x| acc << 1 | u8::from(x));
            out.push(b);
            if b == 0xFF {
                out.push(0);
            }
        }
        out.extend([0xFF, 0xD9]);
        out
    }

    #[test]
    fn flat_jpeg_decodes_to_its_colour_in_linear_texels() {
        // Y 150, Cb 100, Cr 170 is sRGB (208.9, 129.6, 100.4) by the JFIF conversion.
        let t = decode_image(&flat_jpeg(2, [150, 100, 170]), 1000, ImageChannels::Rgb).unwrap();
        assert_eq!((t.width(), t.height()), (16, 8));
        let expected = Texture::from_srgb8(1, 1, vec![[209, 130, 100]])
            .unwrap()
            .texel(0, 0);
        for (x, y) in [(0, 0), (7, 3), (15, 7)] {
            let got = t.texel(x, y);
            assert!((got - expected).abs().max_element() < 0.01, "{got} vs {expected}");
        }
    }

    #[test]
    fn jpeg_claiming_65535_squared_is_refused_from_its_header() {
        let mut jpeg = flat_jpeg(1, [128, 128, 128]);
        // SOF0 sits after SOI (2) and DQT (69): marker 2 bytes, length 2, precision 1.
        assert_eq!(jpeg[71..73], [0xFF, 0xC0]);
        jpeg[76..80].copy_from_slice(&[0xFF, 0xFF, 0xFF, 0xFF]);
        let err =
            decode_image(&jpeg, GltfOptions::DEFAULT.max_texture_pixels, ImageChannels::Rgb).unwrap_err();
        assert!(err.contains("65535×65535"), "{err}");
        // Within the pixel limit but past what the data holds: an error, not a panic.
        jpeg[76..80].copy_from_slice(&[0, 64, 0, 64]);
        let _ = decode_image(&jpeg, 1 << 20, ImageChannels::Rgb);
    }

    #[test]
    fn truncated_or_corrupt_jpegs_are_errors() {
        let whole = flat_jpeg(4, [90, 200, 40]);
        assert!(decode_image(&whole, 1000, ImageChannels::Rgb).is_ok());
        for cut in [3, 10, 40, 72, 80, 100, 150, whole.len() - 12] {
            assert!(
                decode_image(&whole[..cut], 1000, ImageChannels::Rgb).is_err(),
                "cut at {cut}"
            );
        }
        // Zero width in the frame header.
        let mut zero = whole.clone();
        zero[78..80].copy_from_slice(&[0, 0]);
        assert!(decode_image(&zero, 1000, ImageChannels::Rgb).is_err());
    }
}
