//! The extension traits implemented outside the crate: a custom light and a custom
//! partitioner plug into tracing and map building.

use pm_trace::glam::Vec3;
use pm_trace::{
    EmittedRay, Light, LightSample, MapAssignment, PartitionError, Partitioned, Partitioner, PhotonKind,
    PhotonMaps, Ray, Rng, Scene, Surface, TraceOptions, trace_photons,
};

/// A laser: every photon leaves `origin` straight down.
#[derive(Clone, Debug)]
struct Laser {
    origin: Vec3,
    power: Vec3,
}

impl Light for Laser {
    fn power(&self) -> Vec3 {
        self.power
    }
    fn emit(&self, _rng: &mut Rng) -> EmittedRay {
        EmittedRay {
            ray: Ray {
                origin: self.origin,
                direction: Vec3::NEG_Y,
            },
            weight: Vec3::ONE,
        }
    }
    fn sample_incident(&self, _point: Vec3, _normal: Vec3, _rng: &mut Rng) -> Option<LightSample> {
        None
    }
}

/// One map per part.
struct MapPerPart;

impl Partitioner for MapPerPart {
    fn partition(&self, scene: Scene) -> Result<Partitioned, PartitionError> {
        let n = scene.part_count() as u32;
        Partitioned::new(scene, MapAssignment::new((0..n).collect()))
    }
}

#[test]
fn custom_light_and_partitioner_drive_tracing() {
    // Two black floor tiles side by side; the laser hits the second one only.
    let p = [
        Vec3::new(0.0, 0.0, 0.0),
        Vec3::new(0.0, 0.0, 1.0),
        Vec3::new(1.0, 0.0, 1.0),
        Vec3::new(1.0, 0.0, 0.0),
        Vec3::new(2.0, 0.0, 1.0),
        Vec3::new(2.0, 0.0, 0.0),
    ];
    let scene = Scene::builder()
        .mesh(&p, &[[0u32, 1, 2, 3], [3, 2, 4, 5]], Surface::diffuse(Vec3::ZERO))
        .light(Laser {
            origin: Vec3::new(1.5, 1.0, 0.5),
            power: Vec3::splat(2.0),
        })
        .build()
        .unwrap();
    let maps = MapPerPart.partition(scene.clone()).unwrap().assignment().clone();
    assert_eq!(maps.map_count(), 2);
    let traced = trace_photons(
        &scene,
        &maps,
        &TraceOptions {
            photons: 1000,
            seed: 0,
            max_bounces: 4,
            pass: 0,
        },
    )
    .unwrap();
    assert_eq!(traced.stats().stored, vec![[0, 0, 0], [1000, 0, 0]]);
    let p = traced.photons(1)[0];
    assert_eq!(p.kind, PhotonKind::Direct);
    assert!((p.position - Vec3::new(1.5, 0.0, 0.5)).length() < 1e-4);
    assert!((p.power - Vec3::splat(0.002)).abs().max_element() < 1e-7);
    let built = PhotonMaps::build(&scene, &maps, traced).unwrap();
    assert_eq!(built.map(0).tree().len(), 0);
    assert_eq!(built.map(1).tree().len(), 1000);
    assert!((built.map(1).geometry().total_area() - 1.0).abs() < 1e-5);
}
