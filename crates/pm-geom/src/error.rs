//! Errors from building meshes.

use thiserror::Error;

/// Why a [`crate::HalfEdgeMesh`] could not be built, or which invariant `validate` found broken.
#[derive(Debug, Error, Clone, PartialEq)]
#[non_exhaustive]
pub enum MeshError {
    /// A face refers to a vertex that does not exist.
    #[error("face {face}: vertex index {index} out of range for {vertex_count} vertices")]
    IndexOutOfRange {
        /// Input face index.
        face: usize,
        /// The bad index.
        index: u32,
        /// Number of input positions.
        vertex_count: usize,
    },
    /// A face with fewer than three vertices.
    #[error("face {face}: {count} vertices, a face needs at least 3")]
    TooFewVertices {
        /// Input face index.
        face: usize,
        /// Its vertex count.
        count: usize,
    },
    /// A position with a NaN or infinite coordinate.
    #[error("vertex {vertex}: non-finite position {position:?}")]
    NonFinitePosition {
        /// Input vertex index.
        vertex: usize,
        /// The position.
        position: [f32; 3],
    },
    /// `validate` found a broken invariant.
    #[error("invalid mesh: {0}")]
    Invalid(String),
}
