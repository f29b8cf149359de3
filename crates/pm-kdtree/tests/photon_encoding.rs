//! The 20-byte photon: size, and decoding error against the documented bounds (power within
//! one step of 2^(1/100), 0.7 %, per channel at any absolute power in f32's normal range and over a factor 2⁴⁰ within
//! one map, direction within 0.05°) over many random photons.

mod common;

use common::*;
use glam::Vec3;
use pm_kdtree::{CompactPhoton, Photon, PhotonKind, PhotonTree, PowerScale};

fn photon(power: Vec3, direction: Vec3, kind: PhotonKind) -> Photon {
    Photon {
        position: Vec3::new(1.5, -2.0, 0.25),
        power,
        direction,
        kind,
    }
}

#[test]
fn compact_photon_is_20_bytes() {
    assert_eq!(size_of::<CompactPhoton>(), 20);
}

#[test]
fn a_tree_holds_at_most_21_bytes_per_photon() {
    let mut rng = Rng::new(seed());
    for n in [1_000usize, 100_000] {
        let photons: Vec<Photon> = (0..n)
            .map(|_| Photon {
                position: Vec3::new(rng.f32(), rng.f32(), rng.f32()),
                ..photon(Vec3::ONE, Vec3::Y, PhotonKind::Direct)
            })
            .collect();
        let tree = PhotonTree::build(photons).unwrap();
        let per_photon = tree.heap_bytes() as f64 / n as f64;
        assert!(
            (20.0..=21.0).contains(&per_photon),
            "{n} photons: {per_photon:.2} bytes each"
        );
    }
}

/// Relative error of a decoded channel against the exact input, in f64.
fn relative_error(decoded: f32, exact: f32) -> f64 {
    (decoded as f64 / exact as f64 - 1.0).abs()
}

#[test]
fn power_error_is_below_one_step_per_channel() {
    let mut rng = Rng::new(seed());
    let mut worst = 0.0f64;
    for _ in 0..200_000 {
        // Channels drawn independently, log-uniform over 1e-6 … 1e6 W: channel ratios up to 1e12.
        let mut watts = || 10f64.powf(-6.0 + 12.0 * rng.f64());
        let power = Vec3::new(watts() as f32, watts() as f32, watts() as f32);
        let p = photon(power, Vec3::Y, PhotonKind::Indirect);
        let scale = PowerScale::for_photons(&[p]);
        assert_eq!(scale.watts(), power.max_element());
        assert_eq!(scale.channels_below(power), 0);
        let decoded = CompactPhoton::encode(&p, scale).power(scale);
        for c in 0..3 {
            let relative = relative_error(decoded[c], power[c]);
            worst = worst.max(relative);
            assert!(
                relative < 0.007, // the documented bound: one step of 2^(1/100)
                "channel {c} of {power}: decoded {}",
                decoded[c]
            );
        }
    }
    eprintln!("worst relative power error {worst:.5}");
}

/// Photons at distinct positions `(i, 0, 0)` with these powers; a tree of them; then for every
/// photon of the tree its input power and decoded power.
fn round_trip(powers: &[Vec3]) -> (PhotonTree, Vec<(Vec3, Vec3)>) {
    let photons: Vec<Photon> = powers
        .iter()
        .enumerate()
        .map(|(i, &power)| Photon {
            position: Vec3::new(i as f32, 0.0, 0.0),
            ..photon(power, Vec3::NEG_Y, PhotonKind::Indirect)
        })
        .collect();
    let tree = PhotonTree::build(photons).expect("finite positions");
    let pairs = (0..tree.len() as u32)
        .map(|i| (powers[tree.position(i).x as usize], tree.power(i)))
        .collect();
    (tree, pairs)
}

