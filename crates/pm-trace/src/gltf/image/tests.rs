//! PNG and JPEG decoding against hand-made files: texels round-trip to linear values, a missing
//! alpha reads as opaque, sizes claimed in a header are refused before any allocation, and
//! lying, truncated or corrupt files are errors.

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
    let err = decode_image(&png, GltfOptions::DEFAULT.max_texture_pixels, ImageChannels::Rgb).unwrap_err();
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
    let err = decode_image(&jpeg, GltfOptions::DEFAULT.max_texture_pixels, ImageChannels::Rgb).unwrap_err();
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
