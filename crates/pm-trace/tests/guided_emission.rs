//! Camera-driven emission is unbiased and deterministic: in a closed grey unit box lit by a
//! point light, with only the floor "seen", a guided trace stores on each face the direct
//! power the face's solid angle says (closed form) and the same total power as uniform
//! emission (replicates, standard errors), while putting more of its traced paths on the
//! floor; and the same seed gives the same guide and photons on any thread count.

mod common;

use pm_trace::glam::{DVec3, Vec3};
use pm_trace::{
    EmissionGuide, GuideOptions, MapAssignment, Partitioner, PhotonKind, PointLight, Scene, SingleMap,
    Surface, TraceOptions, TracedPhotons, trace_guided_photon_paths, trace_photons,
};

const LIGHT: Vec3 = Vec3::new(0.3, 0.6, 0.4);
const POWER: f32 = 12.0;

fn grey_box() -> (Scene, MapAssignment) {
    let (corners, faces) = common::unit_box();
    let scene = Scene::builder()
        .mesh(&corners, &faces, Surface::diffuse(Vec3::splat(0.5)))
        .light(PointLight::new(LIGHT, Vec3::splat(POWER)))
        .build()
        .unwrap();
    let assignment = SingleMap.partition(scene.clone()).unwrap().assignment().clone();
    (scene, assignment)
}

/// Only the floor (y = 0) is seen.
fn floor_seen(_map: u32, p: Vec3) -> bool {
    p.y < 1e-3
}

/// The face of the unit box a photon lies on: 0/1 x = 0/1, 2/3 y = 0/1, 4/5 z = 0/1.
fn face(p: Vec3) -> usize {
    let d = [p.x, 1.0 - p.x, p.y, 1.0 - p.y, p.z, 1.0 - p.z];
    (0..6).min_by(|&a, &b| d[a].total_cmp(&d[b])).unwrap()
}

/// Power stored per face (summed over channels), of `kind` or of every kind.
fn power_per_face(traced: &TracedPhotons, kind: Option<PhotonKind>) -> [f64; 6] {
    let mut out = [0.0; 6];
    for p in traced.photons_per_map().iter().flatten() {
        if kind.is_none_or(|k| p.kind == k) {
            out[face(p.position)] += f64::from(p.power.element_sum());
        }
    }
    out
}

/// Solid angle of the rectangle `[x0, x1] × [y0, y1]` in a plane at distance `z` from the
/// point (coordinates relative to the point's foot on the plane).
fn rectangle_solid_angle(x0: f64, x1: f64, y0: f64, y1: f64, z: f64) -> f64 {
    let f = |x: f64, y: f64| (x * y / (z * (x * x + y * y + z * z).sqrt())).atan();
    f(x1, y1) - f(x0, y1) - f(x1, y0) + f(x0, y0)
}

/// Direct power per face (summed over channels) from the closed form `Φ Ω / 4π`.
fn direct_power_per_face() -> [f64; 6] {
    let l = LIGHT.as_dvec3();
    let [x, y, z] = l.to_array();
    let omega = [
        rectangle_solid_angle(-y, 1.0 - y, -z, 1.0 - z, x),
        rectangle_solid_angle(-y, 1.0 - y, -z, 1.0 - z, 1.0 - x),
        rectangle_solid_angle(-x, 1.0 - x, -z, 1.0 - z, y),
        rectangle_solid_angle(-x, 1.0 - x, -z, 1.0 - z, 1.0 - y),
        rectangle_solid_angle(-x, 1.0 - x, -y, 1.0 - y, z),
        rectangle_solid_angle(-x, 1.0 - x, -y, 1.0 - y, 1.0 - z),
    ];
    let total: f64 = omega.iter().sum();
    assert!((total - 4.0 * std::f64::consts::PI).abs() < 1e-9, "{total}");
    omega.map(|o| 3.0 * f64::from(POWER) * o / (4.0 * std::f64::consts::PI))
}

/// Mean and standard error of the mean over replicates, per face.
fn mean_and_error(replicates: &[[f64; 6]]) -> ([f64; 6], [f64; 6]) {
    let n = replicates.len() as f64;
    let mut mean = [0.0; 6];
    let mut error = [0.0; 6];
    for f in 0..6 {
        mean[f] = replicates.iter().map(|r| r[f]).sum::<f64>() / n;
        let var = replicates.iter().map(|r| (r[f] - mean[f]).powi(2)).sum::<f64>() / (n - 1.0);
        error[f] = (var / n).sqrt();
    }
    (mean, error)
}

const TRACED: u32 = 20_000;
const REPLICATES: u64 = 10;

fn guided(scene: &Scene, assignment: &MapAssignment, seed: u64) -> (TracedPhotons, EmissionGuide) {
    let options = TraceOptions {
        seed,
        max_bounces: 16,
        ..TraceOptions::default()
    };
    let guide = EmissionGuide::learn(
        scene,
        assignment,
        &options,
        &GuideOptions {
            pilot_photons: 16_384,
            floor: 0.125,
        },
        &floor_seen,
    )
    .unwrap();
    let photons = guide.photons_to_emit(TRACED).unwrap();
    let options = TraceOptions { photons, ..options };
    let traced = trace_guided_photon_paths(scene, assignment, &options, 0..photons, &guide).unwrap();
    (traced, guide)
}

