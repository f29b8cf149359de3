//! The pilot: a photon map traced once, whose k-nearest extents fix the gather volume at every
//! surface point for all passes. The extents are taken at a sparse set of *sites* (every
//! [`SITE_STRIDE`]-th pilot photon in tree order), and a point takes its nearest site's.
//!
//! A k-nearest query per pixel per pass cost as much as the rest of the pass's gather (a
//! 100-nearest search is some 27,000 instructions; the nearest of a few thousand sites some
//! hundreds). The extent at x is therefore the estimator's k-nearest extent in the full pilot
//! map *at the site nearest to x* (in x's map): piecewise constant over the sites' Voronoi
//! cells, which are a few photon spacings across, well inside a gather volume of k = 100
//! photons. It is a deterministic function of x alone (never of a pass's photons), which is all
//! that Knaus & Zwicker's argument asks of the volume; it adapts to the photon density as the
//! k-nearest extent does.
//!
//! Nothing is computed for a point no pass asks about: a site's extent is computed the first
//! time a point takes that site, and a map's polygons (which the extent and every estimate
//! clip) the first time a point in that map is estimated ([`PhotonMaps`]). A camera
//! sees few of a finely split scene's maps (1,090 of a modelled kitchen's 16,854 contact maps
//! in a 320×180 view), and the extent at a site is the same number whoever computes it first,
//! so the images do not change.

use crate::error::RenderError;
use crate::estimator::fixed::FixedVolumeEstimator;
use crate::estimator::options::EstimatorOptions;
use crate::estimator::point::MapView;
use crate::estimator::point::SurfacePoint;
use crate::estimator::scratch::EstimatorScratch;
use glam::Vec3;
use pm_geom::PolygonSet;
use pm_kdtree::{Euclidean, KindMask, PhotonTree};
use pm_trace::{MapError, PartId, PhotonMaps};
use rayon::prelude::*;
use std::sync::OnceLock;

/// One site per this many pilot photons (of the kinds gathered). The photon tree stores its
/// photons in spatial order, so every 16th is an even thinning.
pub(super) const SITE_STRIDE: usize = 16;

/// One map's sites and their extents, each computed when first asked for (`Some(None)`: the
/// k nearest all at one point, no volume).
struct Sites {
    tree: PhotonTree,
    extents: Vec<OnceLock<Option<f32>>>,
}

/// The pilot maps (whose polygons are built when first read), and per map the sites with
/// their extents (computed when first asked for) under `estimator` and `options`.
pub(super) struct Pilot<'e, E> {
    maps: PhotonMaps,
    sites: Vec<Sites>,
    estimator: &'e E,
    options: EstimatorOptions,
}

impl<'e, E: FixedVolumeEstimator> Pilot<'e, E> {
    /// Picks each map's sites among the pilot `maps`' photons (in parallel; the error
    /// reported does not depend on the thread count). Extents and polygons are computed as
    /// points ask for them.
    pub(super) fn new(
        maps: PhotonMaps,
        estimator: &'e E,
        options: &EstimatorOptions,
    ) -> Result<Self, RenderError> {
        let sites: Vec<Result<Sites, RenderError>> = maps
            .trees()
            .par_iter()
            .enumerate()
            .map(|(m, pilot)| {
                let picked = (0..pilot.len() as u32)
                    .filter(|&i| options.kinds.accepts(pilot.get(i).kind()))
                    .step_by(SITE_STRIDE)
                    .map(|i| pilot.photon(i))
                    .collect();
                let tree = PhotonTree::build(picked).map_err(|source| MapError::Tree {
                    map: m as u32,
                    source,
                })?;
                let extents = (0..tree.len()).map(|_| OnceLock::new()).collect();
                Ok(Sites { tree, extents })
            })
            .collect();
        // The first map's error in map order, as one thread would meet it.
        let sites = sites.into_iter().collect::<Result<Vec<_>, _>>()?;
        Ok(Pilot {
            maps,
            sites,
            estimator,
            options: *options,
        })
    }

    /// Heap bytes of the pilot's photon trees and of the sites (trees and extents); the
    /// maps' polygons are the scene's and not counted.
    pub(super) fn heap_bytes(&self) -> usize {
        let trees: usize = self.maps.trees().iter().map(|t| t.heap_bytes()).sum();
        let sites: usize = self
            .sites
            .iter()
            .map(|s| s.tree.heap_bytes() + s.extents.capacity() * size_of::<OnceLock<Option<f32>>>())
            .sum();
        trees + sites
    }

    /// The map of `part`.
    pub(super) fn map_of(&self, part: PartId) -> u32 {
        self.maps.map_of(part)
    }

    /// Map `map`'s polygons (built now if no point asked before), or `None` when there is no
    /// such map.
    pub(super) fn polygons(&self, map: u32) -> Option<&PolygonSet> {
        Some(self.maps.get(map)?.geometry())
    }

    /// How many maps' polygons have been built so far.
    pub(super) fn maps_built(&self) -> usize {
        self.maps.maps_read()
    }

