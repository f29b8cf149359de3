//! Camera-driven photon emission: an [`EmissionGuide`] learnt from a pilot of photon paths
//! says, for each emission bin (light × direction cell × position cell), with what
//! probability a photon emitted there is traced on. Photons in bins whose pilot paths never
//! reached a surface the camera sees are mostly dropped at the light, before any ray is cast,
//! and the survivors carry their bin's share of the power over that probability.
//!
//! **Unbiased.** A photon of bin `b` survives with probability `P_b` and then carries
//! `Φ / P_b`: its expected contribution to any estimate is what uniform emission gives, for
//! every `P_b > 0`, and `P_b` never falls below the guide's floor. The guide only moves where
//! the traced paths go: bins that light what the camera sees keep every photon; others keep
//! one in `1 / floor`. The price is variance where the pilot was wrong: a surface the
//! camera sees that only dropped bins reach gets fewer photons of larger power.
//!
//! **Visibility, not importance.** A pilot path counts as *seen* when any photon it stores
//! passes the caller's test (the render crate tests "near a point the camera's rays reach,
//! in the same photon map"). This is Hachisuka & Jensen's photon-path visibility (2011)
//! applied once, at the light: a bin's keep probability is its smoothed seen fraction over
//! the largest one. Peter & Pietrek's importance (1998) would also guide every bounce; at
//! the light alone the guide costs one hash lookup per photon.
//!
//! **Deterministic.** The pilot draws streams of its own, `(seed', u64::MAX, i)` with `seed'`
//! a hash of the run's seed, counts in integers, and is the same for any thread count.

use super::options::MAX_PHOTON_PATHS;
use crate::error::TraceError;
use crate::ray::Ray;
use glam::Vec3;
use pm_geom::Aabb;
use std::collections::HashMap;
use std::hash::{BuildHasherDefault, Hasher};

/// Direction cells per cube face side (4 × 4 × 6 = 96 cells over the sphere).
const DIRECTION_SIDE: u32 = 4;
/// Position cells per axis of the scene's bounds (4³ = 64 cells).
const POSITION_SIDE: u32 = 4;
/// Weight (in pilot paths) of the scene-wide seen fraction in a bin's smoothed one.
const PRIOR_PATHS: f64 = 1.0;

/// Hashes a bin key (made here, never by a caller: no flooding to fear) with Murmur3's
/// finaliser, a few cycles against SipHash's tens per photon emitted.
#[derive(Default)]
pub(super) struct BinHasher(u64);

impl Hasher for BinHasher {
    fn finish(&self) -> u64 {
        self.0
    }

    fn write(&mut self, bytes: &[u8]) {
        for &b in bytes {
            self.0 = crate::rng::fmix64(self.0 ^ u64::from(b));
        }
    }

    fn write_u64(&mut self, key: u64) {
        self.0 = crate::rng::fmix64(self.0 ^ key);
    }
}

pub(super) type BinMap<V> = HashMap<u64, V, BuildHasherDefault<BinHasher>>;

/// How to learn an [`EmissionGuide`].
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct GuideOptions {
    /// Pilot photon paths traced to learn the guide (their photons are not kept).
    pub pilot_photons: u32,
    /// The least keep probability of any bin, in `(0, 1]`: the most a photon's power is
    /// raised, and the least share of the photons a bin the camera never sees keeps.
    pub floor: f32,
}

impl Default for GuideOptions {
    /// 65,536 pilot paths and a floor of 1/8 (measured: docs/results.md, "Camera-driven photons").
    fn default() -> Self {
        GuideOptions {
            pilot_photons: 1 << 16,
            floor: 0.125,
        }
    }
}

impl GuideOptions {
    /// Refuses a floor outside `(0, 1]` and zero or more than [`MAX_PHOTON_PATHS`] pilot paths.
    pub fn validate(&self) -> Result<(), String> {
        if !(self.floor > 0.0 && self.floor <= 1.0) {
            return Err(format!("guide floor {} is outside (0, 1]", self.floor));
        }
        if self.pilot_photons == 0 || self.pilot_photons > MAX_PHOTON_PATHS {
            return Err(format!(
                "{} pilot photons: give 1 to {MAX_PHOTON_PATHS}",
                self.pilot_photons
            ));
        }
        Ok(())
    }
}

