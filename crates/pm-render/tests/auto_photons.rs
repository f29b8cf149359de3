//! The automatic photon count: batches are prefixes of one photon stream, so the render at the
//! count it stops at is bit-identical to a plain render with that count; the change between
//! batches falls as photons grow; bad settings are refused by type.

use pm_render::{AutoPhotons, GeometryCube, Image, Mode, RenderError, RenderSettings, Renderer};
use pm_trace::{
    CreaseAngle, Partitioned, Partitioner, TraceOptions, scenes, trace_photon_paths, trace_photons,
};

fn cornell() -> Partitioned {
    CreaseAngle::default()
        .partition(scenes::build("cornell-box").unwrap())
        .unwrap()
}

fn settings(mode: Mode) -> RenderSettings {
    RenderSettings {
        width: 16,
        height: 16,
        samples_per_pixel: 1,
        photons: 1_000,
        mode,
        seed: 7,
        ..RenderSettings::default()
    }
}

fn bits(image: &Image) -> Vec<[u32; 3]> {
    image
        .pixels()
        .iter()
        .map(|p| p.to_array().map(f32::to_bits))
        .collect()
}

#[test]
fn two_ranges_of_paths_are_the_whole_run() {
    let partitioned = cornell();
    let options = TraceOptions {
        photons: 5_000,
        seed: 3,
        ..TraceOptions::default()
    };
    let (scene, assignment) = (partitioned.scene(), partitioned.assignment());
    let whole = trace_photons(scene, assignment, &options).unwrap();
    let a = trace_photon_paths(scene, assignment, &options, 0..1_700).unwrap();
    let b = trace_photon_paths(scene, assignment, &options, 1_700..5_000).unwrap();
    assert_eq!(a.stats().emitted + b.stats().emitted, 5_000);
    for m in 0..whole.photons_per_map().len() as u32 {
        let joined: Vec<_> = a.photons(m).iter().chain(b.photons(m)).copied().collect();
        assert_eq!(joined, whole.photons(m), "map {m}");
    }
    assert!(trace_photon_paths(scene, assignment, &options, 10..10).is_err());
    assert!(trace_photon_paths(scene, assignment, &options, 0..5_001).is_err());
}

#[test]
fn the_chosen_count_renders_the_bits_of_a_plain_run_with_it() {
    let partitioned = cornell();
    for mode in [Mode::FinalGather, Mode::PhotonMap] {
        let renderer = Renderer::new(GeometryCube, settings(mode));
        let auto = AutoPhotons {
            max_batches: 4,
            ..AutoPhotons::new(1_000, 0.05)
        };
        let out = renderer.render_auto(&partitioned, &auto, &()).unwrap();
        let report = out.stats.auto_photons.clone().unwrap();
        assert_eq!(report.batches.last().unwrap().photons, report.photons);
        assert!(report.photons >= 2_000, "{report:?}");
        let plain = Renderer::new(
            GeometryCube,
            RenderSettings {
                photons: report.photons,
                ..settings(mode)
            },
        )
        .render(&partitioned, &())
        .unwrap();
        assert_eq!(plain.stats.photons_stored, out.stats.photons_stored);
        assert_eq!(plain.stats.cache_points, out.stats.cache_points);
        assert!(bits(&plain.image) == bits(&out.image), "{mode}: images differ");
    }
}

#[test]
fn the_change_falls_as_photons_grow() {
    let partitioned = cornell();
    let renderer = Renderer::new(GeometryCube, settings(Mode::FinalGather));
    let auto = AutoPhotons {
        max_batches: 5,
        probes: 512,
        ..AutoPhotons::new(2_000, 1e-6)
    };
    let mut stats = Default::default();
    renderer
        .build_photon_cache_auto(&partitioned, &auto, &(), &mut stats)
        .unwrap();
    let report = stats.auto_photons.unwrap();
    assert!(!report.converged);
    assert_eq!(report.batches.len(), 5);
    assert_eq!(report.photons, 2_000 << 4);
    let changes: Vec<f64> = report.batches.iter().filter_map(|b| b.change).collect();
    assert_eq!(changes.len(), 4);
    assert!(changes.iter().all(|c| c.is_finite() && *c > 0.0), "{changes:?}");
    eprintln!("changes {changes:?}");
    // Noise falls about as 1/sqrt(N): four doublings should cut the change well below half.
    assert!(changes[3] < 0.6 * changes[0], "{changes:?}");
}

#[test]
fn bad_settings_are_refused() {
    let partitioned = cornell();
    let renderer = Renderer::new(GeometryCube, settings(Mode::PhotonMap));
    for threshold in [0.0, 1.0, -0.1, 1.5, f64::NAN, f64::INFINITY] {
        let err = renderer
            .render_auto(&partitioned, &AutoPhotons::new(1_000, threshold), &())
            .unwrap_err();
        assert!(
            matches!(err, RenderError::BadAutoThreshold(_)),
            "{threshold}: {err}"
        );
    }
    let refused = [
        AutoPhotons::new(0, 0.1),
        AutoPhotons::new((1 << 24) + 1, 0.1),
        AutoPhotons {
            max_batches: 1,
            ..AutoPhotons::new(1_000, 0.1)
        },
        AutoPhotons {
            max_photons: 500,
            ..AutoPhotons::new(1_000, 0.1)
        },
        AutoPhotons {
            probes: 0,
            ..AutoPhotons::new(1_000, 0.1)
        },
    ];
    for auto in refused {
        let err = renderer.render_auto(&partitioned, &auto, &()).unwrap_err();
        assert!(matches!(err, RenderError::BadAutoPhotons(_)), "{auto:?}: {err}");
    }
    let path_tracer = Renderer::new(GeometryCube, settings(Mode::PathTrace));
    let err = path_tracer
        .render_auto(&partitioned, &AutoPhotons::new(1_000, 0.1), &())
        .unwrap_err();
    assert!(matches!(err, RenderError::UnreadMaps(_)), "{err}");
}
