//! Jensen's disc estimator: `E = Σ Φ_p / (π r²)` over the k nearest photons in a sphere (each
//! power times the caller's photon weight).

use super::gather::counted_neighbours;
use super::{Estimator, find_nearest};
use crate::estimator::gather::gather_found;
use crate::estimator::options::EstimatorOptions;
use crate::estimator::point::MapView;
use crate::estimator::point::SurfacePoint;
use crate::estimator::scratch::EstimatorScratch;
use crate::estimator::weight::PhotonWeight;
use glam::Vec3;
use pm_kdtree::Euclidean;
use std::f32::consts::PI;

/// Jensen's estimator: the k nearest photons (Euclidean) divided by the disc `π r²`, where `r`
/// is the k-th distance or the maximum distance when fewer were found.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct Disc;

impl Estimator for Disc {
    /// `disc`.
    fn identity(&self) -> String {
        "disc".to_owned()
    }

    fn estimate(
        &self,
        at: SurfacePoint,
        map: MapView<'_>,
        options: &EstimatorOptions,
        weight: &dyn PhotonWeight,
        scratch: &mut EstimatorScratch,
    ) -> Vec3 {
        let Some(r) = find_nearest::<Euclidean>(at, map, options, scratch) else {
            return Vec3::ZERO;
        };
        let power: Vec3 = match weight.uniform() {
            // Directions are only needed to reject photons from behind or to weight them:
            // without either, skip decoding them, sum powers relative to the map's scale and
            // scale once.
            Some(uniform) if !options.reject_behind => {
                let counted = counted_neighbours(&scratch.neighbours, options.leave_out_boundary);
                let found = scratch.neighbours.as_slice().iter().filter(|n| counted(n));
                let relative: Vec3 = found.map(|n| map.tree.get(n.index).relative_power()).sum();
                relative * map.tree.power_scale().watts() * uniform
            }
            _ => {
                gather_found(at, map.tree, options, weight, scratch);
                scratch.photons.iter().map(|p| p.power).sum()
            }
        };
        power / (PI * r * r)
    }
}
