//! Errors from building a photon tree.

use thiserror::Error;

/// Why a [`crate::PhotonTree`] could not be built.
#[derive(Debug, Error, Clone, PartialEq)]
#[non_exhaustive]
pub enum BuildError {
    /// A photon position with a NaN or infinite coordinate.
    #[error("photon {index}: non-finite position {position:?}")]
    NonFinitePosition {
        /// Index in the input.
        index: usize,
        /// The position.
        position: [f32; 3],
    },
    /// A photon coordinate beyond [`crate::MAX_COORDINATE`], where squared distances would
    /// overflow f32.
    #[error("photon {index}: position {position:?} is beyond ±{max:e} m", max = crate::MAX_COORDINATE)]
    PositionOutOfRange {
        /// Index in the input.
        index: usize,
        /// The position.
        position: [f32; 3],
    },
}
