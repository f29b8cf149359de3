//! The photon map of every part of a scene: dense map ids, and the parts of each map.

use crate::part::PartId;

/// The photon map of every part of a scene.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct MapAssignment {
    map_of_part: Vec<u32>,
    map_count: u32,
}

impl MapAssignment {
    /// An assignment from the map id of each part. Ids may be any `u32`s: they are renumbered
    /// densely in order of first appearance, so `[7, 3, 7]` gives maps `[0, 1, 0]` and no map
    /// is ever empty. An empty list (a scene without parts) gives one empty map.
    pub fn new(map_ids: Vec<u32>) -> Self {
        let mut dense = std::collections::HashMap::new();
        let map_of_part: Vec<u32> = map_ids
            .iter()
            .map(|&id| {
                let next = dense.len() as u32;
                *dense.entry(id).or_insert(next)
            })
            .collect();
        MapAssignment {
            map_of_part,
            map_count: (dense.len() as u32).max(1),
        }
    }

    /// Every one of `part_count` parts in map 0.
    pub fn single(part_count: usize) -> Self {
        MapAssignment {
            map_of_part: vec![0; part_count],
            map_count: 1,
        }
    }

    /// An assignment from each part's group root, a part index (`roots[p] < roots.len()`):
    /// maps numbered in order of each group's first part, as [`MapAssignment::new`] does,
    /// without hashing.
    pub(super) fn from_roots(roots: &[u32]) -> Self {
        let mut map_of_root = vec![u32::MAX; roots.len()];
        let mut next = 0u32;
        let map_of_part = roots
            .iter()
            .map(|&root| {
                let slot = &mut map_of_root[root as usize];
                if *slot == u32::MAX {
                    *slot = next;
                    next += 1;
                }
                *slot
            })
            .collect();
        MapAssignment {
            map_of_part,
            map_count: next.max(1),
        }
    }

    /// The map of `part`.
    #[inline]
    pub fn map_of(&self, part: PartId) -> u32 {
        self.map_of_part[part.0 as usize]
    }

    /// Number of maps.
    pub fn map_count(&self) -> u32 {
        self.map_count
    }

    /// Number of parts assigned.
    pub fn part_count(&self) -> usize {
        self.map_of_part.len()
    }

    /// A 64-bit fingerprint of the assignment (FNV-1a over the part count and every part's
    /// map): equal assignments have equal fingerprints, and two partitions that put one part
    /// in different maps, or of scenes with different parts, almost surely differ. Renders
    /// that must not be mixed (progressive shards) carry it in their identity.
    pub fn fingerprint(&self) -> u64 {
        let mut h = 0xcbf2_9ce4_8422_2325u64;
        let words = std::iter::once(self.map_of_part.len() as u32).chain(self.map_of_part.iter().copied());
        for word in words {
            for byte in word.to_le_bytes() {
                h ^= u64::from(byte);
                h = h.wrapping_mul(0x0000_0100_0000_01b3);
            }
        }
        h
    }

    /// The parts of each map, in part order.
    pub fn parts_per_map(&self) -> Vec<Vec<PartId>> {
        let mut out = vec![Vec::new(); self.map_count as usize];
        for (p, &m) in self.map_of_part.iter().enumerate() {
            out[m as usize].push(PartId(p as u32));
        }
        out
    }
}