    /// The gather extent at `at` in map `map` (before the pass's shrink factor): the
    /// estimator's k-nearest extent in the pilot map at the site nearest to `at` (computed
    /// now if no point took that site before), or the maximum distance when no site of the
    /// map lies within it. `None` when there is no volume.
    pub(super) fn extent(&self, map: usize, at: Vec3, scratch: &mut EstimatorScratch) -> Option<f32> {
        let sites = self.sites.get(map)?;
        let options = &self.options;
        sites.tree.nearest_k::<Euclidean>(
            at,
            1,
            options.max_distance,
            KindMask::ALL,
            &mut scratch.neighbours,
        );
        let Some(nearest) = scratch.neighbours.as_slice().first().map(|n| n.index) else {
            return Some(options.max_distance);
        };
        *sites.extents[nearest as usize].get_or_init(|| {
            let site = sites.tree.get(nearest);
            let at = SurfacePoint::front(site.position(), -site.direction_l1().normalize_or_zero());
            let pilot = self.maps.map(map as u32);
            let view = MapView {
                tree: pilot.tree(),
                polygons: pilot.geometry(),
            };
            self.estimator.nearest_extent(at, view, options, scratch)
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::emission::emitter::Emitter;
    use crate::estimator::GeometryCube;
    use crate::mode::Mode;
    use crate::progressive::PILOT_PASS;
    use crate::progressive::pass_maps::trace_pass;
    use crate::settings::RenderSettings;
    use pm_trace::{CreaseAngle, MapGeometry, Partitioner, scenes};

    /// A built-in scene's crease maps and shadow-rays settings (k = 20), whose passes' photon
    /// trees the tests trace.
    struct Setup {
        scene: pm_trace::Scene,
        assignment: pm_trace::MapAssignment,
        settings: RenderSettings,
        options: EstimatorOptions,
    }

    impl Setup {
        fn new(name: &str, photons: u32, seed: u64) -> Self {
            let scene = scenes::build(name).unwrap();
            let (scene, assignment, _) = CreaseAngle::default().partition(scene).unwrap().into_parts();
            let settings = RenderSettings {
                photons,
                k: 20,
                mode: Mode::ShadowRays,
                seed,
                ..RenderSettings::default()
            };
            let options = settings.estimator_options(&scene.bounds());
            Setup {
                scene,
                assignment,
                settings,
                options,
            }
        }

        /// Pass `pass`'s photon trees, all kinds.
        fn trace(&self, pass: u64) -> Vec<PhotonTree> {
            let (scene, assignment) = (&self.scene, &self.assignment);
            trace_pass(
                scene,
                assignment,
                &self.settings,
                &Emitter::uniform(),
                pass,
                KindMask::ALL,
            )
            .unwrap()
            .trees
        }

        /// A pilot over the pilot pass's photons, nothing computed yet.
        fn pilot(&self) -> Pilot<'static, GeometryCube> {
            let trees = self.trace(PILOT_PASS);
            let maps = PhotonMaps::from_trees(&self.scene, &self.assignment, trees, MapGeometry::Merged);
            Pilot::new(maps.unwrap(), &GeometryCube, &self.options).unwrap()
        }
    }

    /// The pilot's extent at a point against brute force: the nearest site (every 16th
    /// photon of the gathered kinds, in tree order) found by a scan, and the k-th smallest
    /// Chebyshev distance from it to the map's photons of those kinds (the maximum distance
    /// when fewer than k lie within it).
    #[test]
    fn extent_is_the_brute_force_k_nearest_extent_at_the_nearest_site() {
        let setup = Setup::new("colored-rooms", 4_000, 3);
        let options = setup.options;
        let queries = setup.trace(0);
        let pilot = setup.pilot();
        assert_eq!(pilot.maps_built(), 0, "nothing built before a point asks");
        let mut scratch = EstimatorScratch::new();
        let mut checked = 0;
        for (m, tree) in pilot.maps.trees().iter().enumerate() {
            let accepted: Vec<Vec3> = (0..tree.len() as u32)
                .filter(|&i| options.kinds.accepts(tree.get(i).kind()))
                .map(|i| tree.position(i))
                .collect();
            let sites: Vec<Vec3> = accepted.iter().copied().step_by(SITE_STRIDE).collect();
            let probe = &queries[m];
            for q in (0..probe.len() as u32).step_by(37).map(|i| probe.position(i)) {
                let got = pilot.extent(m, q, &mut scratch);
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

    /// Extents computed on demand are the same bits whatever order points ask in and on
    /// whichever thread asks first, and only the maps asked about get polygons.
    #[test]
    fn extents_do_not_depend_on_who_asks_first() {
        let setup = Setup::new("cornell-box", 3_000, 5);
        let queries: Vec<(usize, Vec3)> = setup
            .trace(0)
            .iter()
            .enumerate()
            .flat_map(|(m, t)| (0..t.len() as u32).map(move |i| (m, t.position(i))))
            .collect();
        assert!(queries.len() > 1_000);
        let (forward, backward) = (setup.pilot(), setup.pilot());
        let mut scratch = EstimatorScratch::new();
        let in_order: Vec<Option<f32>> = queries
            .iter()
            .map(|&(m, q)| forward.extent(m, q, &mut scratch))
            .collect();
        let mut reversed: Vec<Option<f32>> = queries
            .par_iter()
            .rev()
            .map_init(EstimatorScratch::new, |scratch, &(m, q)| {
                backward.extent(m, q, scratch)
            })
            .collect();
        reversed.reverse();
        let bits = |v: &[Option<f32>]| v.iter().map(|e| e.map(f32::to_bits)).collect::<Vec<_>>();
        assert_eq!(bits(&in_order), bits(&reversed));
        let asked: std::collections::BTreeSet<usize> = queries.iter().map(|&(m, _)| m).collect();
        let with_sites = asked
            .iter()
            .filter(|&&m| !forward.sites[m].tree.is_empty())
            .count();
        assert_eq!(forward.maps_built(), with_sites);
    }
}
