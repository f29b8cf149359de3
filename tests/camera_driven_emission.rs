//! Camera-driven photon emission through the renderers: a progressive render's image mean
//! with camera-driven passes agrees with uniform passes' (same volumes, independent seeds,
//! standard errors) on rooms the camera sees one of; one-shot and SPPM images are the same
//! bits on one and three threads; progressive shards (each learning the guide again) merge
//! into the bits of the single run; the option is refused where no photons are traced, with an
//! automatic photon count, and out of range; and a cache made with it is refused by name by a
//! run without it; a cache for several cameras learns what all of them see.

#[path = "support/replicates.rs"]
mod replicates;
use replicates::mean_and_error;

use photon_maps::render::cache_file::CacheIdentity;
use photon_maps::render::emission::PhotonEmission;
use photon_maps::render::glam::Vec3;
use photon_maps::render::progressive::{
    ProgressiveRenderer, ProgressiveSettings, Shard, SppmRenderer, SppmSettings,
};
use photon_maps::render::{
    AutoPhotons, GeometryCube, Mode, RenderError, RenderSettings, RenderStats, Renderer,
};
use photon_maps::trace::{Camera, CreaseAngle, GuideOptions, Partitioned, Partitioner, scenes};

fn rooms(n: u32) -> Partitioned {
    CreaseAngle::default()
        .partition(scenes::build(&format!("doorway-rooms-{n}")).unwrap())
        .unwrap()
}

fn camera() -> PhotonEmission {
    PhotonEmission::CameraDriven(GuideOptions {
        pilot_photons: 8_192,
        floor: 0.125,
    })
}

fn base() -> RenderSettings {
    RenderSettings {
        width: 24,
        height: 18,
        photons: 8_000,
        mode: Mode::ShadowRays,
        ..RenderSettings::default()
    }
}

/// Mean over channels and pixels of a progressive render of `passes` passes.
fn progressive_mean(partitioned: &Partitioned, settings: RenderSettings, passes: u64) -> f64 {
    let rendered = ProgressiveRenderer::new(GeometryCube, ProgressiveSettings::new(settings, passes))
        .render(partitioned, &())
        .unwrap();
    if let PhotonEmission::CameraDriven(_) = settings.emission {
        let stats = &rendered.stats;
        let report = stats.emission.expect("a camera-driven run reports its guide");
        assert!(report.keep_rate < 0.6, "{report:?}");
        assert!(stats.photons_traced < stats.photons_emitted, "{stats:?}");
    }
    f64::from(rendered.accumulation.mean().mean().element_sum()) / 3.0
}

#[test]
fn camera_driven_passes_estimate_what_uniform_passes_estimate() {
    let partitioned = rooms(4);
    let mut uniform = Vec::new();
    let mut guided = Vec::new();
    for seed in 0..5 {
        uniform.push(progressive_mean(
            &partitioned,
            RenderSettings { seed, ..base() },
            6,
        ));
        let settings = RenderSettings {
            seed: 100 + seed,
            emission: camera(),
            ..base()
        };
        guided.push(progressive_mean(&partitioned, settings, 6));
    }
    let ((u, us), (g, gs)) = (mean_and_error(&uniform), mean_and_error(&guided));
    let z = (g - u) / (us * us + gs * gs).sqrt();
    assert!(
        z.abs() < 4.0,
        "uniform {u} ± {us}, camera-driven {g} ± {gs}: {z:.2} se"
    );
    assert!((g / u - 1.0).abs() < 0.02, "uniform {u}, camera-driven {g}");
}

#[test]
fn camera_driven_images_are_the_same_bits_on_one_and_three_threads() {
    let partitioned = rooms(3);
    for mode in [Mode::PhotonMap, Mode::FinalGather] {
        let image = |threads: usize| {
            let settings = RenderSettings {
                threads,
                mode,
                emission: camera(),
                ..base()
            };
            Renderer::new(GeometryCube, settings)
                .render(&partitioned, &())
                .unwrap()
                .image
        };
        assert_eq!(image(1).pixels(), image(3).pixels(), "{mode}");
    }
    let sppm = |threads: usize| {
        let render = RenderSettings {
            threads,
            emission: camera(),
            ..base()
        };
        SppmRenderer::new(SppmSettings::new(render, 3))
            .render(partitioned.scene(), &())
            .unwrap()
            .image
    };
    assert_eq!(sppm(1).pixels(), sppm(3).pixels());
}

