//! Partitions of the scene's parts into photon maps: the trait, its result (the scene it
//! partitioned, every part's map and what the contact split found), one map for everything,
//! flood fill across mesh edges with a small crease angle, and the same aware of faces in
//! contact.

pub(crate) mod assignment;
mod contact;
pub(crate) mod crease;
mod flood;
mod partitioned;
mod record;

pub use assignment::MapAssignment;
pub use contact::Contact;
pub use crease::CreaseAngle;
pub use partitioned::{PartitionError, Partitioned};
pub use record::{ContactRecord, ContactSeconds};

use crate::scene::Scene;

/// Decides which photon map each part of a scene belongs to.
///
/// A partitioner takes the scene and returns a [`Partitioned`]: the scene it partitioned
/// (for [`Contact`], rebuilt with its faces cut where other faces meet them), the map of every
/// part of *that* scene, and for [`Contact`] what the split found. Renderers and photon
/// tracing take the value, so a scene and an assignment made for another scene cannot meet,
/// and contact maps come only with the scene split for them.
///
/// To write one, compute a [`MapAssignment`] for the scene and return
/// [`Partitioned::new`]`(scene, assignment)`.
pub trait Partitioner {
    /// Partitions `scene`. Fails when the partitioner cannot serve it (the contact split past
    /// its bounds, or an assignment that does not cover the scene's parts).
    fn partition(&self, scene: Scene) -> Result<Partitioned, PartitionError>;
}

/// Every part in map 0: one global photon map (Ball & Stejko's basic variant).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct SingleMap;

impl Partitioner for SingleMap {
    fn partition(&self, scene: Scene) -> Result<Partitioned, PartitionError> {
        let assignment = MapAssignment::single(scene.part_count());
        Partitioned::new(scene, assignment)
    }
}
