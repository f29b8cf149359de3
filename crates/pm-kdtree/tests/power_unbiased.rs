//! The stored photon power is unbiased: over many photons of one coloured power, the decoded
//! mean converges to the exact power (in standard errors of the mean), where rounding to the
//! nearest code would leave a fixed colour offset of up to 0.35 %. And it stays deterministic.

mod common;

use common::*;
use glam::Vec3;
use pm_kdtree::{CompactPhoton, Photon, PhotonKind, PhotonTree, PowerScale};

/// `n` photons of power `power` at random positions and directions.
fn photons_of(power: Vec3, n: usize, rng: &mut Rng) -> Vec<Photon> {
    (0..n)
        .map(|_| Photon {
            position: Vec3::new(rng.f32(), rng.f32(), rng.f32()) * 4.0 - 2.0,
            power,
            direction: Vec3::new(rng.f32() - 0.5, rng.f32() - 0.5, rng.f32() - 0.5),
            kind: PhotonKind::Direct,
        })
        .collect()
}

/// Per channel: the decoded mean's relative error and its standard error (relative), from the
/// decoded values' own spread.
fn decoded_mean(photons: &[Photon], scale: PowerScale) -> [(f64, f64); 3] {
    let exact = photons[0].power;
    let n = photons.len() as f64;
    let mut out = [(0.0, 0.0); 3];
    for (c, o) in out.iter_mut().enumerate() {
        let (mut sum, mut sum2) = (0.0f64, 0.0f64);
        for p in photons {
            let v = CompactPhoton::encode(p, scale).power(scale)[c] as f64;
            sum += v;
            sum2 += v * v;
        }
        let mean = sum / n;
        let var = (sum2 / n - mean * mean).max(0.0) * n / (n - 1.0);
        let e = exact[c] as f64;
        *o = (mean / e - 1.0, (var / n).sqrt() / e);
    }
    out
}

/// The relative error of rounding `v` (relative to the scale) to the nearest code, as the
/// encoding did before it rounded stochastically.
fn nearest_code_error(v: f64) -> f64 {
    let code = (v.log2() * 100.0).round();
    (code / 100.0).exp2() / v - 1.0
}

#[test]
fn a_coloured_light_decodes_to_its_power_on_average() {
    // The Cornell box light's colour: nearest rounding stores G +0.174 % and B −0.176 %.
    let power = Vec3::new(17.0, 12.0, 4.0) / 1e6;
    assert!(nearest_code_error(12.0 / 17.0) > 0.0017);
    assert!(nearest_code_error(4.0 / 17.0) < -0.0017);
    let mut rng = Rng::new(seed());
    let photons = photons_of(power, 1_000_000, &mut rng);
    let scale = PowerScale::for_photons(&photons);
    for (c, (bias, se)) in decoded_mean(&photons, scale).into_iter().enumerate() {
        eprintln!(
            "channel {c}: decoded mean {:+.5} % ± {:.5} % (standard error)",
            bias * 100.0,
            se * 100.0
        );
        // The spread is at most half a step (0.35 %) per photon: a standard error ≤ 3.5e-6.
        assert!(se < 4e-6, "channel {c}: standard error {se}");
        assert!(
            bias.abs() < 5.0 * se,
            "channel {c}: {bias} is over 5 standard errors ({se})"
        );
        assert!(bias.abs() < 5e-5, "channel {c}: {bias} is not far below 0.05 %");
    }
}

#[test]
fn random_colours_decode_to_their_power_on_average() {
    // 40 colours with channels log-uniform over 1e-4 … 1 of the brightest: each channel's mean
    // within 5 standard errors (120 channels: a false alarm has probability ~7e-5).
    let mut rng = Rng::new(seed() ^ 0xc0105);
    let mut worst_z = 0.0f64;
    let mut worst_nearest = 0.0f64;
    for _ in 0..40 {
        let mut channel = || 10f64.powf(-4.0 * rng.f64()) as f32;
        let power = Vec3::new(channel(), channel(), channel()) * 3.0;
        let photons = photons_of(power, 50_000, &mut rng);
        let scale = PowerScale::for_photons(&photons);
        for (c, (bias, se)) in decoded_mean(&photons, scale).into_iter().enumerate() {
            let relative = power[c] as f64 / scale.watts() as f64;
            worst_nearest = worst_nearest.max(nearest_code_error(relative).abs());
            if se == 0.0 {
                // Exactly on a code (the brightest channel is the scale itself).
                assert_eq!(bias, 0.0, "{power} channel {c}");
                continue;
            }
            let z = bias / se;
            worst_z = worst_z.max(z.abs());
            assert!(
                z.abs() < 5.0,
                "{power} channel {c}: {bias} is {z} standard errors"
            );
        }
    }
    eprintln!("worst |z| {worst_z:.2}; nearest rounding would err by up to {worst_nearest:.5}");
    assert!(
        worst_nearest > 0.003,
        "the colours test offsets nearest rounding would leave"
    );
}

#[test]
fn the_rounding_is_a_function_of_the_photon_alone() {
    // The same photons in another order (and a tree built from them, in parallel above 32k
    // photons) store the same power for each photon.
    let mut rng = Rng::new(seed() ^ 0x0dde);
    let photons = photons_of(Vec3::new(0.3, 0.2, 0.07), 70_000, &mut rng);
    let mut shuffled = photons.clone();
    for i in (1..shuffled.len()).rev() {
        shuffled.swap(i, rng.below(i + 1));
    }
    let stored = |photons: Vec<Photon>| {
        let tree = PhotonTree::build(photons).expect("finite");
        let mut pairs: Vec<([u32; 3], [u32; 3])> = (0..tree.len() as u32)
            .map(|i| {
                let p = tree.position(i).to_array().map(f32::to_bits);
                (p, tree.power(i).to_array().map(f32::to_bits))
            })
            .collect();
        pairs.sort_unstable();
        pairs
    };
    let a = stored(photons.clone());
    assert_eq!(a, stored(shuffled));
    // And it is not nearest rounding: some photons of this one power round up, some down.
    let distinct: std::collections::BTreeSet<[u32; 3]> = a.iter().map(|&(_, w)| w).collect();
    assert!(distinct.len() > 1, "{distinct:?}");
}
