//! The library's shard identity names the estimator and the partition, not only the settings:
//! shards of one run merge, shards made with another estimator or another partition of the
//! same scene are refused, without any command line adding to the identity.

use pm_render::progressive::{ProgressiveRenderer, ProgressiveSettings, Shard, ShardError};
use pm_render::{EstimatorKind, Mode, RenderSettings};
use pm_trace::{CreaseAngle, Partitioned, Partitioner, SingleMap, scenes};

fn shard(kind: EstimatorKind, partitioned: &Partitioned, first_pass: u64) -> Shard {
    let render = RenderSettings {
        width: 8,
        height: 8,
        photons: 2_000,
        mode: Mode::PhotonMap,
        seed: 4,
        threads: 1,
        ..RenderSettings::default()
    };
    let settings = ProgressiveSettings {
        first_pass,
        ..ProgressiveSettings::new(render, 1)
    };
    ProgressiveRenderer::new(kind, settings)
        .render(partitioned, &())
        .unwrap()
        .shard("lit-unlit-rooms")
        .unwrap()
}

#[test]
fn shards_of_another_estimator_or_partition_are_refused() {
    let scene = scenes::build("lit-unlit-rooms").unwrap();
    let crease = CreaseAngle::default().partition(scene.clone()).unwrap();
    let single = SingleMap.partition(scene).unwrap();
    let first = shard(EstimatorKind::GeometryCube, &crease, 0);

    let same = shard(EstimatorKind::GeometryCube, &crease, 1);
    let merged = Shard::merge(&[first.clone(), same]).unwrap();
    assert_eq!(merged.header("merged").passes, 2);

    for (other, what) in [
        (shard(EstimatorKind::Disc, &crease, 1), "estimator"),
        (shard(EstimatorKind::GeometryCube, &single, 1), "partition"),
    ] {
        match Shard::merge(&[first.clone(), other]) {
            Err(ShardError::SettingsMismatch { a, b }) => assert_ne!(a, b, "{what}"),
            other => panic!("a shard of another {what} was not refused: {other:?}"),
        }
    }
}
