//! Compact 20-byte photons and an implicit kd-tree with k-nearest queries in a sphere
//! (Euclidean) or a cube (Chebyshev, L∞).
//!
//! (Crate docs to be completed by the pm-kdtree issue: conventions, example.)

pub mod error;
pub mod metric;
pub mod photon;
pub mod query;
pub mod tree;

pub use error::BuildError;
pub use metric::{Chebyshev, Euclidean, Metric};
pub use photon::{CompactPhoton, KindMask, Photon, PhotonKind};
pub use query::{Neighbour, Neighbours};
pub use tree::PhotonTree;
