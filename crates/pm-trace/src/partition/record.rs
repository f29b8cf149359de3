//! What the contact partition found when it split a scene: the segments no map crosses, the
//! pieces inside closed solids, and counts of each kind of meeting.

use crate::part::{PartId, SourceFace};
use pm_geom::{ArrangementSeconds, BarrierSet, IntersectionCounts};

/// What [`Contact`](super::Contact) found and cut when it split a scene: the meeting segments no map crosses, the pieces
/// inside closed solids, and counts of each kind of meeting.
#[derive(Clone, Debug, Default)]
pub struct ContactRecord {
    pub(super) barriers: BarrierSet,
    pub(super) sealed_parts: Vec<bool>,
    /// The user's face of each part of the split scene (`None` for analytic parts).
    pub(super) source_faces: Vec<Option<SourceFace>>,
    pub(super) counts: IntersectionCounts,
    pub(super) seconds: f64,
    pub(super) phases: ContactSeconds,
}

/// Wall-clock seconds of each step of the contact partition, in the order they run; their sum
/// is [`ContactRecord::seconds`] (the few instructions between two steps are not counted).
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct ContactSeconds {
    /// Collecting the scene's mesh faces as polygons.
    pub faces: f64,
    /// Cutting them where they meet, step by step.
    pub arrangement: ArrangementSeconds,
    /// Rebuilding the scene's meshes from the pieces (welding, half-edge meshes, parts).
    pub rebuild: f64,
    /// Locating the pieces on the faces as given, which the rays meet.
    pub faces_as_given: f64,
    /// Filling the maps of the split scene (the flood fill, the joins across meshes).
    pub fill: f64,
}

impl ContactSeconds {
    /// The sum of the steps.
    pub fn total(&self) -> f64 {
        self.faces + self.arrangement.total() + self.rebuild + self.faces_as_given + self.fill
    }
}

impl ContactRecord {
    /// How many meetings of each kind were found, and pieces dropped or sealed.
    pub fn counts(&self) -> IntersectionCounts {
        self.counts
    }

    /// The segments along which faces meet: no photon map joins across them.
    pub fn barriers(&self) -> &BarrierSet {
        &self.barriers
    }

    /// True when `part` lies inside a closed solid, where no light reaches.
    pub fn is_sealed(&self, part: PartId) -> bool {
        self.sealed_parts.get(part.0 as usize).copied().unwrap_or(false)
    }

    /// The face the user gave that `part` of the split scene is a piece of (`None` for an
    /// analytic part or a part not in the scene).
    pub fn source_face(&self, part: PartId) -> Option<SourceFace> {
        self.source_faces.get(part.0 as usize).copied().flatten()
    }

    /// Wall-clock seconds the partition took: cutting the faces where they meet, rebuilding
    /// the scene from the pieces, and filling its maps.
    pub fn seconds(&self) -> f64 {
        self.seconds
    }

    /// The same time step by step.
    pub fn phases(&self) -> ContactSeconds {
        self.phases
    }
}
