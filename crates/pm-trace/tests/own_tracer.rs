//! Photons from a tracer written outside the crate become photon maps through the public
//! constructors alone, and bad photons are refused with errors that say which and why.

use pm_trace::glam::Vec3;
use pm_trace::{
    CreaseAngle, MapError, Partitioner, Photon, PhotonFault, PhotonKind, PhotonMaps, PointLight, Ray,
    RayKind, Scene, Surface, TraceError, TracedPhotons,
};

/// Two 1 m floor tiles side by side, folded 90° apart so that crease maps keep them apart.
fn scene() -> Scene {
    let p = [
        Vec3::new(0.0, 0.0, 0.0),
        Vec3::new(0.0, 0.0, 1.0),
        Vec3::new(1.0, 0.0, 1.0),
        Vec3::new(1.0, 0.0, 0.0),
        Vec3::new(1.0, 1.0, 1.0),
        Vec3::new(1.0, 1.0, 0.0),
    ];
    Scene::builder()
        .mesh(
            &p,
            &[[0u32, 1, 2, 3], [3, 2, 4, 5]],
            Surface::diffuse(Vec3::splat(0.5)),
        )
        .light(PointLight::new(Vec3::new(0.5, 0.5, 0.5), Vec3::splat(4.0)))
        .build()
        .unwrap()
}

/// "Our own tracer": a 10 × 10 grid of rays straight down onto the floor, one photon each.
fn own_photons(scene: &Scene, maps: &pm_trace::MapAssignment) -> Vec<Vec<Photon>> {
    let mut out = vec![Vec::new(); maps.map_count() as usize];
    for i in 0..10 {
        for j in 0..10 {
            let origin = Vec3::new((i as f32 + 0.5) / 10.0, 0.5, (j as f32 + 0.5) / 10.0);
            let ray = Ray::new(origin, Vec3::NEG_Y);
            let hit = scene.intersect(&ray, 10.0, RayKind::Other).unwrap();
            out[maps.map_of(hit.part) as usize].push(Photon {
                position: hit.position,
                power: Vec3::splat(0.01),
                direction: Vec3::NEG_Y,
                kind: PhotonKind::Direct,
            });
        }
    }
    out
}

#[test]
fn photons_of_our_own_become_photon_maps() {
    let partitioned = CreaseAngle::default().partition(scene()).unwrap();
    let (scene, assignment) = (partitioned.scene(), partitioned.assignment());
    assert_eq!(assignment.map_count(), 2);
    let photons = own_photons(scene, assignment);
    let traced = TracedPhotons::new(photons, 100).unwrap();
    assert_eq!(traced.stats().emitted, 100);
    let floor_map = assignment.map_of(pm_trace::PartId(0)); // the first face: the floor tile
    let mut expected = vec![[0u64; 3]; 2];
    expected[floor_map as usize][PhotonKind::Direct as usize] = 100;
    assert_eq!(traced.stats().stored, expected);
    let maps = PhotonMaps::build(scene, assignment, traced).unwrap();
    maps.validate().unwrap();
    assert_eq!(maps.map(floor_map).tree().len(), 100);
    assert_eq!(maps.map(1 - floor_map).tree().len(), 0);
}

/// A change that makes a photon unfit for a map.
type Spoil = fn(&mut Photon);

#[test]
fn bad_photons_are_refused_naming_the_photon_and_the_fault() {
    let partitioned = CreaseAngle::default().partition(scene()).unwrap();
    let (scene, assignment) = (partitioned.scene(), partitioned.assignment());
    let good = own_photons(scene, assignment);
    let map = good.iter().position(|m| !m.is_empty()).unwrap();
    let cases: [(Spoil, PhotonFault); 4] = [
        (|p| p.position.x = f32::NAN, PhotonFault::Position),
        (|p| p.direction = Vec3::ZERO, PhotonFault::Direction),
        (|p| p.power.y = f32::INFINITY, PhotonFault::Power),
        (|p| p.power.z = -1.0, PhotonFault::Power),
    ];
    for (spoil, reason) in cases {
        let mut photons = good.clone();
        spoil(&mut photons[map][7]);
        assert_eq!(
            TracedPhotons::new(photons, 100).err(),
            Some(TraceError::InvalidPhoton {
                map,
                index: 7,
                reason
            })
        );
    }
    // Photons for another number of maps than the assignment has are refused by the maps.
    let one_map = vec![good.concat()];
    let traced = TracedPhotons::new(one_map, 100).unwrap();
    assert!(matches!(
        PhotonMaps::build(scene, assignment, traced),
        Err(MapError::Mismatch(_))
    ));
}
