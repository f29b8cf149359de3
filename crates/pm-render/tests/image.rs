//! Image tests: EXR round trip, metrics against hand-computed values, the 2×2 grid, sRGB.

use glam::Vec3;
use pm_render::{Image, RenderError, image::linear_to_srgb8};
use std::path::PathBuf;

fn tmp(name: &str) -> PathBuf {
    PathBuf::from(env!("CARGO_TARGET_TMPDIR")).join(format!("pm-render-{}-{name}", std::process::id()))
}

fn awkward_image() -> Image {
    // Values that a lossy or half-float file would change: tiny, huge, negative, subnormal.
    Image::from_fn(37, 19, |x, y| {
        let i = (y * 37 + x) as f32;
        Vec3::new(
            i.sin() * 1e-3 + 1.0 / 3.0,
            (i * 0.77).cos() * 12345.678,
            -i * 1e-38,
        )
    })
    .unwrap()
}

#[cfg(feature = "exr")]
#[test]
fn exr_round_trip_is_bit_exact() {
    let image = awkward_image();
    let path = tmp("round.exr");
    image.write_exr(&path).unwrap();
    let back = Image::read_exr(&path).unwrap();
    assert_eq!((back.width(), back.height()), (37, 19));
    for (a, b) in image.pixels().iter().zip(back.pixels()) {
        assert_eq!(a.to_array().map(f32::to_bits), b.to_array().map(f32::to_bits));
    }
    std::fs::remove_file(path).ok();
}

#[cfg(feature = "exr")]
#[test]
fn exr_errors_name_the_file() {
    let missing = tmp("does-not-exist.exr");
    let err = Image::read_exr(&missing).unwrap_err();
    assert!(err.to_string().contains("does-not-exist.exr"), "{err}");
    let unwritable = PathBuf::from("/nonexistent-dir/x.exr");
    let err = awkward_image().write_exr(&unwritable).unwrap_err();
    assert!(err.to_string().contains("/nonexistent-dir/x.exr"), "{err}");
}

#[cfg(feature = "png")]
#[test]
fn png_preview_has_the_png_signature_and_size() {
    let path = tmp("preview.png");
    awkward_image().write_png(&path, 0.0).unwrap();
    let bytes = std::fs::read(&path).unwrap();
    assert_eq!(&bytes[..8], b"\x89PNG\r\n\x1a\n");
    // IHDR width and height, big-endian, right after the chunk header.
    assert_eq!(u32::from_be_bytes(bytes[16..20].try_into().unwrap()), 37);
    assert_eq!(u32::from_be_bytes(bytes[20..24].try_into().unwrap()), 19);
    std::fs::remove_file(path).ok();
}

#[test]
fn srgb_curve_matches_the_standard() {
    // Reference code values from the sRGB definition (IEC 61966-2-1).
    assert_eq!(linear_to_srgb8(0.0), 0);
    assert_eq!(linear_to_srgb8(1.0), 255);
    assert_eq!(linear_to_srgb8(2.0), 255);
    assert_eq!(linear_to_srgb8(-1.0), 0);
    assert_eq!(linear_to_srgb8(f32::NAN), 0);
    assert_eq!(linear_to_srgb8(0.18), 118); // middle grey
    assert_eq!(linear_to_srgb8(0.5), 188);
    assert_eq!(linear_to_srgb8(0.002), 7); // linear segment: 12.92 * 0.002 * 255 = 6.6
}

#[test]
fn metrics_match_hand_computed_values() {
    // 2x2: pixel values 0, 1, 2, 3 (grey).
    let a = Image::from_fn(2, 2, |x, y| Vec3::splat((y * 2 + x) as f32)).unwrap();
    assert_eq!(a.mean(), Vec3::splat(1.5));
    assert_eq!(a.mean_in_rect(1, 0, 1, 2).unwrap(), Vec3::splat(2.0));
    assert_eq!(a.mean_in_rect(0, 1, 2, 1).unwrap(), Vec3::splat(2.5));
    let b = Image::from_fn(2, 2, |_, _| Vec3::splat(1.0)).unwrap();
    // differences -1, 0, 1, 2 → mean square (1 + 0 + 1 + 4) / 4 = 1.5
    assert!((a.rmse(&b).unwrap() - 1.5f32.sqrt()).abs() < 1e-6);
    assert!((a.relative_rmse(&b).unwrap() - 1.5f32.sqrt()).abs() < 1e-6);
    assert_eq!(a.rmse(&a).unwrap(), 0.0);
}

#[test]
fn bad_sizes_and_rectangles_are_errors() {
    assert!(matches!(
        Image::new(0, 10),
        Err(RenderError::EmptyImage { width: 0, height: 10 })
    ));
    let a = Image::new(4, 3).unwrap();
    let b = Image::new(3, 4).unwrap();
    assert!(matches!(a.rmse(&b), Err(RenderError::SizeMismatch { .. })));
    assert!(a.mean_in_rect(3, 0, 2, 1).is_err());
    assert!(a.mean_in_rect(0, 0, 0, 1).is_err());
    assert!(a.mean_in_rect(u32::MAX, 0, 2, 1).is_err());
    assert!(Image::grid_2x2([&a, &a, &b, &a]).is_err());
}

#[test]
fn grid_puts_each_image_in_its_quadrant() {
    let cells: Vec<Image> = (0..4)
        .map(|i| Image::from_fn(3, 2, |_, _| Vec3::splat(i as f32)).unwrap())
        .collect();
    let g = Image::grid_2x2([&cells[0], &cells[1], &cells[2], &cells[3]]).unwrap();
    assert_eq!((g.width(), g.height()), (6, 4));
    assert_eq!(g.mean_in_rect(0, 0, 3, 2).unwrap(), Vec3::splat(0.0));
    assert_eq!(g.mean_in_rect(3, 0, 3, 2).unwrap(), Vec3::splat(1.0));
    assert_eq!(g.mean_in_rect(0, 2, 3, 2).unwrap(), Vec3::splat(2.0));
    assert_eq!(g.mean_in_rect(3, 2, 3, 2).unwrap(), Vec3::splat(3.0));
}
