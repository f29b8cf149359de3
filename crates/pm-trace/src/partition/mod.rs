//! Partitions of the scene's parts into photon maps: the trait, one map for everything, flood
//! fill across mesh edges with a small crease angle, and the same aware of faces in contact.

mod contact;
mod crease;

pub use contact::Contact;
pub use crease::CreaseAngle;

use crate::{PartId, Scene, SceneError};

/// The photon map of every part of a scene.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct MapAssignment {
    map_of_part: Vec<u32>,
    map_count: u32,
}

impl MapAssignment {
    /// An assignment from the map of each part. `None` unless every id is `< map_count` and
    /// `map_count` is at most the number of parts (at least 1): a map without parts could hold
    /// no photons, and a huge count would only make tracing allocate per-map tables for it.
    pub fn new(map_of_part: Vec<u32>, map_count: u32) -> Option<Self> {
        let plausible = map_count as usize <= map_of_part.len().max(1);
        (plausible && map_of_part.iter().all(|&m| m < map_count)).then_some(MapAssignment {
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

    /// Prepares a scene for this partition before photons are traced, once per scene. The
    /// default returns it unchanged; [`Contact`] splits faces along the lines where other faces
    /// stand on them, which changes the scene's parts.
    fn prepare_scene(&self, scene: Scene) -> Result<Scene, SceneError> {
        Ok(scene)
    }
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