#[test]
fn power_round_trips_within_one_step_at_any_absolute_power() {
    // One tree per decade from 1e-37 to 1e32 W (f32's normal range spans 1.2e-38 … 3.4e38),
    // each of photons with random colours whose channels spread over a factor 10⁶ above the
    // decade: 1e-37 … 1e38 W in all, and within each tree powers differing by up to 10⁶.
    let mut rng = Rng::new(seed());
    let mut worst = 0.0f64;
    for decade in -37..=32 {
        let base = 10f64.powi(decade);
        let powers: Vec<Vec3> = (0..500)
            .map(|_| {
                let mut channel = || (base * 10f64.powf(6.0 * rng.f64())) as f32;
                Vec3::new(channel(), channel(), channel())
            })
            .collect();
        assert!(
            powers
                .iter()
                .all(|p| p.min_element() >= f32::MIN_POSITIVE && p.is_finite())
        );
        let (tree, pairs) = round_trip(&powers);
        assert_eq!(tree.channels_below_range(), 0, "1e{decade}");
        let brightest = powers.iter().map(|p| p.max_element()).fold(0.0, f32::max);
        assert_eq!(tree.power_scale().watts(), brightest, "1e{decade}");
        for (exact, decoded) in pairs {
            for c in 0..3 {
                let relative = relative_error(decoded[c], exact[c]);
                worst = worst.max(relative);
                assert!(relative < 0.007, "1e{decade}: {exact} decodes to {decoded}");
            }
        }
    }
    // The very ends of the normal range, alone and together with a 10⁶ times brighter photon.
    for w in [
        f32::MIN_POSITIVE,
        2.0 * f32::MIN_POSITIVE,
        f32::MAX,
        f32::MAX / 3.0,
    ] {
        for powers in [
            vec![Vec3::splat(w)],
            vec![Vec3::splat(w), Vec3::splat((w * 1e6).min(f32::MAX))],
        ] {
            let (tree, pairs) = round_trip(&powers);
            assert_eq!(tree.channels_below_range(), 0);
            for (exact, decoded) in pairs {
                for c in 0..3 {
                    assert!(
                        relative_error(decoded[c], exact[c]) < 0.007,
                        "{exact} → {decoded}"
                    );
                }
            }
        }
    }
    eprintln!("worst relative power error {worst:.5}");
}

#[test]
fn photons_of_one_map_may_differ_by_a_trillion() {
    // Channels log-uniform over 2⁻⁴⁰ … 1 times a random scale (2⁻⁴⁰ ≈ 9.1e-13): every one
    // round-trips. Then photons with channels further below: stored as zero, and counted.
    let mut rng = Rng::new(seed());
    for _ in 0..20 {
        let scale = 10f64.powf(-20.0 + 40.0 * rng.f64());
        let mut channel = || (scale * (-40.0 * rng.f64()).exp2()) as f32;
        let mut powers: Vec<Vec3> = (0..5000)
            .map(|_| Vec3::new(channel(), channel(), channel()))
            .collect();
        powers.push(Vec3::new(
            scale as f32,
            (scale * 1e-12) as f32,
            (scale * 2f64.powi(-40)) as f32,
        ));
        let (tree, pairs) = round_trip(&powers);
        assert_eq!(tree.channels_below_range(), 0);
        for (exact, decoded) in &pairs {
            for c in 0..3 {
                assert!(
                    relative_error(decoded[c], exact[c]) < 0.007,
                    "{exact} → {decoded}"
                );
            }
        }
        // Add photons with channels 2⁻⁴², 2⁻⁵⁰, 2⁻⁶⁰ and 2⁻⁷⁰ times the scale (still positive
        // in f32), all below the smallest code (≈ 2⁻⁴⁰·⁹⁴), besides one 2⁻³⁰ (in range), a zero,
        // a negative and a NaN channel.
        let below = |e: i32| (scale * 2f64.powi(-e)) as f32;
        powers.extend([
            Vec3::new(below(42), below(50), below(70)),
            Vec3::new(below(42), 0.0, -1.0),
            Vec3::new(below(60), below(30), f32::NAN),
        ]);
        let (tree, pairs) = round_trip(&powers);
        assert_eq!(
            tree.channels_below_range(),
            5,
            "3 + 1 + 1 positive channels too small"
        );
        for (exact, decoded) in pairs {
            for c in 0..3 {
                let e = exact[c];
                if e > 0.0 && (e as f64) < scale * 2f64.powi(-41) {
                    assert_eq!(decoded[c], 0.0, "{exact}");
                } else if e > 0.0 {
                    assert!(relative_error(decoded[c], e) < 0.007, "{exact} → {decoded}");
                } else {
                    assert_eq!(decoded[c], 0.0, "zero, negative and NaN stay zero: {exact}");
                }
            }
        }
    }
}

#[test]
fn power_edge_values_decode_sensibly() {
    // A photon whose brightest channel is 1 W sets the scale to 1 W.
    let scale = PowerScale::for_photons(&[photon(Vec3::new(0.5, 1.0, 1.0), Vec3::Y, PhotonKind::Direct)]);
    assert_eq!(scale.watts(), 1.0);
    let decode = |w: f32| {
        CompactPhoton::encode(
            &photon(Vec3::new(w, 1.0, 1.0), Vec3::Y, PhotonKind::Direct),
            scale,
        )
        .power(scale)
        .x
    };
    assert_eq!(decode(0.0), 0.0);
    assert_eq!(decode(-3.0), 0.0, "negative power is not light");
    assert_eq!(decode(f32::NAN), 0.0);
    assert_eq!(decode(1e-14), 0.0, "far below the scale is zero");
    assert_eq!(
        scale.channels_below(Vec3::new(1e-14, 0.0, f32::NAN)),
        1,
        "and counted"
    );
    assert_eq!(decode(f32::INFINITY), 1.0, "infinity clamps to the scale");
    assert_eq!(decode(1e9), 1.0, "above the scale clamps");
    assert!(scale.smallest() < 2f32.powi(-40) && scale.smallest() > 2f32.powi(-41));
    // Exactly representable: whole powers of two from the scale down 40 octaves.
    for e in -40..=0 {
        let w = 2f32.powi(e);
        assert_eq!(decode(w), w, "2^{e}");
    }
    // The scale ignores non-finite and non-positive channels; without any positive one it is 1 W.
    let odd = [photon(
        Vec3::new(f32::INFINITY, f32::NAN, 3.0),
        Vec3::Y,
        PhotonKind::Direct,
    )];
    assert_eq!(PowerScale::for_photons(&odd).watts(), 3.0);
    let dark = [photon(
        Vec3::new(0.0, -1.0, f32::NAN),
        Vec3::Y,
        PhotonKind::Direct,
    )];
    assert_eq!(PowerScale::for_photons(&dark).watts(), 1.0);
    assert_eq!(PowerScale::for_photons(&[]).watts(), 1.0);
}

