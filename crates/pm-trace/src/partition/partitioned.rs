//! What a partitioner returns: the scene it partitioned, the map of every part of that scene,
//! and what the contact split found; the only way a renderer gets maps.

use super::assignment::MapAssignment;
use super::record::ContactRecord;
use crate::camera::Camera;
use crate::error::SceneError;
use crate::part::{PartId, SourceFace};
use crate::scene::Scene;

/// A scene with the photon map of each of its parts: what a [`super::Partitioner`] returns and
/// what the renderers take.
///
/// The assignment always covers exactly the scene's parts. For the contact partition the
/// scene is the one it split (its faces cut where other faces meet them) and
/// [`Partitioned::record`] says what it found; every other partitioner leaves the scene as it
/// was given and has no record. So contact maps come only with a split scene: there is no
/// step to forget.
#[derive(Clone, Debug)]
pub struct Partitioned {
    scene: Scene,
    assignment: MapAssignment,
    record: Option<ContactRecord>,
}

impl Partitioned {
    /// `scene` with `assignment`, for a partitioner written outside this crate. Refuses an
    /// assignment whose part count is not the scene's
    /// ([`PartitionError::AssignmentMismatch`]).
    pub fn new(scene: Scene, assignment: MapAssignment) -> Result<Self, PartitionError> {
        if assignment.part_count() != scene.part_count() {
            return Err(PartitionError::AssignmentMismatch {
                scene_parts: scene.part_count(),
                assigned_parts: assignment.part_count(),
            });
        }
        Ok(Partitioned {
            scene,
            assignment,
            record: None,
        })
    }

    /// The contact partition's result: the split scene, its assignment and the record.
    pub(super) fn with_record(scene: Scene, assignment: MapAssignment, record: ContactRecord) -> Self {
        debug_assert_eq!(assignment.part_count(), scene.part_count());
        Partitioned {
            scene,
            assignment,
            record: Some(record),
        }
    }

    /// The scene partitioned: for the contact partition, the split scene.
    pub fn scene(&self) -> &Scene {
        &self.scene
    }

    /// The photon map of every part of [`Partitioned::scene`].
    pub fn assignment(&self) -> &MapAssignment {
        &self.assignment
    }

    /// A text naming this partition for a render's identity: the part and map counts and the
    /// assignment's [`MapAssignment::fingerprint`]. Two partitions with the same identity put
    /// every part of the same parts in the same map, whichever partitioner made them.
    pub fn identity(&self) -> String {
        format!(
            "parts={} maps={} assignment={:016x}",
            self.assignment.part_count(),
            self.assignment.map_count(),
            self.assignment.fingerprint()
        )
    }

    /// What the contact partition found and cut; `None` for every other partitioner.
    pub fn record(&self) -> Option<&ContactRecord> {
        self.record.as_ref()
    }

    /// The same partition seen through `camera` (checked as [`Scene::with_camera`] checks
    /// it): the parts and their maps do not depend on the viewpoint.
    pub fn with_camera(self, camera: Camera) -> Result<Self, SceneError> {
        Ok(Partitioned {
            scene: self.scene.with_camera(camera)?,
            ..self
        })
    }

    /// The face the user gave that `part` of [`Partitioned::scene`] is (or, after the contact
    /// split, is a piece of): its mesh and face index in the scene as built, so per-face data
    /// (a material id, an object id) can be looked up. `None` for analytic parts.
    pub fn source_face(&self, part: PartId) -> Option<SourceFace> {
        match &self.record {
            Some(record) => record.source_face(part),
            None => self.scene.source_face(part),
        }
    }

    /// The scene, the assignment and the record, by value.
    pub fn into_parts(self) -> (Scene, MapAssignment, Option<ContactRecord>) {
        (self.scene, self.assignment, self.record)
    }
}

/// Why a scene could not be partitioned.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
#[non_exhaustive]
pub enum PartitionError {
    /// The contact partition could not split the scene where its faces meet: more meetings
    /// than the arrangement's bounds allow ([`SceneError::Arrangement`]), or the rebuilt scene
    /// was refused.
    #[error("splitting the scene where its faces meet: {0}")]
    Split(#[from] SceneError),
    /// An assignment for a different number of parts than the scene has.
    #[error("the assignment covers {assigned_parts} parts but the scene has {scene_parts}")]
    AssignmentMismatch {
        /// Parts of the scene.
        scene_parts: usize,
        /// Parts the assignment covers.
        assigned_parts: usize,
    },
}
