//! Bad input to the render example's options is refused by the library with a typed error
//! naming the problem (the example prints it on one line and exits non-zero).

use photon_maps::render::{EstimatorKind, Image, Mode, RenderError, RenderSettings};
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
fn an_unknown_scene_is_an_error_that_names_it() {
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

#[test]
fn huge_images_and_maps_of_another_scene_are_typed_errors() {
    let huge = RenderSettings {
        width: u32::MAX,
        height: u32::MAX,
        ..RenderSettings::default()
    };
    assert!(matches!(huge.validate(), Err(RenderError::ImageTooLarge { .. })));
    assert!(matches!(
        Image::new(1 << 16, 1 << 16),
        Err(RenderError::ImageTooLarge { .. })
    ));

    // Maps of the Cornell box (11+ parts) used for the accordion (8 parts).
    use photon_maps::render::RenderStats;
    use photon_maps::trace::{CreaseAngle, Partitioner};
    let cornell = scenes::build("cornell-box").unwrap();
    let renderer = photon_maps::render::Renderer::new(
        EstimatorKind::Disc,
        RenderSettings {
            width: 8,
            height: 8,
            photons: 1000,
            ..RenderSettings::default()
        },
    );
    let maps = renderer
        .build_maps(
            &cornell,
            &CreaseAngle::default()
                .partition(cornell.clone())
                .unwrap()
                .assignment()
                .clone(),
            &(),
            &mut RenderStats::default(),
        )
        .unwrap();
    let accordion = scenes::build("accordion").unwrap();
    assert!(matches!(
        renderer.render_image(&accordion, Some(&maps), &()),
        Err(RenderError::MapsForAnotherScene { .. })
    ));
}

#[test]
fn an_exr_claiming_a_billion_pixels_is_refused_before_allocating() {
    // A valid small EXR, then its data window widened in the header to 40000 x 40000.
    let dir = std::env::temp_dir().join(format!("pm-exr-huge-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let path = dir.join("small.exr");
    Image::new(4, 4).unwrap().write_exr(&path).unwrap();
    let mut bytes = std::fs::read(&path).unwrap();
    let name = b"dataWindow\0box2i\0";
    let at = bytes
        .windows(name.len())
        .position(|w| w == name)
        .expect("a dataWindow attribute")
        + name.len()
        + 4;
    // box2i: xMin, yMin, xMax, yMax as i32.
    bytes[at + 8..at + 12].copy_from_slice(&39_999i32.to_le_bytes());
    bytes[at + 12..at + 16].copy_from_slice(&39_999i32.to_le_bytes());
    let huge = dir.join("huge.exr");
    std::fs::write(&huge, bytes).unwrap();
    let result = Image::read_exr(&huge);
    std::fs::remove_dir_all(&dir).ok();
    assert!(
        result.is_err(),
        "a 40000x40000 EXR with 16 pixels of data must not load"
    );
}

#[test]
fn a_scene_without_lights_is_a_typed_trace_error() {
    use photon_maps::render::RenderStats;
    use photon_maps::trace::glam::Vec3;
    use photon_maps::trace::{Partitioner, Scene, SingleMap, Surface, TraceError};
    let floor = [
        Vec3::new(0.0, 0.0, 0.0),
        Vec3::new(1.0, 0.0, 0.0),
        Vec3::new(1.0, 0.0, 1.0),
        Vec3::new(0.0, 0.0, 1.0),
    ];
    let dark = Scene::builder()
        .mesh(&floor, &[[0u32, 1, 2, 3]], Surface::diffuse(Vec3::splat(0.5)))
        .build()
        .unwrap();
    let renderer = photon_maps::render::Renderer::new(EstimatorKind::Disc, RenderSettings::default());
    let error = renderer
        .build_maps(
            &dark,
            &SingleMap.partition(dark.clone()).unwrap().assignment().clone(),
            &(),
            &mut RenderStats::default(),
        )
        .unwrap_err();
    assert!(
        matches!(error, RenderError::Trace(TraceError::NoLights)),
        "{error:?}"
    );
    // The message says which stage refused and why.
    assert!(error.to_string().starts_with("photon tracing:"), "{error}");
}
