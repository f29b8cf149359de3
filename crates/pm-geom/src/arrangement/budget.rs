//! The bounds on an arrangement's work: pieces and vertices are counted before they are kept,
//! and the error that says which bound was reached.

use glam::Vec3;

/// Why [`split_polygons_at_intersections`](super::split_polygons_at_intersections) stopped: a bound was reached before it allocated
/// more.
#[derive(Clone, Debug, PartialEq, Eq, thiserror::Error)]
#[non_exhaustive]
pub enum ArrangementError {
    /// More candidate face pairs than [`ArrangementOptions::max_pairs`](super::ArrangementOptions::max_pairs).
    #[error("more than {limit} pairs of faces overlap: too many intersecting faces to resolve")]
    TooManyPairs {
        /// The bound.
        limit: usize,
    },
    /// More pieces or cut segments than [`ArrangementOptions::piece_limit`](super::ArrangementOptions::piece_limit)
    /// allows.
    #[error(
        "cutting the faces where they meet makes more than {limit} pieces (faces that nearly coincide over and over, such as near-copies of one mesh, cut each other into grids)"
    )]
    TooManyPieces {
        /// The bound.
        limit: usize,
    },
    /// More distinct cut lines on one polygon than
    /// [`ArrangementOptions::max_cut_lines_per_polygon`](super::ArrangementOptions::max_cut_lines_per_polygon).
    #[error(
        "input polygon {polygon} is cut along more than {limit} lines (a face under a dense field of objects within the gap of it)"
    )]
    TooManyCutLines {
        /// The polygon (its index in the input).
        polygon: usize,
        /// The bound.
        limit: usize,
    },
    /// More vertices than [`ArrangementOptions::max_vertices`](super::ArrangementOptions::max_vertices).
    #[error("cutting the faces where they meet makes more than {limit} vertices")]
    TooManyVertices {
        /// The bound.
        limit: usize,
    },
}

/// Counts pieces and vertices against the bounds before they are kept.
pub(super) struct Budget {
    pub(super) pieces: usize,
    pub(super) vertices: usize,
    max_pieces: usize,
    max_vertices: usize,
}

impl Budget {
    pub(super) fn new(max_pieces: usize, max_vertices: usize) -> Self {
        Budget {
            pieces: 0,
            vertices: 0,
            max_pieces,
            max_vertices,
        }
    }

    pub(super) fn check(&self, pieces: usize, vertices: usize) -> Result<(), ArrangementError> {
        if pieces > self.max_pieces {
            return Err(ArrangementError::TooManyPieces {
                limit: self.max_pieces,
            });
        }
        if vertices > self.max_vertices {
            return Err(ArrangementError::TooManyVertices {
                limit: self.max_vertices,
            });
        }
        Ok(())
    }

    pub(super) fn add(&mut self, piece: &[Vec3]) -> Result<(), ArrangementError> {
        self.check(self.pieces + 1, self.vertices + piece.len())?;
        self.pieces += 1;
        self.vertices += piece.len();
        Ok(())
    }
}
