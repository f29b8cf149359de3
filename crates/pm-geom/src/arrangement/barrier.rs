//! Barrier segments: the lines along which faces meet, which no photon map may cross, with a
//! query that tells whether a mesh edge runs along one of them.

use crate::aabb::Aabb;
use crate::bounds_bvh::BoundsBvh;
use glam::Vec3;

/// A set of segments and a tolerance, answering "does this edge run along a segment".
///
/// ```
/// use pm_geom::BarrierSet;
/// use pm_geom::glam::vec3;
/// let barriers = BarrierSet::new(vec![[vec3(1., 0., 0.), vec3(1., 0., 1.)]], 1e-5);
/// assert!(barriers.covers_edge(vec3(1., 0., 0.25), vec3(1., 0., 0.75)));
/// assert!(!barriers.covers_edge(vec3(0., 0., 0.5), vec3(2., 0., 0.5))); // crosses it
/// ```
#[derive(Clone, Debug, Default)]
pub struct BarrierSet {
    segments: Vec<[Vec3; 2]>,
    boxes: Vec<Aabb>,
    bvh: BoundsBvh,
    tolerance: f32,
}

impl BarrierSet {
    /// The set of `segments`, with points within `tolerance` (metres) of a segment on it.
    /// Non-finite segments are left out.
    pub fn new(mut segments: Vec<[Vec3; 2]>, tolerance: f32) -> Self {
        segments.retain(|s| s[0].is_finite() && s[1].is_finite());
        let pad = Vec3::splat(tolerance);
        let boxes: Vec<Aabb> = segments
            .iter()
            .map(|s| {
                let b = Aabb::from_points(s);
                Aabb::new(b.min - pad, b.max + pad)
            })
            .collect();
        BarrierSet {
            bvh: BoundsBvh::build_sah(&boxes, crate::bounds_bvh::MAX_LEAF),
            segments,
            boxes,
            tolerance,
        }
    }

    /// True when the set has no segment.
    pub fn is_empty(&self) -> bool {
        self.segments.is_empty()
    }

    /// Number of segments.
    pub fn len(&self) -> usize {
        self.segments.len()
    }

    /// The segments.
    pub fn segments(&self) -> &[[Vec3; 2]] {
        &self.segments
    }

    /// True when the edge `pq` runs along some segment: both ends lie on the segment's line
    /// and its midpoint on the segment (all within the tolerance). An edge only partly along a
    /// barrier counts, so that a photon map never joins across any part of one.
    pub fn covers_edge(&self, p: Vec3, q: Vec3) -> bool {
        if self.segments.is_empty() {
            return false;
        }
        let middle = (p + q) * 0.5;
        let query = Aabb::new(middle, middle);
        let mut covered = false;
        self.bvh.for_each_candidate(&query, |i| {
            if covered || !self.boxes[i as usize].contains_point(middle) {
                return;
            }
            let [a, b] = self.segments[i as usize];
            let Some(direction) = (b - a).try_normalize() else {
                return;
            };
            let off_line = |x: Vec3| (x - a).reject_from_normalized(direction).length();
            covered = off_line(p) <= self.tolerance
                && off_line(q) <= self.tolerance
                && super::face::distance_to_segment(middle, a, b) <= self.tolerance;
        });
        covered
    }
}
