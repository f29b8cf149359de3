//! Photon maps: per map, the photons in a kd-tree and the map's polygons (with an overlap
//! index) for the geometry-based estimators, built the first time the map is read.

use super::map_geometry::{MapGeometry, MapPolygonTable, check_assignment};
use super::traced::TracedPhotons;
use crate::error::{MapError, TraceError};
use crate::part::PartId;
use crate::partition::assignment::MapAssignment;
use crate::scene::Scene;
use glam::Vec3;
use pm_geom::{Aabb, PolygonSet};
use pm_kdtree::PhotonTree;
use rayon::prelude::*;

/// One photon map: its photons and its geometry, borrowed from its [`PhotonMaps`].
#[derive(Clone, Copy, Debug)]
pub struct PhotonMap<'a> {
    tree: &'a PhotonTree,
    table: &'a MapPolygonTable,
    id: usize,
}

impl<'a> PhotonMap<'a> {
    /// The photons.
    pub fn tree(&self) -> &'a PhotonTree {
        self.tree
    }

    /// The map's polygons (mesh faces with coplanar neighbours merged, analytic parts as fine
    /// proxies), indexed; built now if the map was not read before.
    pub fn geometry(&self) -> &'a PolygonSet {
        &self.table.get(self.id).polygons
    }

    /// Bounds of the map's polygons (building them if the map was not read before).
    pub fn bounds(&self) -> Aabb {
        self.table.get(self.id).bounds
    }
}

/// All photon maps of a scene and the map of each part: the maps' photon trees and their
/// polygons in two tables (the trees as they were built, never copied), read as
/// [`PhotonMap`]s.
///
/// A map's polygons are merged and indexed the first time the map is read
/// ([`PhotonMap::geometry`]): the maps hold a copy of the scene's faces, and a renderer that
/// estimates where its camera looks builds the polygons of the few maps it sees (on a modelled
/// kitchen split into 16,854 contact maps, 1,090 in a 320×180 view). The polygons are the
/// same whenever and on whichever thread they are built.
#[derive(Clone, Debug)]
pub struct PhotonMaps {
    trees: Vec<PhotonTree>,
    geometry: MapPolygonTable,
    assignment: MapAssignment,
}

impl PhotonMaps {
    /// Builds every map (in parallel): a kd-tree over its photons and its polygon set, with
    /// coplanar faces merged ([`MapGeometry::Merged`]).
    pub fn build(scene: &Scene, assignment: &MapAssignment, traced: TracedPhotons) -> Result<Self, MapError> {
        Self::build_with(scene, assignment, traced, MapGeometry::Merged)
    }

    /// As [`PhotonMaps::build`], storing each map's polygons as `geometry` says.
    pub fn build_with(
        scene: &Scene,
        assignment: &MapAssignment,
        traced: TracedPhotons,
        geometry: MapGeometry,
    ) -> Result<Self, MapError> {
        check_assignment(scene, assignment)?;
        let (photons, _) = traced.into_parts();
        if photons.len() != assignment.map_count() as usize {
            return Err(TraceError::AssignmentMismatch {
                assigned: photons.len(),
                parts: assignment.map_count() as usize,
            }
            .into());
        }
        let trees = photons
            .into_par_iter()
            .enumerate()
            // Encodes relative to the map's brightest channel and drops the full-precision photons.
            .map(|(m, photons)| {
                PhotonTree::build(photons).map_err(|source| MapError::Tree {
                    map: m as u32,
                    source,
                })
            })
            .collect::<Result<Vec<_>, _>>()?;
        Self::from_trees(scene, assignment, trees, geometry)
    }

    /// The maps of photon trees built before (`trees[m]` for map `m` of `assignment`, e.g.
    /// read back from a cache file), each with its polygons from `scene` as `geometry` says
    /// (the faces copied now, merged when first read): the same maps, bit for bit, as
    /// [`PhotonMaps::build_with`] made with those trees.
    /// Refused when the scene's part count or the map count differs from the assignment's.
    pub fn from_trees(
        scene: &Scene,
        assignment: &MapAssignment,
        trees: Vec<PhotonTree>,
        geometry_kind: MapGeometry,
    ) -> Result<Self, MapError> {
        check_assignment(scene, assignment)?;
        if trees.len() != assignment.map_count() as usize {
            return Err(TraceError::AssignmentMismatch {
                assigned: trees.len(),
                parts: assignment.map_count() as usize,
            }
            .into());
        }
        Ok(PhotonMaps {
            trees,
            geometry: MapPolygonTable::new(scene, assignment, geometry_kind),
            assignment: assignment.clone(),
        })
    }

