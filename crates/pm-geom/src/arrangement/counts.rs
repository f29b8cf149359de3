//! How many meetings of each kind an arrangement found, and the pieces it dropped or sealed.

/// How many meetings of each kind [`split_polygons_at_intersections`](super::split_polygons_at_intersections) found.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct IntersectionCounts {
    /// Face pairs passing through each other.
    pub piercing: usize,
    /// Face pairs where an edge of one lies in the other, across its inside.
    pub in_plane: usize,
    /// Face pairs lying in one plane and overlapping.
    pub coplanar_overlap: usize,
    /// Face pairs closer than the gap tolerance without meeting.
    pub near_contact: usize,
    /// Pieces dropped because another face covers them in the same plane, facing the same way
    /// (duplicated faces: only the first is kept).
    pub duplicate_pieces: usize,
    /// Pieces inside a closed solid, where no light reaches.
    pub sealed_pieces: usize,
    /// Face pairs examined: those the broad phase found close enough to meet (each pair
    /// once), of which the counts above met.
    pub candidate_pairs: usize,
}

impl IntersectionCounts {
    /// Meetings of every kind (not counting dropped or sealed pieces).
    pub fn meetings(&self) -> usize {
        self.piercing + self.in_plane + self.coplanar_overlap + self.near_contact
    }
}
