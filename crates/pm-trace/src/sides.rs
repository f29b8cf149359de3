//! Which sides of a surface emit light and which the camera sees: the renderer's reading of
//! glTF's `doubleSided`, and the built-in scenes' front-emitting default.

/// Which sides of a surface emit (if it emits) and which camera rays see.
///
/// A face's front is the side its counter-clockwise winding's normal points to. Photon,
/// shadow and path rays always see both sides, whatever this says, so closed scenes stay
/// closed: a photon that reaches the back of a single-sided face is stored or scattered
/// there like anywhere else, and a single-sided wall still casts shadows both ways.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
pub enum Sides {
    /// Emits from the front only; camera rays see both sides. The library's own scenes use
    /// this (their area lights are one-sided quads whose backs are plain black surfaces).
    #[default]
    Front,
    /// glTF `doubleSided: false`: emits from the front only, and camera rays (primary and
    /// specular eye rays) pass through the back, as glTF viewers cull back faces. The back is
    /// skipped inside the closest-hit search, so it never hides a front face at the same
    /// distance (two rooms modelled on one wall plane).
    Single,
    /// glTF `doubleSided: true`: emits the same radiance from both sides (an area light of
    /// area `A` and radiance `L` emits `2πLA` watts), and camera rays see both sides.
    Double,
}

impl Sides {
    /// True when the back side emits too.
    #[inline]
    pub fn emits_back(self) -> bool {
        self == Sides::Double
    }

    /// True when camera rays pass through the back side.
    #[inline]
    pub fn culls_back(self) -> bool {
        self == Sides::Single
    }

    /// The number of emitting sides, 1 or 2 (the factor on an emitter's power).
    #[inline]
    pub fn emitting_sides(self) -> f32 {
        if self.emits_back() { 2.0 } else { 1.0 }
    }
}