    /// How each map stores its polygons.
    pub fn geometry_kind(&self) -> MapGeometry {
        self.geometry.kind()
    }

    /// How many maps' polygons have been built so far (each the first time its map was read).
    pub fn maps_read(&self) -> usize {
        self.geometry.built_count()
    }

    /// The area of map `id`'s faces, square metres (its polygons' area up to rounding,
    /// without building them), or `None` when there is no such map.
    pub fn face_area(&self, id: u32) -> Option<f64> {
        ((id as usize) < self.len()).then(|| self.geometry.face_area(id as usize))
    }

    /// The map of `part`.
    #[inline]
    pub fn map_of(&self, part: PartId) -> u32 {
        self.assignment.map_of(part)
    }

    /// Map `id`. Panics when `id` is not below [`PhotonMaps::len`], like slice indexing.
    #[inline]
    pub fn map(&self, id: u32) -> PhotonMap<'_> {
        PhotonMap {
            tree: &self.trees[id as usize],
            table: &self.geometry,
            id: id as usize,
        }
    }

    /// Map `id`, or `None` when there is no such map.
    #[inline]
    pub fn get(&self, id: u32) -> Option<PhotonMap<'_>> {
        Some(PhotonMap {
            tree: self.trees.get(id as usize)?,
            table: &self.geometry,
            id: id as usize,
        })
    }

    /// All maps, in order of their ids.
    pub fn iter(&self) -> impl ExactSizeIterator<Item = PhotonMap<'_>> + '_ {
        self.trees.iter().enumerate().map(|(id, tree)| PhotonMap {
            tree,
            table: &self.geometry,
            id,
        })
    }

    /// Every map's photon tree, in order of the maps' ids.
    pub fn trees(&self) -> &[PhotonTree] {
        &self.trees
    }

    /// Number of maps.
    pub fn len(&self) -> usize {
        self.trees.len()
    }

    /// True when there are no maps.
    pub fn is_empty(&self) -> bool {
        self.trees.is_empty()
    }

    /// Checks every map: its kd-tree's invariants, and that every photon lies within the
    /// map's geometry bounds (grown by 1 % of their diagonal for the proxies of analytic
    /// parts), i.e. photons were stored in the map of the surface they hit.
    pub fn validate(&self) -> Result<(), MapError> {
        if self.trees.len() != self.assignment.map_count() as usize || self.geometry.len() != self.trees.len()
        {
            return Err(MapError::Invalid {
                map: self.trees.len() as u32,
                what: format!(
                    "{} trees and {} polygon sets for an assignment of {} maps",
                    self.trees.len(),
                    self.geometry.len(),
                    self.assignment.map_count()
                ),
            });
        }
        for (m, map) in self.iter().enumerate() {
            let m = m as u32;
            map.tree.validate().map_err(|e| MapError::Invalid {
                map: m,
                what: e.to_string(),
            })?;
            if map.tree.is_empty() {
                continue;
            }
            let bounds = map.bounds();
            let grow = Vec3::splat(0.01 * bounds.diagonal() + 1e-4);
            let bounds = Aabb::new(bounds.min - grow, bounds.max + grow);
            for i in 0..map.tree.len() as u32 {
                let p = map.tree.get(i).position();
                if !bounds.contains_point(p) {
                    return Err(MapError::Invalid {
                        map: m,
                        what: format!("photon {i} at {p} outside the map's bounds"),
                    });
                }
            }
        }
        Ok(())
    }

    /// Photon power channels (positive and finite) too small to encode relative to their
    /// map's power scale, so stored as zero, over all maps: more than 2⁴⁰ (about 10¹²) times
    /// smaller than the map's brightest photon channel. Zero in any ordinary scene; see
    /// [`PhotonTree::channels_below_range`].
    pub fn channels_below_range(&self) -> u64 {
        self.trees.iter().map(|t| t.channels_below_range()).sum()
    }

    /// The assignment the maps were built with.
    pub fn assignment(&self) -> &MapAssignment {
        &self.assignment
    }
}