/// Keep probabilities per emission bin, learnt by [`EmissionGuide::learn`] (in `pilot.rs`); used by
/// [`trace_guided_photon_paths`](super::trace_guided_photon_paths).
#[derive(Clone, Debug, PartialEq)]
pub struct EmissionGuide {
    keep: BinMap<f32>,
    bounds: Aabb,
    keep_rate: f64,
    seen_fraction: f64,
    floor: f32,
}

impl EmissionGuide {
    /// The guide of pilot counts `[paths, seen paths]` per bin.
    pub(super) fn from_counts(counts: BinMap<[u32; 2]>, bounds: Aabb, paths: u32, floor: f32) -> Self {
        let seen: u64 = counts.values().map(|c| u64::from(c[1])).sum();
        let seen_fraction = seen as f64 / f64::from(paths);
        if seen == 0 {
            return EmissionGuide {
                keep: BinMap::default(),
                bounds,
                keep_rate: 1.0,
                seen_fraction,
                floor,
            };
        }
        let smoothed =
            |[n, s]: [u32; 2]| (f64::from(s) + PRIOR_PATHS * seen_fraction) / (f64::from(n) + PRIOR_PATHS);
        let best = counts.values().map(|&c| smoothed(c)).fold(0.0, f64::max);
        let keep: BinMap<f32> = counts
            .iter()
            .map(|(&k, &c)| (k, ((smoothed(c) / best) as f32).clamp(floor, 1.0)))
            .collect();
        let keep_rate = counts
            .iter()
            .map(|(k, c)| f64::from(c[0]) * f64::from(keep[k]))
            .sum::<f64>()
            / f64::from(paths);
        EmissionGuide {
            keep,
            bounds,
            keep_rate,
            seen_fraction,
            floor,
        }
    }

    /// The probability that a photon of light `light` leaving along `ray` is traced on (1 in
    /// bins the pilot never reached).
    #[inline]
    pub fn keep(&self, light: usize, ray: &Ray) -> f32 {
        if self.keep.is_empty() {
            return 1.0;
        }
        self.keep
            .get(&bin(light, ray, &self.bounds))
            .copied()
            .unwrap_or(1.0)
    }

    /// The expected share of emitted photons traced on (over the pilot's emission).
    pub fn keep_rate(&self) -> f64 {
        self.keep_rate
    }

    /// The share of the pilot's paths that stored a photon the camera sees.
    pub fn seen_fraction(&self) -> f64 {
        self.seen_fraction
    }

    /// The least keep probability of a bin.
    pub fn floor(&self) -> f32 {
        self.floor
    }

    /// The bins the pilot reached.
    pub fn bin_count(&self) -> usize {
        self.keep.len()
    }

    /// How many photons to emit so that about `traced` paths are traced on:
    /// `⌈traced / keep_rate⌉`. Errors past [`MAX_PHOTON_PATHS`]
    /// ([`TraceError::TooManyGuidedPhotons`]).
    pub fn photons_to_emit(&self, traced: u32) -> Result<u32, TraceError> {
        let emit = (f64::from(traced) / self.keep_rate).ceil();
        if emit > f64::from(MAX_PHOTON_PATHS) {
            return Err(TraceError::TooManyGuidedPhotons {
                photons: traced,
                keep_rate: self.keep_rate,
            });
        }
        Ok(emit as u32)
    }
}

