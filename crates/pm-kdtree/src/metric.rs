//! Distance metrics for k-nearest queries: Euclidean (a sphere) and Chebyshev (a cube).

use glam::Vec3;

/// A distance metric. Queries are generic over it so the hot loop is monomorphised.
pub trait Metric: Copy + Send + Sync + 'static {
    /// Distance between two points (true distance, not squared).
    fn distance(a: Vec3, b: Vec3) -> f32;
}

/// Euclidean distance: the k nearest lie in a sphere.
#[derive(Clone, Copy, Debug, Default)]
pub struct Euclidean;
/// Chebyshev (L∞) distance: the k nearest lie in an axis-aligned cube.
#[derive(Clone, Copy, Debug, Default)]
pub struct Chebyshev;

impl Metric for Euclidean {
    fn distance(a: Vec3, b: Vec3) -> f32 {
        a.distance(b)
    }
}
impl Metric for Chebyshev {
    fn distance(a: Vec3, b: Vec3) -> f32 {
        (a - b).abs().max_element()
    }
}