#[test]
fn guided_photons_store_the_closed_form_direct_power_and_uniform_emissions_total() {
    let (scene, assignment) = grey_box();
    let mut guided_direct = Vec::new();
    let mut guided_total = Vec::new();
    let mut uniform_total = Vec::new();
    let mut floor_share = [0.0f64; 2];
    for seed in 0..REPLICATES {
        let (traced, guide) = guided(&scene, &assignment, seed);
        // Paths the camera never sees were dropped: fewer traced than emitted, about as many
        // as asked for.
        assert!(guide.keep_rate() < 0.8, "{}", guide.keep_rate());
        let stats = traced.stats();
        assert!(stats.traced < stats.emitted);
        assert!(
            (stats.traced as f64 / f64::from(TRACED) - 1.0).abs() < 0.05,
            "{}",
            stats.traced
        );
        guided_direct.push(power_per_face(&traced, Some(PhotonKind::Direct)));
        guided_total.push(power_per_face(&traced, None));
        let floor = |t: &TracedPhotons| {
            let n = t
                .photons_per_map()
                .iter()
                .flatten()
                .filter(|p| face(p.position) == 2)
                .count();
            n as f64 / t.stats().traced as f64
        };
        floor_share[0] += floor(&traced);
        let options = TraceOptions {
            photons: TRACED,
            seed: 1000 + seed,
            max_bounces: 16,
            ..TraceOptions::default()
        };
        let uniform = trace_photons(&scene, &assignment, &options).unwrap();
        floor_share[1] += floor(&uniform);
        uniform_total.push(power_per_face(&uniform, None));
    }
    let exact = direct_power_per_face();
    let (direct, direct_se) = mean_and_error(&guided_direct);
    let (total, total_se) = mean_and_error(&guided_total);
    let (uniform, uniform_se) = mean_and_error(&uniform_total);
    for f in 0..6 {
        let z = (direct[f] - exact[f]) / direct_se[f];
        assert!(
            z.abs() < 4.0,
            "face {f}: direct {} vs {} ({z:.2} se)",
            direct[f],
            exact[f]
        );
        let se = (total_se[f].powi(2) + uniform_se[f].powi(2)).sqrt();
        let z = (total[f] - uniform[f]) / se;
        assert!(
            z.abs() < 4.0,
            "face {f}: total {} vs uniform {} ({z:.2} se)",
            total[f],
            uniform[f]
        );
    }
    // The floor's share of stored photons per traced path grows.
    assert!(floor_share[0] > 1.5 * floor_share[1], "{floor_share:?}");
    // The guided estimate is no worse than uniform emission's on the floor.
    assert!(
        total_se[2] < uniform_se[2] * 1.2,
        "{} vs {}",
        total_se[2],
        uniform_se[2]
    );
    let summed: DVec3 = DVec3::splat(direct.iter().sum::<f64>());
    assert!(
        (summed.x / (3.0 * f64::from(POWER)) - 1.0).abs() < 0.02,
        "{summed}"
    );
}

#[test]
fn guide_and_guided_photons_are_the_same_on_one_and_three_threads() {
    let (scene, assignment) = grey_box();
    let run = |threads: usize| {
        rayon::ThreadPoolBuilder::new()
            .num_threads(threads)
            .build()
            .unwrap()
            .install(|| guided(&scene, &assignment, 5))
    };
    let (a, ga) = run(1);
    let (b, gb) = run(3);
    assert_eq!(ga, gb);
    assert_eq!(a.photons_per_map(), b.photons_per_map());
    assert_eq!(a.stats().traced, b.stats().traced);
}

#[test]
fn a_guide_that_sees_nothing_changes_nothing() {
    let (scene, assignment) = grey_box();
    let options = TraceOptions {
        photons: 3_000,
        seed: 3,
        ..TraceOptions::default()
    };
    let guide = EmissionGuide::learn(
        &scene,
        &assignment,
        &options,
        &GuideOptions::default(),
        &|_, _| false,
    )
    .unwrap();
    assert_eq!(guide.seen_fraction(), 0.0);
    assert_eq!(guide.keep_rate(), 1.0);
    let guided = trace_guided_photon_paths(&scene, &assignment, &options, 0..3_000, &guide).unwrap();
    let uniform = trace_photons(&scene, &assignment, &options).unwrap();
    assert_eq!(guided.photons_per_map(), uniform.photons_per_map());
}

/// The floor's extreme: a floor of 1 keeps every photon whatever the pilot saw, and draws
/// nothing more from any path's stream, so the photons are uniform emission's bit for bit.
#[test]
fn a_floor_of_one_keeps_every_photon_as_uniform_emission() {
    let (scene, assignment) = grey_box();
    let options = TraceOptions {
        photons: 3_000,
        seed: 4,
        ..TraceOptions::default()
    };
    let guide = EmissionGuide::learn(
        &scene,
        &assignment,
        &options,
        &GuideOptions {
            pilot_photons: 4_096,
            floor: 1.0,
        },
        &floor_seen,
    )
    .unwrap();
    assert!(guide.seen_fraction() > 0.0 && guide.seen_fraction() < 1.0);
    assert_eq!(guide.keep_rate(), 1.0);
    assert_eq!(guide.photons_to_emit(3_000).unwrap(), 3_000);
    let guided = trace_guided_photon_paths(&scene, &assignment, &options, 0..3_000, &guide).unwrap();
    let uniform = trace_photons(&scene, &assignment, &options).unwrap();
    assert_eq!(guided.photons_per_map(), uniform.photons_per_map());
    assert_eq!(guided.stats().traced, 3_000);
}