#[test]
fn camera_driven_emission_is_refused_where_it_cannot_apply() {
    let path_trace = RenderSettings {
        mode: Mode::PathTrace,
        emission: camera(),
        ..base()
    };
    assert!(matches!(path_trace.validate(), Err(RenderError::BadEmission(m)) if m.contains("path-trace")));
    for (floor, pilot_photons) in [(0.0, 100), (1.5, 100), (f32::NAN, 100), (0.5, 0)] {
        let settings = RenderSettings {
            emission: PhotonEmission::CameraDriven(GuideOptions { pilot_photons, floor }),
            ..base()
        };
        assert!(
            matches!(settings.validate(), Err(RenderError::BadEmission(_))),
            "{floor} {pilot_photons}"
        );
    }
    let renderer = Renderer::new(
        GeometryCube,
        RenderSettings {
            emission: camera(),
            ..base()
        },
    );
    let auto = AutoPhotons::new(4_000, 0.5);
    let err = renderer
        .build_photon_cache_auto(&rooms(2), &auto, &(), &mut Default::default())
        .unwrap_err();
    assert!(matches!(err, RenderError::BadEmission(_)), "{err}");
}

#[test]
fn a_camera_driven_cache_is_named_apart_from_a_uniform_one() {
    let partitioned = rooms(2);
    let uniform = CacheIdentity::of_run(&Renderer::new(GeometryCube, base()), &partitioned);
    let guided = CacheIdentity::of_run(
        &Renderer::new(
            GeometryCube,
            RenderSettings {
                emission: camera(),
                ..base()
            },
        ),
        &partitioned,
    );
    assert_eq!(guided.get("emission"), Some("camera/pilot=8192/floor=0.125"));
    let err = uniform.check_file(&guided).unwrap_err().to_string();
    assert!(err.contains("emission"), "{err}");
    let err = guided.check_file(&uniform).unwrap_err().to_string();
    assert!(err.contains("emission"), "{err}");
}

#[test]
fn camera_driven_shards_merge_into_the_single_run() {
    let partitioned = rooms(3);
    let run = |first_pass: u64, passes: u64| {
        let settings = ProgressiveSettings {
            first_pass,
            ..ProgressiveSettings::new(
                RenderSettings {
                    emission: camera(),
                    ..base()
                },
                passes,
            )
        };
        let renderer = ProgressiveRenderer::new(GeometryCube, settings);
        let out = renderer.render(&partitioned, &()).unwrap();
        assert!(
            out.identity.contains("emission=camera/pilot=8192/floor=0.125"),
            "{}",
            out.identity
        );
        Shard::from_accumulation(&out.accumulation, "doorway-rooms-3", &out.identity).unwrap()
    };
    let single = run(0, 4);
    let merged = Shard::merge(&[run(2, 2), run(0, 2)]).unwrap();
    let bits = |s: &Shard| {
        s.mean()
            .pixels()
            .iter()
            .map(|p| p.to_array().map(f32::to_bits))
            .collect::<Vec<_>>()
    };
    assert_eq!(bits(&merged), bits(&single));
}

#[test]
fn a_cache_for_several_cameras_learns_what_all_of_them_see() {
    let partitioned = rooms(1);
    // An image wider than the 128 camera rays a single camera is read with.
    let settings = RenderSettings {
        width: 256,
        height: 192,
        emission: camera(),
        ..base()
    };
    let renderer = Renderer::new(GeometryCube, settings);
    let seen_from = |cameras: &[Camera]| {
        let mut stats = RenderStats::default();
        renderer
            .build_photon_cache_seen_from(&partitioned, cameras, &(), &mut stats)
            .unwrap();
        stats.emission.expect("camera-driven")
    };
    let own = *partitioned.scene().camera();
    // The room's opposite half, seen from its far corner.
    let back = Camera::new(
        Vec3::new(0.9, 0.55, 0.92),
        Vec3::new(0.05, 0.35, 0.4),
        Vec3::Y,
        70f32.to_radians(),
    );
    let one = seen_from(&[own]);
    let both = seen_from(&[own, back]);
    assert!(both.seen_fraction > one.seen_fraction + 0.05, "{one:?} {both:?}");
    assert!(both.keep_rate > one.keep_rate, "{one:?} {both:?}");
    // Two cameras hold no more points than one (each a grid half as fine).
    assert!(both.seen_points <= one.seen_points, "{one:?} {both:?}");
    // build_photon_cache is the scene's own camera.
    let mut stats = RenderStats::default();
    renderer
        .build_photon_cache(&partitioned, &(), &mut stats)
        .unwrap();
    assert_eq!(stats.emission.unwrap().keep_rate, one.keep_rate);
}
