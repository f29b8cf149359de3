//! A fast hash map for the geometry's own integer keys: grid cells, vertex indices and the bit
//! patterns of coordinates. Welding a scene looks up grid cells and blocks of them per vertex and linking
//! twins hashes every edge, so on a 57k-triangle interior the standard library's SipHash
//! took a third of the time of building the meshes.
//!
//! The hasher folds the key's words with a multiply-rotate step (rustc's FxHash) and mixes
//! the result once at the end (SplitMix64's finaliser), so both the low bits that pick a
//! bucket and the high bits that tag it depend on every bit of the key: grid cells in a row,
//! which differ in one low bit, spread over the table. It does not resist keys chosen to
//! collide, which mesh coordinates are not. Every map keyed with it is read by lookups only,
//! or its iteration is sorted first, so nothing built depends on the hash.

use std::collections::{HashMap, HashSet};
use std::hash::{BuildHasherDefault, Hasher};

/// A [`HashMap`] hashed with [`FastHasher`].
pub(crate) type FastHashMap<K, V> = HashMap<K, V, BuildHasherDefault<FastHasher>>;

/// A [`HashSet`] hashed with [`FastHasher`].
pub(crate) type FastHashSet<K> = HashSet<K, BuildHasherDefault<FastHasher>>;

/// An empty [`FastHashMap`] with room for `capacity` entries.
pub(crate) fn fast_map_with_capacity<K, V>(capacity: usize) -> FastHashMap<K, V> {
    FastHashMap::with_capacity_and_hasher(capacity, BuildHasherDefault::default())
}

/// Multiply-rotate folding with a final mix; see the module documentation.
#[derive(Default)]
pub(crate) struct FastHasher(u64);

impl FastHasher {
    #[inline]
    fn add(&mut self, word: u64) {
        self.0 = (self.0.rotate_left(5) ^ word).wrapping_mul(0x51_7c_c1_b7_27_22_0a_95);
    }
}

impl Hasher for FastHasher {
    #[inline]
    fn write(&mut self, bytes: &[u8]) {
        let mut words = bytes.chunks_exact(8);
        for word in &mut words {
            self.add(u64::from_le_bytes(word.try_into().expect("chunks of 8 bytes")));
        }
        let rest = words.remainder();
        if !rest.is_empty() {
            let mut word = [0u8; 8];
            word[..rest.len()].copy_from_slice(rest);
            self.add(u64::from_le_bytes(word));
        }
    }

    #[inline]
    fn write_u32(&mut self, i: u32) {
        self.add(u64::from(i));
    }

    #[inline]
    fn write_u64(&mut self, i: u64) {
        self.add(i);
    }

    #[inline]
    fn write_usize(&mut self, i: usize) {
        self.add(i as u64);
    }

    #[inline]
    fn finish(&self) -> u64 {
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xbf58_476d_1ce4_e5b9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94d0_49bb_1331_11eb);
        z ^ (z >> 31)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::hash::BuildHasher;

    /// Grid cells along a row, a column and a diagonal fill a table's buckets about evenly:
    /// in 2^12 buckets (the low bits, as a table picks them) no bucket gets more than 12 of
    /// 4,096 cells (a uniform hash gives at most about 9), and the tag bits (the top 7) take
    /// all 128 values. A hash of the first coordinate only would put each column in one bucket.
    #[test]
    fn rows_of_grid_cells_spread_over_buckets_and_tags() {
        let build = BuildHasherDefault::<FastHasher>::default();
        for step in [[1i64, 0, 0], [0, 1, 0], [0, 0, 1], [1, 1, 1], [1 << 20, 0, -3]] {
            let mut buckets = vec![0u32; 1 << 12];
            let mut tags = [false; 128];
            for k in 0..4096i64 {
                let cell = [step[0] * k - 7, step[1] * k + 11, step[2] * k];
                let h = build.hash_one(cell);
                buckets[(h & 0xfff) as usize] += 1;
                tags[(h >> 57) as usize] = true;
            }
            let fullest = buckets.iter().copied().max().unwrap();
            assert!(fullest <= 12, "step {step:?}: {fullest} cells in one bucket");
            assert!(tags.iter().all(|&t| t), "step {step:?}: unused tags");
        }
    }

    #[test]
    fn keys_that_differ_hash_apart_and_equal_keys_alike() {
        let build = BuildHasherDefault::<FastHasher>::default();
        assert_eq!(build.hash_one((3u32, 9u32)), build.hash_one((3u32, 9u32)));
        assert_ne!(build.hash_one((3u32, 9u32)), build.hash_one((9u32, 3u32)));
        assert_ne!(build.hash_one([0u32, 0, 1]), build.hash_one([0u32, 1, 0]));
    }
}
