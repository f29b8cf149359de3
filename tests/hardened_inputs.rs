//! Hostile input through the library: every case ends as a typed error naming the problem,
//! before anything large is allocated, and a failed write leaves the file it named intact.

#[path = "support/scratch.rs"]
mod scratch;
use scratch::Scratch;

use photon_maps::kdtree::{
    BuildError, Euclidean, KindMask, MAX_COORDINATE, Neighbours, Photon, PhotonKind, PhotonTree,
};
use photon_maps::render::{Image, Mode, RenderError, RenderSettings};
use photon_maps::trace::glam::Vec3;
use photon_maps::trace::{
    AreaLight, Camera, DirectionalLight, MAX_PHOTON_PATHS, PointLight, Scene, SceneError, SingleMap,
    SpotLight, Surface, TraceError, TraceOptions, trace_photons,
};
use photon_maps::trace::{Partitioner, gltf};

fn floor() -> [Vec3; 4] {
    [
        Vec3::new(-1.0, 0.0, -1.0),
        Vec3::new(-1.0, 0.0, 1.0),
        Vec3::new(1.0, 0.0, 1.0),
        Vec3::new(1.0, 0.0, -1.0),
    ]
}

/// A lit floor, built with `light` and `camera` (when given).
fn build_with(
    light: Option<Box<dyn photon_maps::trace::Light>>,
    camera: Option<Camera>,
) -> Result<Scene, SceneError> {
    let mut b = Scene::builder()
        .mesh(&floor(), &[[0u32, 1, 2, 3]], Surface::diffuse(Vec3::splat(0.5)))
        .light(PointLight::new(Vec3::Y, Vec3::splat(10.0)));
    if let Some(light) = light {
        b = b.boxed_light(light);
    }
    if let Some(camera) = camera {
        b = b.camera(camera);
    }
    b.build()
}

// Class 6, 7, 12: limits checked with the settings, before anything is allocated.

#[test]
fn photon_counts_past_the_limit_are_refused_before_tracing() {
    let settings = RenderSettings {
        photons: u32::MAX,
        ..RenderSettings::default()
    };
    let err = settings.validate().unwrap_err();
    assert!(
        matches!(
            err,
            RenderError::Trace(TraceError::TooManyPhotons { photons: u32::MAX })
        ),
        "{err}"
    );
    assert!(err.to_string().contains(&MAX_PHOTON_PATHS.to_string()), "{err}");
    // Path tracing reads no photon maps: the count does not matter there.
    assert!(
        RenderSettings {
            mode: Mode::PathTrace,
            ..settings
        }
        .validate()
        .is_ok()
    );
    // The tracer refuses it itself, before reserving for the run.
    let scene = build_with(None, None).unwrap();
    let err = trace_photons(
        &scene,
        &SingleMap.partition(scene.clone()).unwrap().assignment().clone(),
        &TraceOptions {
            photons: MAX_PHOTON_PATHS + 1,
            ..TraceOptions::default()
        },
    )
    .unwrap_err();
    assert!(matches!(err, TraceError::TooManyPhotons { .. }), "{err}");
}

#[test]
fn thread_counts_past_the_limit_are_refused_with_a_message() {
    for threads in [RenderSettings::MAX_THREADS + 1, 65_535, 65_536, usize::MAX] {
        let err = RenderSettings {
            threads,
            ..RenderSettings::default()
        }
        .validate()
        .unwrap_err();
        assert!(
            matches!(err, RenderError::TooManyThreads(t) if t == threads),
            "{err}"
        );
        assert!(err.to_string().contains("threads"), "{err}");
    }
    let max = RenderSettings {
        threads: RenderSettings::MAX_THREADS,
        ..RenderSettings::default()
    };
    assert!(max.validate().is_ok());
}