fn angle_degrees(a: Vec3, b: Vec3) -> f64 {
    let (a, b) = (a.as_dvec3().normalize(), b.as_dvec3().normalize());
    // atan2 of cross and dot: accurate for tiny angles, unlike acos.
    a.cross(b).length().atan2(a.dot(b)).to_degrees()
}

#[test]
fn direction_error_is_below_five_hundredths_of_a_degree() {
    let mut rng = Rng::new(seed());
    let mut directions: Vec<Vec3> = Vec::new();
    // The poles, axes, the octahedron's edges and folds (z = 0, |x| + |y| = 1), and random ones.
    for x in [-1.0f32, -0.5, 0.0, 0.5, 1.0] {
        for y in [-1.0f32, -0.5, 0.0, 0.5, 1.0] {
            for z in [-1.0f32, -1e-4, 0.0, 1e-4, 1.0] {
                directions.push(Vec3::new(x, y, z));
            }
        }
    }
    for _ in 0..300_000 {
        // Uniform on the sphere.
        let z = 2.0 * rng.f64() - 1.0;
        let phi = std::f64::consts::TAU * rng.f64();
        let r = (1.0 - z * z).sqrt();
        directions.push(Vec3::new(
            (r * phi.cos()) as f32,
            (r * phi.sin()) as f32,
            z as f32,
        ));
    }
    let mut worst = 0.0f64;
    for d in directions.into_iter().filter(|d| d.length() > 0.0) {
        let decoded =
            CompactPhoton::encode(&photon(Vec3::ONE, d, PhotonKind::Caustic), PowerScale::default())
                .direction();
        assert!(
            (decoded.length() - 1.0).abs() < 1e-6,
            "{d} decodes to non-unit {decoded}"
        );
        let angle = angle_degrees(d, decoded);
        worst = worst.max(angle);
        assert!(angle <= 0.05, "{d} decodes to {decoded}: {angle}°");
    }
    eprintln!("worst direction error {worst:.4}°");
}

#[test]
fn kind_and_position_round_trip_exactly() {
    let mut rng = Rng::new(seed());
    for kind in [PhotonKind::Direct, PhotonKind::Indirect, PhotonKind::Caustic] {
        let p = Photon {
            position: rng.vec3() * 100.0 - 50.0,
            power: Vec3::new(0.1, 2.0, 30.0),
            direction: Vec3::NEG_Y,
            kind,
        };
        let decoded = CompactPhoton::encode(&p, PowerScale::new(30.0)).decode(PowerScale::new(30.0));
        assert_eq!(decoded.power.z, 30.0);
        assert_eq!(decoded.kind, kind);
        assert_eq!(decoded.position, p.position);
        assert_eq!(decoded.direction, Vec3::NEG_Y, "axis directions are exact");
    }
}

#[test]
fn zero_or_non_finite_direction_becomes_plus_z() {
    for d in [Vec3::ZERO, Vec3::NAN, Vec3::new(f32::INFINITY, 0.0, 0.0)] {
        let decoded = CompactPhoton::encode(&photon(Vec3::ONE, d, PhotonKind::Direct), PowerScale::default())
            .direction();
        assert!(angle_degrees(decoded, Vec3::Z) < 0.05, "{d} → {decoded}");
    }
}

#[test]
fn tiny_and_huge_directions_keep_their_direction() {
    for unit in [
        Vec3::X,
        Vec3::NEG_Y,
        Vec3::new(0.6, -0.8, 0.0),
        Vec3::new(-1.0, 2.0, -2.0).normalize(),
    ] {
        for scale in [1e-30f32, 1e-20, 1e20, 1e30] {
            let d = unit * scale;
            let decoded =
                CompactPhoton::encode(&photon(Vec3::ONE, d, PhotonKind::Direct), PowerScale::default())
                    .direction();
            assert!(angle_degrees(decoded, unit) < 0.05, "{d} → {decoded}");
        }
    }
}
