//! The 20-byte photon: size, and decoding error against the documented bounds (power within
//! 0.5 % per channel over 1e-6 … 1e6 W, direction within 0.05°) over many random photons.

mod common;

use common::*;
use glam::Vec3;
use pm_kdtree::{CompactPhoton, Photon, PhotonKind};

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
fn power_error_is_below_half_a_percent_per_channel() {
    let mut rng = Rng::new(seed());
    let mut worst = 0.0f64;
    for _ in 0..200_000 {
        // Channels drawn independently, log-uniform over 1e-6 … 1e6 W: channel ratios up to 1e12.
        let mut watts = || 10f64.powf(-6.0 + 12.0 * rng.f64());
        let power = Vec3::new(watts() as f32, watts() as f32, watts() as f32);
        let decoded = CompactPhoton::encode(&photon(power, Vec3::Y, PhotonKind::Indirect)).power();
        for c in 0..3 {
            let relative = (decoded[c] as f64 / power[c] as f64 - 1.0).abs();
            worst = worst.max(relative);
            assert!(
                relative <= 0.0035, // the documented bound; the issue asks for 0.5 %
                "channel {c} of {power}: decoded {}",
                decoded[c]
            );
        }
    }
    eprintln!("worst relative power error {worst:.5}");
}

#[test]
fn power_edge_values_decode_sensibly() {
    let decode = |w: f32| {
        CompactPhoton::encode(&photon(Vec3::new(w, 1.0, 1.0), Vec3::Y, PhotonKind::Direct))
            .power()
            .x
    };
    assert_eq!(decode(0.0), 0.0);
    assert_eq!(decode(-3.0), 0.0, "negative power is not light");
    assert_eq!(decode(f32::NAN), 0.0);
    assert_eq!(decode(1e-12), 0.0, "far below the range rounds to zero");
    assert_eq!(decode(f32::INFINITY), CompactPhoton::MAX_POWER);
    assert_eq!(decode(1e9), CompactPhoton::MAX_POWER, "above the range clamps");
    const { assert!(CompactPhoton::MIN_POWER <= 1e-6 && CompactPhoton::MAX_POWER >= 1e6) };
    // Exactly representable: whole powers of two inside the range.
    for e in -20..=20 {
        let w = 2f32.powi(e);
        assert_eq!(decode(w), w, "2^{e}");
    }
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
        let decoded = CompactPhoton::encode(&photon(Vec3::ONE, d, PhotonKind::Caustic)).direction();
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
        let decoded = CompactPhoton::encode(&p).decode();
        assert_eq!(decoded.kind, kind);
        assert_eq!(decoded.position, p.position);
        assert_eq!(decoded.direction, Vec3::NEG_Y, "axis directions are exact");
    }
}

#[test]
fn zero_or_non_finite_direction_becomes_plus_z() {
    for d in [Vec3::ZERO, Vec3::NAN, Vec3::new(f32::INFINITY, 0.0, 0.0)] {
        let decoded = CompactPhoton::encode(&photon(Vec3::ONE, d, PhotonKind::Direct)).direction();
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
            let decoded = CompactPhoton::encode(&photon(Vec3::ONE, d, PhotonKind::Direct)).direction();
            assert!(angle_degrees(decoded, unit) < 0.05, "{d} → {decoded}");
        }
    }
}
