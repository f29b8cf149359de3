//! Shared helpers of the pm-kdtree tests: a seeded generator, point clouds, brute force.
#![allow(dead_code)]

use glam::Vec3;
use pm_kdtree::{Photon, PhotonKind};

/// The seed of this run: `PM_KDTREE_SEED` when set, else a fixed default. Printed so a
/// failing run can be repeated.
pub fn seed() -> u64 {
    let seed = std::env::var("PM_KDTREE_SEED")
        .ok()
        .and_then(|s| s.parse().ok())
        .unwrap_or(0x5eed_1234);
    eprintln!("PM_KDTREE_SEED={seed}");
    seed
}

/// SplitMix64: small, good enough for test data.
pub struct Rng(u64);

impl Rng {
    pub fn new(seed: u64) -> Self {
        Rng(seed)
    }
    pub fn next_u64(&mut self) -> u64 {
        self.0 = self.0.wrapping_add(0x9e37_79b9_7f4a_7c15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xbf58_476d_1ce4_e5b9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94d0_49bb_1331_11eb);
        z ^ (z >> 31)
    }
    /// Uniform in [0, 1).
    pub fn f32(&mut self) -> f32 {
        (self.next_u64() >> 40) as f32 / (1u64 << 24) as f32
    }
    pub fn f64(&mut self) -> f64 {
        (self.next_u64() >> 11) as f64 / (1u64 << 53) as f64
    }
    pub fn below(&mut self, n: usize) -> usize {
        (self.next_u64() % n as u64) as usize
    }
    pub fn vec3(&mut self) -> Vec3 {
        Vec3::new(self.f32(), self.f32(), self.f32())
    }
    pub fn kind(&mut self) -> PhotonKind {
        [PhotonKind::Direct, PhotonKind::Indirect, PhotonKind::Caustic][self.below(3)]
    }
}

/// Points uniform in the unit cube.
pub fn uniform(rng: &mut Rng, n: usize) -> Vec<Vec3> {
    (0..n).map(|_| rng.vec3()).collect()
}

/// Points uniform on the five walls of the unit box open at z = 0 (floor, ceiling, left,
/// right, back), the way photons land in a Cornell box: exact coordinates 0 or 1 on one axis.
pub fn box_walls(rng: &mut Rng, n: usize) -> Vec<Vec3> {
    (0..n)
        .map(|_| {
            let (a, b) = (rng.f32(), rng.f32());
            match rng.below(5) {
                0 => Vec3::new(a, 0.0, b),
                1 => Vec3::new(a, 1.0, b),
                2 => Vec3::new(0.0, a, b),
                3 => Vec3::new(1.0, a, b),
                _ => Vec3::new(a, b, 1.0),
            }
        })
        .collect()
}

/// Photons of 1 W at `points` with random kinds.
pub fn photons_at(rng: &mut Rng, points: &[Vec3]) -> Vec<Photon> {
    points
        .iter()
        .map(|&position| Photon {
            position,
            power: Vec3::ONE,
            direction: Vec3::NEG_Y,
            kind: rng.kind(),
        })
        .collect()
}

/// True Euclidean distance in f64.
pub fn euclidean(a: Vec3, b: Vec3) -> f64 {
    let d = a.as_dvec3() - b.as_dvec3();
    d.length()
}

/// True Chebyshev distance in f64.
pub fn chebyshev(a: Vec3, b: Vec3) -> f64 {
    let d = a.as_dvec3() - b.as_dvec3();
    d.abs().max_element()
}

/// The sorted distances of the k nearest by brute force.
pub fn brute_k(
    points: &[Vec3],
    accept: impl Fn(usize) -> bool,
    query: Vec3,
    k: usize,
    max_distance: f64,
    distance: fn(Vec3, Vec3) -> f64,
) -> Vec<f64> {
    let mut d: Vec<f64> = (0..points.len())
        .filter(|&i| accept(i))
        .map(|i| distance(points[i], query))
        .filter(|&d| d <= max_distance)
        .collect();
    d.sort_by(f64::total_cmp);
    d.truncate(k);
    d
}

/// Panics with a readable message when two sorted distance lists differ beyond f32 rounding.
pub fn assert_same_distances(got: &[f64], want: &[f64], what: &str) {
    assert_eq!(
        got.len(),
        want.len(),
        "{what}: found {} photons, brute force {}",
        got.len(),
        want.len()
    );
    for (i, (g, w)) in got.iter().zip(want).enumerate() {
        assert!(
            (g - w).abs() <= 1e-6 * w.max(1e-3),
            "{what}: neighbour {i}: distance {g} vs brute force {w}"
        );
    }
}
