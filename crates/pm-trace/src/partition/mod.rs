//! Partitions of the scene's parts into photon maps: the trait, one map for everything, flood
//! fill across mesh edges with a small crease angle, and the same aware of faces in contact.

mod contact;
mod crease;
pub(crate) mod record;

pub use contact::Contact;
pub use crease::CreaseAngle;
pub use record::ContactRecord;

use crate::error::SceneError;
use crate::part::PartId;
use crate::scene::Scene;

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

    /// Refuses a scene this partition cannot serve as it is — [`Contact`] refuses one that
    /// its [`Partitioner::prepare_scene`] has not split, where it would silently give the
    /// crease-angle maps. Renderers call it before [`Partitioner::partition`]. The default
    /// accepts every scene.
    fn check_scene(&self, scene: &Scene) -> Result<(), PartitionError> {
        let _ = scene;
        Ok(())
    }

    /// [`Partitioner::check_scene`], then [`Partitioner::partition`].
    fn try_partition(&self, scene: &Scene) -> Result<MapAssignment, PartitionError> {
        self.check_scene(scene)?;
        Ok(self.partition(scene))
    }
}

/// A scene a partitioner cannot serve as it is.
#[derive(Clone, Debug, PartialEq, Eq, thiserror::Error)]
#[non_exhaustive]
pub enum PartitionError {
    /// [`Contact`] was given a scene its `prepare_scene` has not split along the contacts.
    #[error(
        "the contact partition needs a scene split along its contacts: pass the scene through \
         `Contact::prepare_scene` (or `Contact::split_scene`) first"
    )]
    NotSplitAtContacts,
}

/// Every part in map 0: one global photon map (Ball & Stejko's basic variant).
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
