//! The accordion's two facet orientations receive direct irradiance E₀ cos 15° and E₀ cos 75°
//! (ratio 3.73), measured from photon counts.

use pm_trace::{CreaseAngle, PartId, Partitioner, PhotonKind, TraceOptions, scenes, trace_photons};

#[test]
fn facet_irradiance_ratio_is_cos15_over_cos75() {
    let scene = scenes::build("accordion").unwrap();
    let maps = CreaseAngle::default()
        .partition(scene.clone())
        .unwrap()
        .assignment()
        .clone();
    let n = 400_000;
    let traced = trace_photons(
        &scene,
        &maps,
        &TraceOptions {
            photons: n,
            seed: 8,
            max_bounces: 8,
            pass: 0,
        },
    )
    .unwrap();
    let per_photon = scene.lights()[0].power().x as f64 / n as f64;
    // Direct photon counts per orientation; each facet is 0.25 m × 1 m.
    let (mut facing, mut away) = (0u64, 0u64);
    for f in 0..8u32 {
        let m = maps.map_of(PartId(f));
        let count = traced
            .photons(m)
            .iter()
            .filter(|p| p.kind == PhotonKind::Direct)
            .count() as u64;
        let normal = scene.meshes()[0].half_edge_mesh().face_normal(pm_geom::FaceId(f));
        assert!(normal.y > 0.7, "facet {f} faces down");
        if normal.x < 0.0 {
            facing += count
        } else {
            away += count
        }
    }
    let area = 4.0 * 0.25;
    let e0 = 10.0f64;
    let e_facing = facing as f64 * per_photon / area;
    let e_away = away as f64 * per_photon / area;
    let se = |count: u64, e: f64| e / (count as f64).sqrt();
    let cos15 = 15f64.to_radians().cos();
    let cos75 = 75f64.to_radians().cos();
    assert!(
        (e_facing - e0 * cos15).abs() < 3.0 * se(facing, e_facing),
        "{e_facing} vs {}",
        e0 * cos15
    );
    assert!(
        (e_away - e0 * cos75).abs() < 3.0 * se(away, e_away),
        "{e_away} vs {}",
        e0 * cos75
    );
    let ratio = e_facing / e_away;
    let rel = (1.0 / facing as f64 + 1.0 / away as f64).sqrt();
    assert!((ratio / (cos15 / cos75) - 1.0).abs() < 3.0 * rel, "ratio {ratio}");
}
