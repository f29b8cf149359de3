//! `--compare`: the paper's four variants in a 2×2 grid, the preview exposure picked from the
//! image when none is given, and each panel labelled in a small built-in bitmap font.

use super::choices::{EstimatorChoice, MapsChoice};
use photon_maps::render::Image;
use photon_maps::render::glam::Vec3;

/// The four variants, in grid order (top left, top right, bottom left, bottom right).
pub const VARIANTS: [(&str, MapsChoice, EstimatorChoice); 4] = [
    ("basic", MapsChoice::Single, EstimatorChoice::Disc),
    ("multiple maps", MapsChoice::Crease, EstimatorChoice::Disc),
    ("geometry area", MapsChoice::Single, EstimatorChoice::Cube),
    ("both", MapsChoice::Crease, EstimatorChoice::Cube),
];

/// The share of pixels the automatic exposure lets clip: the brightest channel of the pixel at
/// this quantile maps to white.
const AUTO_QUANTILE: f64 = 0.99;

/// Exposure in stops that maps the [`AUTO_QUANTILE`] of the pixels' brightest channel to
/// white, so about 1 % of the pixels clip (a visible light, a hot spot) and the rest keep
/// their gradation; 0 for an image with nothing lit.
pub fn auto_exposure(image: &Image) -> f32 {
    let mut brightest: Vec<f32> = image
        .pixels()
        .iter()
        .map(|p| p.max_element())
        .filter(|v| v.is_finite())
        .collect();
    if brightest.is_empty() {
        return 0.0;
    }
    let at = ((brightest.len() - 1) as f64 * AUTO_QUANTILE).round() as usize;
    let (_, &mut level, _) = brightest.select_nth_unstable_by(at, f32::total_cmp);
    if level > 0.0 { -level.log2() } else { 0.0 }
}

/// Draws each variant's label into the top left corner of its panel of `grid` (panels of
/// `width × height`), white on black at the preview's `exposure`.
pub fn label_panels(grid: &mut Image, width: u32, height: u32, exposure: f32) {
    let white = Vec3::splat(2f32.powf(-exposure));
    for (i, (label, _, _)) in VARIANTS.iter().enumerate() {
        let (x0, y0) = ((i as u32 % 2) * width, (i as u32 / 2) * height);
        draw_label(grid, label, x0, y0, width, height, white);
    }
}

/// Glyph width and height in font pixels, and the advance between glyphs.
const GLYPH_W: u32 = 5;
const GLYPH_H: u32 = 7;
const ADVANCE: u32 = GLYPH_W + 1;

/// Draws `text` (upper-cased) at the top left of the panel at `(x0, y0)`, on a black box with
/// a one-font-pixel margin, scaled so that labels stay legible on large panels and clipped to
/// the panel.
fn draw_label(image: &mut Image, text: &str, x0: u32, y0: u32, width: u32, height: u32, white: Vec3) {
    let scale = (width / 200).max(1);
    let chars = text.chars().count() as u32;
    let box_w = ((chars * ADVANCE + 1) * scale).min(width);
    let box_h = ((GLYPH_H + 2) * scale).min(height);
    for y in 0..box_h {
        for x in 0..box_w {
            image.set(x0 + x, y0 + y, Vec3::ZERO);
        }
    }
    for (c, ch) in text.chars().enumerate() {
        let rows = glyph(ch.to_ascii_uppercase());
        for (row, bits) in rows.iter().enumerate() {
            for col in 0..GLYPH_W {
                if bits >> (GLYPH_W - 1 - col) & 1 == 0 {
                    continue;
                }
                let fx = 1 + c as u32 * ADVANCE + col;
                let fy = 1 + row as u32;
                for dy in 0..scale {
                    for dx in 0..scale {
                        let (x, y) = (fx * scale + dx, fy * scale + dy);
                        if x < box_w && y < box_h {
                            image.set(x0 + x, y0 + y, white);
                        }
                    }
                }
            }
        }
    }
}

/// The 5×7 glyph of `ch`, one row per byte, the leftmost column in bit 4; blank for
/// characters the labels do not use.
fn glyph(ch: char) -> [u8; 7] {
    match ch {
        'A' => [0x0E, 0x11, 0x11, 0x1F, 0x11, 0x11, 0x11],
        'B' => [0x1E, 0x11, 0x11, 0x1E, 0x11, 0x11, 0x1E],
        'C' => [0x0E, 0x11, 0x10, 0x10, 0x10, 0x11, 0x0E],
        'E' => [0x1F, 0x10, 0x10, 0x1E, 0x10, 0x10, 0x1F],
        'G' => [0x0E, 0x11, 0x10, 0x17, 0x11, 0x11, 0x0F],
        'H' => [0x11, 0x11, 0x11, 0x1F, 0x11, 0x11, 0x11],
        'I' => [0x0E, 0x04, 0x04, 0x04, 0x04, 0x04, 0x0E],
        'L' => [0x10, 0x10, 0x10, 0x10, 0x10, 0x10, 0x1F],
        'M' => [0x11, 0x1B, 0x15, 0x15, 0x11, 0x11, 0x11],
        'O' => [0x0E, 0x11, 0x11, 0x11, 0x11, 0x11, 0x0E],
        'P' => [0x1E, 0x11, 0x11, 0x1E, 0x10, 0x10, 0x10],
        'R' => [0x1E, 0x11, 0x11, 0x1E, 0x14, 0x12, 0x11],
        'S' => [0x0F, 0x10, 0x10, 0x0E, 0x01, 0x01, 0x1E],
        'T' => [0x1F, 0x04, 0x04, 0x04, 0x04, 0x04, 0x04],
        'U' => [0x11, 0x11, 0x11, 0x11, 0x11, 0x11, 0x0E],
        'Y' => [0x11, 0x11, 0x0A, 0x04, 0x04, 0x04, 0x04],
        _ => [0; 7],
    }
}