/// The emission bin of a photon of light `light` leaving along `ray`: light, cube-map cell of
/// the direction, cell of the origin in the scene's bounds.
#[inline]
pub(super) fn bin(light: usize, ray: &Ray, bounds: &Aabb) -> u64 {
    let d = ray.direction;
    let a = d.abs();
    let (face, u, v, m) = if a.x >= a.y && a.x >= a.z {
        (u32::from(d.x < 0.0), d.y, d.z, a.x)
    } else if a.y >= a.z {
        (2 + u32::from(d.y < 0.0), d.x, d.z, a.y)
    } else {
        (4 + u32::from(d.z < 0.0), d.x, d.y, a.z)
    };
    let cell = |t: f32| {
        (((t / m.max(f32::MIN_POSITIVE) + 1.0) * 0.5 * DIRECTION_SIDE as f32) as u32).min(DIRECTION_SIDE - 1)
    };
    let direction = (face * DIRECTION_SIDE + cell(u)) * DIRECTION_SIDE + cell(v);
    let extent = (bounds.max - bounds.min).max(Vec3::splat(f32::MIN_POSITIVE));
    let t = ((ray.origin - bounds.min) / extent * POSITION_SIDE as f32)
        .clamp(Vec3::ZERO, Vec3::splat((POSITION_SIDE - 1) as f32));
    let position = (t.x as u32 * POSITION_SIDE + t.y as u32) * POSITION_SIDE + t.z as u32;
    ((light as u64) << 16) | (u64::from(direction) << 6) | u64::from(position)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn ray(origin: Vec3, direction: Vec3) -> Ray {
        Ray { origin, direction }
    }

    /// Every direction falls in one of the 96 cells, opposite directions in different cells,
    /// and the origin's cell and the light make the rest of the key.
    #[test]
    fn bins_cover_the_sphere_and_tell_lights_and_places_apart() {
        let bounds = Aabb::cube(Vec3::ZERO, 1.0);
        let mut cells = std::collections::HashSet::new();
        let mut rng = crate::rng::Rng::new(1, 2);
        for _ in 0..20_000 {
            let d = crate::sampling::uniform_sphere(glam::Vec2::new(rng.next_f32(), rng.next_f32()));
            let key = bin(0, &ray(Vec3::ZERO, d), &bounds);
            let minus = bin(0, &ray(Vec3::ZERO, -d), &bounds);
            assert_ne!(key, minus, "{d}");
            cells.insert(key);
        }
        assert_eq!(cells.len(), 96);
        let d = Vec3::Y;
        assert_ne!(
            bin(0, &ray(Vec3::ZERO, d), &bounds),
            bin(1, &ray(Vec3::ZERO, d), &bounds)
        );
        assert_ne!(
            bin(0, &ray(Vec3::splat(-0.9), d), &bounds),
            bin(0, &ray(Vec3::splat(0.9), d), &bounds)
        );
        // Outside the bounds, non-finite: still a key, never a panic.
        bin(0, &ray(Vec3::splat(1e30), d), &bounds);
        bin(0, &ray(Vec3::NAN, Vec3::NAN), &bounds);
    }

    /// Keep probabilities: the most-seen bin keeps all, an unseen one the floor; the keep rate
    /// is the pilot-weighted mean; nothing seen keeps everything.
    #[test]
    fn keep_probabilities_follow_the_smoothed_seen_fraction() {
        let bounds = Aabb::cube(Vec3::ZERO, 1.0);
        let counts = BinMap::from_iter([(1u64, [100u32, 100u32]), (2, [100, 0]), (3, [200, 50])]);
        let g = EmissionGuide::from_counts(counts, bounds, 400, 0.125);
        assert_eq!(g.keep[&1], 1.0);
        assert_eq!(g.keep[&2], 0.125);
        let seen = 150.0 / 400.0;
        let expect = ((50.0 + seen) / 201.0) / ((100.0 + seen) / 101.0);
        assert!((f64::from(g.keep[&3]) - expect).abs() < 1e-6, "{}", g.keep[&3]);
        let rate = (100.0 + 100.0 * 0.125 + 200.0 * f64::from(g.keep[&3])) / 400.0;
        assert!((g.keep_rate() - rate).abs() < 1e-9);
        assert_eq!(g.photons_to_emit(1000).unwrap(), (1000.0 / rate).ceil() as u32);
        let none = EmissionGuide::from_counts(BinMap::from_iter([(1u64, [10u32, 0u32])]), bounds, 10, 0.125);
        assert_eq!(none.keep(0, &ray(Vec3::ZERO, Vec3::Y)), 1.0);
        assert_eq!(none.keep_rate(), 1.0);
    }

    #[test]
    fn options_out_of_range_are_refused() {
        for floor in [0.0, -1.0, 1.5, f32::NAN] {
            let o = GuideOptions {
                floor,
                ..GuideOptions::default()
            };
            assert!(o.validate().unwrap_err().contains("floor"));
        }
        let o = GuideOptions {
            pilot_photons: 0,
            ..GuideOptions::default()
        };
        assert!(o.validate().is_err());
        assert!(GuideOptions::default().validate().is_ok());
    }
}
