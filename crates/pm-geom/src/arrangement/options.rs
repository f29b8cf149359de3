//! What a caller sets for an arrangement: the tolerance under which points coincide, the gap
//! under which faces touch, and the bounds on its work.

/// Tolerances and bounds of [`split_polygons_at_intersections`](super::split_polygons_at_intersections).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ArrangementOptions {
    /// Distance (metres) under which points coincide and a point lies on a plane or a line; a
    /// good choice is `1e-5` × the scene's diagonal, and a mesh welded from the output should
    /// use the same weld tolerance.
    pub tolerance: f32,
    /// Distance (metres, at least `tolerance`) under which two faces that do not meet count as
    /// touching: a wall that stops this close to a floor cuts the floor as if it stood on it.
    pub gap: f32,
    /// Most candidate face pairs (faces whose padded bounds overlap) examined.
    pub max_pairs: usize,
    /// Most output pieces, and most cut segments.
    pub max_pieces: usize,
    /// Most vertices over all output pieces.
    pub max_vertices: usize,
}

impl ArrangementOptions {
    /// Default [`Self::max_pairs`]: 16 million pairs, a few seconds of work.
    pub const DEFAULT_MAX_PAIRS: usize = 16_000_000;
    /// Default [`Self::max_pieces`]: 2 million pieces.
    pub const DEFAULT_MAX_PIECES: usize = 2_000_000;
    /// Default [`Self::max_vertices`]: 16 million vertices (192 MB of positions).
    pub const DEFAULT_MAX_VERTICES: usize = 16_000_000;

    /// `tolerance` and `gap` with the default bounds.
    pub fn new(tolerance: f32, gap: f32) -> Self {
        ArrangementOptions {
            tolerance,
            gap,
            max_pairs: Self::DEFAULT_MAX_PAIRS,
            max_pieces: Self::DEFAULT_MAX_PIECES,
            max_vertices: Self::DEFAULT_MAX_VERTICES,
        }
    }
}
