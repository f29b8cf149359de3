//! The pilot: a photon map traced once, whose k-nearest extents fix the gather volume at every
//! surface point for all passes. The extents are computed once, at a sparse set of *sites*
//! (every [`SITE_STRIDE`]-th pilot photon in tree order), and a point takes its nearest site's.
//!
//! A k-nearest query per pixel per pass cost as much as the rest of the pass's gather (a
//! 100-nearest search is some 27,000 instructions; the nearest of a few thousand sites some
//! hundreds). The extent at x is therefore the estimator's k-nearest extent in the full pilot
//! map *at the site nearest to x* (in x's map): piecewise constant over the sites' Voronoi
//! cells, which are a few photon spacings across, well inside a gather volume of k = 100
//! photons. It is a deterministic function of x alone (never of a pass's photons), which is all
//! that Knaus & Zwicker's argument asks of the volume; it adapts to the photon density as the
//! k-nearest extent does.

use crate::error::RenderError;
use crate::estimator::fixed::FixedVolumeEstimator;
use crate::estimator::options::EstimatorOptions;
use crate::estimator::point::MapView;
use crate::estimator::point::SurfacePoint;
use crate::estimator::scratch::EstimatorScratch;
use glam::Vec3;
use pm_kdtree::{Euclidean, KindMask, PhotonTree};
use pm_trace::{MapError, PhotonMaps};
use rayon::prelude::*;

/// One site per this many pilot photons (of the kinds gathered). The photon tree stores its
/// photons in spatial order, so every 16th is an even thinning.
pub(super) const SITE_STRIDE: usize = 16;

/// One map's sites and their extents (`None`: the k nearest all at one point, no volume).
struct Sites {
    tree: PhotonTree,
    extents: Vec<Option<f32>>,
}

/// The pilot maps and, per map, the sites with their extents.
pub(super) struct Pilot {
    pub(super) maps: PhotonMaps,
    sites: Vec<Sites>,
}

impl Pilot {
    /// Picks each map's sites and computes their extents with `estimator` (in parallel over
    /// maps and over each map's sites; the result, and the error reported, do not depend on
    /// the thread count).
    pub(super) fn new<E: FixedVolumeEstimator>(
        maps: PhotonMaps,
        estimator: &E,
        options: &EstimatorOptions,
    ) -> Result<Self, RenderError> {
        let sites: Vec<Result<Sites, RenderError>> = (0..maps.len() as u32)
            .into_par_iter()
            .map(|m| {
                let map = maps.map(m);
                let pilot = map.tree();
                let picked = (0..pilot.len() as u32)
                    .filter(|&i| options.kinds.accepts(pilot.get(i).kind()))
                    .step_by(SITE_STRIDE)
                    .map(|i| pilot.photon(i))
                    .collect();
                let tree = PhotonTree::build(picked).map_err(|source| MapError::Tree { map: m, source })?;
                let view = MapView {
                    tree: pilot,
                    polygons: map.geometry(),
                };
                let extents = (0..tree.len() as u32)
                    .into_par_iter()
                    .map_init(EstimatorScratch::new, |scratch, i| {
                        let site = tree.get(i);
                        let at =
                            SurfacePoint::front(site.position(), -site.direction_l1().normalize_or_zero());
                        estimator.nearest_extent(at, view, options, scratch)
                    })
                    .collect();
                Ok(Sites { tree, extents })
            })
            .collect();
        // The first map's error in map order, as one thread would meet it.
        let sites = sites.into_iter().collect::<Result<Vec<_>, _>>()?;
        Ok(Pilot { maps, sites })
    }

    /// Heap bytes of the pilot's photon trees and of the sites (trees and extents); the
    /// maps' polygons are the scene's and not counted.
    pub(super) fn heap_bytes(&self) -> usize {
        let trees: usize = self.maps.iter().map(|m| m.tree().heap_bytes()).sum();
        let sites: usize = self
            .sites
            .iter()
            .map(|s| s.tree.heap_bytes() + s.extents.capacity() * size_of::<Option<f32>>())
            .sum();
        trees + sites
    }