#[test]
fn images_too_large_to_write_are_refused_up_front() {
    // 16384² rendered for 25 s and then exhausted memory while encoding.
    for (width, height) in [(16_384, 16_384), (8193, 8192), (1, (1 << 26) + 1)] {
        let err = RenderSettings {
            width,
            height,
            ..RenderSettings::default()
        }
        .validate()
        .unwrap_err();
        assert!(
            matches!(err, RenderError::ImageTooLarge { .. }),
            "{width}x{height}: {err}"
        );
    }
    assert!(
        RenderSettings {
            width: 8192,
            height: 8192,
            ..RenderSettings::default()
        }
        .validate()
        .is_ok()
    );
    // A 2×2 grid counts its four cells: checked before the cells are copied.
    let cell = Image::new(1, 1 << 25).unwrap();
    assert!(matches!(
        Image::grid_2x2([&cell, &cell, &cell, &cell]),
        Err(RenderError::ImageTooLarge { .. })
    ));
    let err = RenderSettings {
        samples_per_pixel: u32::MAX,
        ..RenderSettings::default()
    }
    .validate()
    .unwrap_err();
    assert!(matches!(err, RenderError::TooManySamples(u32::MAX)), "{err}");
}

// Class 8: atomic writes.

#[cfg(all(unix, feature = "exr", feature = "png"))]
#[test]
fn a_failed_image_write_leaves_the_named_link_and_file_intact() {
    let scratch = Scratch::new("atomic");
    let image = Image::from_fn(4, 4, |x, y| Vec3::new(x as f32, y as f32, 1.0)).unwrap();
    // A link to a device that fails every write: the exr crate removed the link on failure.
    let link = scratch.0.join("x.exr");
    std::os::unix::fs::symlink("/dev/full", &link).unwrap();
    assert!(image.write_exr(&link).is_err());
    assert!(
        std::fs::symlink_metadata(&link).is_ok_and(|m| m.file_type().is_symlink()),
        "the link named as output was removed"
    );
    let png_link = scratch.0.join("x.png");
    std::os::unix::fs::symlink("/dev/full", &png_link).unwrap();
    assert!(image.write_png(&png_link, 0.0).is_err());
    assert!(std::fs::symlink_metadata(&png_link).is_ok_and(|m| m.file_type().is_symlink()));
    // A folder named as output is refused and kept.
    let folder = scratch.0.join("folder.exr");
    std::fs::create_dir(&folder).unwrap();
    assert!(image.write_exr(&folder).is_err());
    assert!(folder.is_dir());
    // A successful write through a link to a regular file replaces the file, keeps the link.
    let real = scratch.0.join("real.exr");
    std::fs::write(&real, b"previous").unwrap();
    let to_real = scratch.0.join("to-real.exr");
    std::os::unix::fs::symlink("real.exr", &to_real).unwrap();
    image.write_exr(&to_real).unwrap();
    assert!(
        std::fs::symlink_metadata(&to_real)
            .unwrap()
            .file_type()
            .is_symlink()
    );
    assert_eq!(Image::read_exr(&real).unwrap(), image);
    let names: Vec<_> = std::fs::read_dir(&scratch.0)
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .filter(|n| n.ends_with(".tmp"))
        .collect();
    assert!(names.is_empty(), "temporary files left: {names:?}");
}

#[cfg(feature = "png")]
#[test]
fn a_non_finite_exposure_is_refused() {
    let scratch = Scratch::new("exposure");
    let image = Image::new(2, 2).unwrap();
    for exposure in [f32::NAN, f32::INFINITY, f32::NEG_INFINITY] {
        let path = scratch.0.join("x.png");
        let err = image.write_png(&path, exposure).unwrap_err();
        assert!(matches!(err, RenderError::BadExposure(_)), "{err}");
        assert!(!path.exists());
    }
}

// Class 9: FIFOs are never opened.

#[cfg(unix)]
fn make_fifo(path: &std::path::Path) {
    let status = std::process::Command::new("mkfifo")
        .arg(path)
        .status()
        .expect("mkfifo runs");
    assert!(status.success());
}

/// Opens the FIFO for writing without blocking, which frees a reader stuck in `open`.
#[cfg(unix)]
fn unblock(path: &std::path::Path) {
    use std::os::unix::fs::OpenOptionsExt;
    let _ = std::fs::OpenOptions::new()
        .write(true)
        .custom_flags(0o4000) // O_NONBLOCK on Linux
        .open(path);
}

