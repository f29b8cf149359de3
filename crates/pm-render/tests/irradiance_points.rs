//! The cache's irradiance points against brute force: each point keeps its own normal and
//! irradiance after the index reorders the positions (duplicate positions included), and a
//! lookup answers with the nearest point whose normal agrees.

use pm_kdtree::Neighbours;
use pm_render::cache::{IrradiancePoint, IrradiancePoints, NORMAL_AGREEMENT};
use pm_render::glam::Vec3;
use pm_trace::Rng;

fn random_points(n: usize, rng: &mut Rng) -> Vec<IrradiancePoint> {
    let mut unit = || Vec3::new(rng.next_f32(), rng.next_f32(), rng.next_f32());
    (0..n)
        .map(|i| {
            // Every fifth point repeats the position before it, with its own normal.
            let position = unit() * 2.0 - Vec3::ONE;
            let normal = (unit() * 2.0 - Vec3::ONE).normalize_or(Vec3::Y);
            IrradiancePoint {
                position,
                normal,
                irradiance: Vec3::splat(i as f32),
            }
        })
        .collect::<Vec<_>>()
        .chunks(5)
        .flat_map(|c| {
            let mut c = c.to_vec();
            let (first, at) = (c[0].position, 1 % c.len());
            c[at].position = first;
            c
        })
        .collect()
}

#[test]
fn every_point_keeps_its_own_fields() {
    let mut rng = Rng::new(1, 2);
    let points = random_points(2_000, &mut rng);
    let indexed = IrradiancePoints::new(points.clone()).unwrap();
    assert_eq!(indexed.len(), points.len());
    let mut seen: Vec<IrradiancePoint> = indexed.iter().collect();
    let key = |p: &IrradiancePoint| p.irradiance.x as usize;
    seen.sort_by_key(key);
    for (a, b) in seen.iter().zip(&points) {
        // The irradiance names the input point; position and normal must be that point's,
        // except that two points at one position may have traded normals.
        assert_eq!(a.position, b.position);
        let twin_normal = points
            .iter()
            .filter(|p| p.position == b.position)
            .any(|p| p.normal == a.normal);
        assert!(twin_normal, "point {} lost its normal", key(b));
    }
}

#[test]
fn a_lookup_is_the_nearest_agreeing_point() {
    let mut rng = Rng::new(3, 4);
    let points = random_points(3_000, &mut rng);
    let indexed = IrradiancePoints::new(points.clone()).unwrap();
    let mut neighbours = Neighbours::new();
    let mut checked = 0;
    for _ in 0..500 {
        let q = Vec3::new(rng.next_f32(), rng.next_f32(), rng.next_f32()) * 2.0 - Vec3::ONE;
        let n = (Vec3::new(rng.next_f32(), rng.next_f32(), rng.next_f32()) * 2.0 - Vec3::ONE)
            .normalize_or(Vec3::Y);
        let radius = 0.3;
        let got = indexed.nearest_agreeing(q, n, radius, &mut neighbours);
        // Brute force: among the 8 nearest within the radius (the lookup's candidates), the
        // nearest that agrees.
        let mut near: Vec<&IrradiancePoint> = points
            .iter()
            .filter(|p| p.position.distance(q) <= radius)
            .collect();
        near.sort_by(|a, b| a.position.distance(q).total_cmp(&b.position.distance(q)));
        near.truncate(8);
        let expected = near.iter().find(|p| p.normal.dot(n) >= NORMAL_AGREEMENT);
        match (got, expected) {
            (None, None) => {}
            (Some(e), Some(p)) => {
                // Equal distances may pick either point; accept any agreeing point at the
                // same distance.
                let d = p.position.distance(q);
                assert!(
                    points.iter().any(|o| o.irradiance == e
                        && (o.position.distance(q) - d).abs() < 1e-6
                        && o.normal.dot(n) >= NORMAL_AGREEMENT),
                    "lookup at {q} gave {e}, brute force {}",
                    p.irradiance
                );
                checked += 1;
            }
            (got, expected) => panic!(
                "lookup at {q}: {got:?} against {:?}",
                expected.map(|p| p.irradiance)
            ),
        }
    }
    assert!(checked > 100, "{checked} lookups found a point");
}

#[test]
fn non_finite_positions_are_refused() {
    let bad = IrradiancePoint {
        position: Vec3::new(f32::NAN, 0.0, 0.0),
        normal: Vec3::Y,
        irradiance: Vec3::ONE,
    };
    assert!(IrradiancePoints::new(vec![bad]).is_err());
    assert!(IrradiancePoints::new(Vec::new()).unwrap().is_empty());
}