    /// The gather extent at `at` in map `map` (before the pass's shrink factor): the
    /// estimator's k-nearest extent at the site nearest to `at`, or the maximum distance when
    /// no site of the map lies within it. `None` when there is no volume.
    pub(super) fn extent(
        &self,
        map: usize,
        at: Vec3,
        options: &EstimatorOptions,
        scratch: &mut EstimatorScratch,
    ) -> Option<f32> {
        let sites = self.sites.get(map)?;
        sites.tree.nearest_k::<Euclidean>(
            at,
            1,
            options.max_distance,
            KindMask::ALL,
            &mut scratch.neighbours,
        );
        match scratch.neighbours.as_slice().first() {
            Some(nearest) => sites.extents[nearest.index as usize],
            None => Some(options.max_distance),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::emission::emitter::Emitter;
    use crate::estimator::GeometryCube;
    use crate::mode::Mode;
    use crate::progressive::{PILOT_PASS, trace_and_build};
    use crate::settings::RenderSettings;
    use pm_trace::{CreaseAngle, Partitioner, scenes};

    /// The pilot's extent at a point against brute force: the nearest site (every 16th
    /// photon of the gathered kinds, in tree order) found by a scan, and the k-th smallest
    /// Chebyshev distance from it to the map's photons of those kinds (the maximum distance
    /// when fewer than k lie within it).
    #[test]
    fn extent_is_the_brute_force_k_nearest_extent_at_the_nearest_site() {
        let scene = scenes::build("colored-rooms").unwrap();
        let partitioned = CreaseAngle::default().partition(scene).unwrap();
        let (scene, assignment, _) = partitioned.into_parts();
        let settings = RenderSettings {
            photons: 4_000,
            k: 20,
            mode: Mode::ShadowRays,
            seed: 3,
            ..RenderSettings::default()
        };
        let options = settings.estimator_options(&scene.bounds());
        let maps = trace_and_build(&scene, &assignment, &settings, &Emitter::uniform(), PILOT_PASS)
            .unwrap()
            .0;
        let queries = trace_and_build(&scene, &assignment, &settings, &Emitter::uniform(), 0)
            .unwrap()
            .0;
        let pilot = Pilot::new(maps, &GeometryCube, &options).unwrap();
        let mut scratch = EstimatorScratch::new();
        let mut checked = 0;
        for (m, map) in pilot.maps.iter().enumerate() {
            let tree = map.tree();
            let accepted: Vec<Vec3> = (0..tree.len() as u32)
                .filter(|&i| options.kinds.accepts(tree.get(i).kind()))
                .map(|i| tree.position(i))
                .collect();
            let sites: Vec<Vec3> = accepted.iter().copied().step_by(SITE_STRIDE).collect();
            let probe = queries.map(m as u32).tree();
            for q in (0..probe.len() as u32).step_by(37).map(|i| probe.position(i)) {
                let got = pilot.extent(m, q, &options, &mut scratch);
                let nearest = sites
                    .iter()
                    .copied()
                    .filter(|s| s.distance(q) <= options.max_distance)
                    .min_by(|a, b| a.distance(q).total_cmp(&b.distance(q)));
                let expected = match nearest {
                    None => Some(options.max_distance),
                    Some(site) => {
                        let mut d: Vec<f32> = accepted
                            .iter()
                            .map(|p| (*p - site).abs().max_element())
                            .filter(|&d| d <= options.max_distance)
                            .collect();
                        d.sort_by(f32::total_cmp);
                        let extent = d.get(options.k - 1).copied().unwrap_or(options.max_distance);
                        (extent > 0.0).then_some(extent)
                    }
                };
                match (got, expected) {
                    (Some(g), Some(e)) => {
                        assert!((g - e).abs() <= 1e-5 * e.max(1e-3), "map {m} at {q}: {g} vs {e}")
                    }
                    (g, e) => assert_eq!(g, e, "map {m} at {q}"),
                }
                checked += 1;
            }
        }
        assert!(checked > 50, "only {checked} points checked");
    }
}
