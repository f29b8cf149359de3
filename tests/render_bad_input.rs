//! Bad input to the render example's options is refused by the library with a typed error
//! naming the problem (the example prints it on one line and exits non-zero).

use photon_maps::render::{EstimatorKind, Image, Mode, RenderError, RenderSettings, parse_image_size};
use photon_maps::trace::scenes;

#[test]
fn bad_settings_are_typed_errors() {
    let ok = RenderSettings::default();
    assert!(ok.validate().is_ok());
    assert!(matches!(
        RenderSettings { k: 0, ..ok }.validate(),
        Err(RenderError::ZeroK)
    ));
    assert!(matches!(
        RenderSettings { photons: 0, ..ok }.validate(),
        Err(RenderError::ZeroPhotons)
    ));
    assert!(matches!(
        RenderSettings { width: 0, ..ok }.validate(),
        Err(RenderError::EmptyImage { .. })
    ));
    assert!(matches!(
        RenderSettings {
            samples_per_pixel: 0,
            ..ok
        }
        .validate(),
        Err(RenderError::ZeroSamples)
    ));
    assert!(
        RenderSettings {
            max_distance: Some(-1.0),
            ..ok
        }
        .validate()
        .is_err()
    );
    // Path tracing needs no photons.
    assert!(
        RenderSettings {
            photons: 0,
            mode: Mode::PathTrace,
            ..ok
        }
        .validate()
        .is_ok()
    );
}

#[test]
fn bad_names_and_sizes_are_errors_that_name_them() {
    for text in ["0x10", "10x0", "10", "x", "-5x5", "axb", ""] {
        let err = parse_image_size(text).unwrap_err();
        assert!(err.to_string().contains(&format!("'{text}'")), "{err}");
    }
    assert_eq!(parse_image_size("500x300").unwrap(), (500, 300));
    assert!(
        "spheres"
            .parse::<EstimatorKind>()
            .unwrap_err()
            .to_string()
            .contains("spheres")
    );
    assert!(
        "raytrace"
            .parse::<Mode>()
            .unwrap_err()
            .to_string()
            .contains("raytrace")
    );
    assert!(
        scenes::build("no-such-scene")
            .unwrap_err()
            .to_string()
            .contains("no-such-scene")
    );
}

#[cfg(feature = "exr")]
#[test]
fn unwritable_output_is_an_error_naming_the_path() {
    let image = Image::new(2, 2).unwrap();
    let err = image.write_exr("/proc/no-such-dir/out.exr").unwrap_err();
    assert!(err.to_string().contains("/proc/no-such-dir/out.exr"), "{err}");
}
