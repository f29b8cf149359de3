//! Partitions of the scene's parts into photon maps: the trait, one map for everything, and
//! flood fill across mesh edges with a small crease angle.

mod crease;

pub use crease::CreaseAngle;

use crate::{PartId, Scene};

/// The photon map of every part of a scene.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct MapAssignment {
    map_of_part: Vec<u32>,
    map_count: u32,
}

impl MapAssignment {
    /// An assignment from the map of each part (ids must be `< map_count`; `None` otherwise).
    pub fn new(map_of_part: Vec<u32>, map_count: u32) -> Option<Self> {
        map_of_part
            .iter()
            .all(|&m| m < map_count)
            .then_some(MapAssignment {
                map_of_part,
                map_count,
            })
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

    /// The parts of each map, in part order.
    pub fn parts_per_map(&self) -> Vec<Vec<PartId>> {
        let mut out = vec![Vec::new(); self.map_count as usize];
        for (p, &m) in self.map_of_part.iter().enumerate() {
            out[m as usize].push(PartId(p as u32));
        }
        out
    }
}

/// Decides which photon map each part of a scene belongs to.
pub trait Partitioner {
    /// The assignment for `scene` (one entry per part).
    fn partition(&self, scene: &Scene) -> MapAssignment;
}

/// Every part in map 0: one global photon map (the paper's basic variant).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct SingleMap;

impl Partitioner for SingleMap {
    fn partition(&self, scene: &Scene) -> MapAssignment {
        MapAssignment {
            map_of_part: vec![0; scene.part_count()],
            map_count: 1,
        }
    }
}