#[cfg(all(unix, feature = "gltf"))]
#[test]
fn a_fifo_scene_or_buffer_is_refused_without_blocking() {
    let scratch = Scratch::new("fifo");
    let fifo = scratch.0.join("scene.gltf");
    make_fifo(&fifo);
    let (tx, rx) = std::sync::mpsc::channel();
    let path = fifo.clone();
    std::thread::spawn(move || {
        let _ = tx.send(gltf::load_scene(&path).map(|_| ()).map_err(|e| e.to_string()));
    });
    // A guard against hanging forever, not a timing assertion: the old loader blocked in open.
    let result = rx.recv_timeout(std::time::Duration::from_secs(60));
    if result.is_err() {
        unblock(&fifo);
    }
    let err = result.expect("loading a FIFO blocked").unwrap_err();
    assert!(err.contains("not a regular file"), "{err}");

    // A buffer naming a FIFO.
    let pipe = scratch.0.join("pipe.bin");
    make_fifo(&pipe);
    let json = r#"{"asset":{"version":"2.0"},"buffers":[{"uri":"pipe.bin","byteLength":36}],"scenes":[{"nodes":[]}]}"#;
    let file = scratch.0.join("buffer.gltf");
    std::fs::write(&file, json).unwrap();
    let err = gltf::load_scene(&file).unwrap_err();
    assert_eq!(err.kind(), "buffer/not-regular-file", "{err}");
}

// Class 10: lights and the camera are checked when the scene is built.

#[test]
fn invalid_lights_are_refused_naming_the_light() {
    let nan = Vec3::splat(f32::NAN);
    let inf = Vec3::splat(f32::INFINITY);
    let cases: Vec<(Box<dyn photon_maps::trace::Light>, &str)> = vec![
        (Box::new(PointLight::new(nan, Vec3::ONE)), "position"),
        (Box::new(PointLight::new(inf, Vec3::ONE)), "position"),
        (Box::new(PointLight::new(Vec3::Y, Vec3::splat(-5.0))), "power"),
        (
            Box::new(SpotLight::new(Vec3::Y, Vec3::NEG_Y, f32::NAN, Vec3::ONE)),
            "cone",
        ),
        (
            Box::new(SpotLight::new(Vec3::Y, Vec3::NEG_Y, 0.0, Vec3::ONE)),
            "cone",
        ),
        (
            Box::new(SpotLight::new(nan, Vec3::NEG_Y, 0.5, Vec3::ONE)),
            "position",
        ),
        (
            Box::new(SpotLight::new(Vec3::Y, nan, 0.5, Vec3::ONE)),
            "direction",
        ),
        (Box::new(DirectionalLight::new(nan, Vec3::ONE)), "direction"),
        (
            Box::new(AreaLight::from_triangles(&[[nan, nan, nan]], Vec3::ONE)),
            "area",
        ),
        (Box::new(PointLight::new(Vec3::Y, Vec3::splat(3e38))), "power"),
    ];
    for (light, needle) in cases {
        let described = format!("{light:?}");
        let err = build_with(Some(light), None).unwrap_err();
        assert!(
            matches!(&err, SceneError::InvalidLight { light: 1, .. }),
            "{described}: {err}"
        );
        let message = err.to_string();
        assert!(message.starts_with("light 1:"), "{described}: {message}");
        assert!(message.contains(needle), "{described}: {message}");
    }
    // Two lights that are each finite but whose total power overflows f32.
    let two = Scene::builder()
        .mesh(&floor(), &[[0u32, 1, 2, 3]], Surface::diffuse(Vec3::splat(0.5)))
        .light(PointLight::new(Vec3::Y, Vec3::new(3e38, 0.0, 0.0)))
        .light(PointLight::new(Vec3::Y, Vec3::new(3e38, 0.0, 0.0)))
        .build()
        .unwrap_err();
    assert!(matches!(two, SceneError::InvalidLight { light: 1, .. }), "{two}");
    assert!(two.to_string().contains("total power"), "{two}");
}

#[test]
fn invalid_cameras_are_refused_naming_the_problem() {
    let at = Vec3::new(0.0, 1.0, 3.0);
    let cases = [
        (
            Camera::new(Vec3::splat(f32::NAN), Vec3::ZERO, Vec3::Y, 1.0),
            "not finite",
        ),
        (
            Camera::new(Vec3::splat(f32::INFINITY), Vec3::ZERO, Vec3::Y, 1.0),
            "not finite",
        ),
        (Camera::new(at, at, Vec3::Y, 1.0), "look-at"),
        (Camera::new(at, Vec3::ZERO, Vec3::Y, f32::NAN), "field of view"),
        (
            Camera::new(at, Vec3::ZERO, Vec3::Y, f32::INFINITY),
            "field of view",
        ),
        (Camera::new(at, Vec3::ZERO, Vec3::Y, 0.0), "field of view"),
        (Camera::new(at, Vec3::ZERO, Vec3::Y, -1.0), "field of view"),
    ];
    for (camera, needle) in cases {
        let err = build_with(None, Some(camera)).unwrap_err();
        assert!(
            matches!(err, SceneError::InvalidCamera { .. }),
            "{camera:?}: {err}"
        );
        assert!(err.to_string().contains(needle), "{camera:?}: {err}");
    }
    assert!(build_with(None, Some(Camera::new(at, Vec3::ZERO, Vec3::Y, 1.0))).is_ok());
}

