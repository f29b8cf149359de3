//! The photon maps the estimator benches read: 100,000 photons (seed 0) traced into the maps of
//! a partition, built.

use photon_maps::trace::{Partitioner, PhotonMaps, Scene, TraceOptions, trace_photons};

/// `scene`'s photon maps under `partitioner`.
pub fn maps(scene: &Scene, partitioner: &dyn Partitioner) -> PhotonMaps {
    let assignment = partitioner
        .partition(scene.clone())
        .expect("the scene partitions")
        .assignment()
        .clone();
    let options = TraceOptions {
        photons: 100_000,
        seed: 0,
        ..TraceOptions::default()
    };
    let traced = trace_photons(scene, &assignment, &options).expect("the scene traces");
    PhotonMaps::build(scene, &assignment, traced).expect("the maps build")
}