// Class 11: squared distances in the kd-tree cannot overflow.

fn photon_at(position: Vec3) -> Photon {
    Photon {
        position,
        power: Vec3::ONE,
        direction: Vec3::NEG_Y,
        kind: PhotonKind::Direct,
    }
}

#[test]
fn kd_tree_coordinates_whose_squares_overflow_are_refused() {
    for far in [2e19f32, -1.8e19, 3e38] {
        let photons = vec![photon_at(Vec3::ZERO), photon_at(Vec3::new(far, 0.0, 0.0))];
        let err = PhotonTree::build(photons).unwrap_err();
        assert!(
            matches!(err, BuildError::PositionOutOfRange { index: 1, .. }),
            "{err}"
        );
    }
    // At the limit, distances stay finite and the nearest photon is the true nearest one.
    let m = MAX_COORDINATE;
    let photons: Vec<Photon> = [
        Vec3::new(m, m, m),
        Vec3::new(-m, -m, -m),
        Vec3::new(m, -m, 0.0),
        Vec3::new(0.9 * m, m, m),
    ]
    .into_iter()
    .map(photon_at)
    .collect();
    let tree = PhotonTree::from_photons(&photons).unwrap();
    let mut near = Neighbours::new();
    let query = Vec3::new(-m, -m, -0.9 * m);
    tree.nearest_k::<Euclidean>(query, 1, f32::INFINITY, KindMask::ALL, &mut near);
    let found = near.as_slice();
    assert_eq!(found.len(), 1);
    assert!(found[0].distance.is_finite(), "{found:?}");
    let got = tree.get(found[0].index).position();
    assert_eq!(got, Vec3::new(-m, -m, -m));
}

// Class 14: messages.

#[cfg(feature = "gltf")]
#[test]
fn gltf_messages_have_one_prefix_and_world_positions() {
    let scratch = Scratch::new("messages");
    // Fails the gltf crate's validation (an accessor without a type).
    let bad = r#"{"asset":{"version":"2.0"},"accessors":[{"componentType":5126,"count":1}]}"#;
    let file = scratch.0.join("bad.gltf");
    std::fs::write(&file, bad).unwrap();
    let message = gltf::load_scene(&file).unwrap_err().to_string();
    assert_eq!(message.matches("invalid glTF").count(), 1, "{message}");

    // A finite local position that the node's scale sends to infinity.
    let data = "data:application/octet-stream;base64,AAAAAAAAAAAAAAAAAACAPwAAAAAAAAAAAAAAAAAAgD8AAAAA";
    let json = format!(
        concat!(
            r#"{{"asset":{{"version":"2.0"}},"scenes":[{{"nodes":[0]}}],"nodes":[{{"mesh":0,"scale":[3e38,1,1],"translation":[3e38,0,0]}}],"#,
            r#""meshes":[{{"primitives":[{{"attributes":{{"POSITION":0}}}}]}}],"#,
            r#""buffers":[{{"uri":"{data}","byteLength":36}}],"bufferViews":[{{"buffer":0,"byteLength":36}}],"#,
            r#""accessors":[{{"bufferView":0,"componentType":5126,"count":3,"type":"VEC3","min":[0,0,0],"max":[1,1,0]}}]}}"#
        ),
        data = data
    );
    let file = scratch.0.join("far.gltf");
    std::fs::write(&file, json).unwrap();
    let message = gltf::load_scene(&file).unwrap_err().to_string();
    // f64 composition puts it at 6e38 m, 1.5e38 m from the re-centred origin: past the
    // photon maps' range, refused where it is placed.
    assert!(
        message.contains("in the world") && message.contains("position"),
        "{message}"
    );
}
