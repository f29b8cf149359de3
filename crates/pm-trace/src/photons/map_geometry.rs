//! A photon map's polygons for the geometry-based estimators: the scene's faces of the map's
//! parts, coplanar neighbours merged ([`MapGeometry`]). [`PhotonMaps`](super::PhotonMaps)
//! builds every map's at once; [`MapGeometryOnDemand`] builds each the first time it is asked
//! for, the same polygons bit for bit, for renderers that read only the maps their camera
//! sees.

use crate::error::{MapError, TraceError};
use crate::part::PartId;
use crate::partition::assignment::MapAssignment;
use crate::scene::Scene;
use pm_geom::{Aabb, CoplanarMerger, MergeOptions, PolygonSet};
use std::sync::OnceLock;

/// How a map stores its polygons for the geometry-based estimators.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum MapGeometry {
    /// Coplanar, edge-connected faces merged into larger convex polygons (the same area in
    /// any volume, up to rounding): a gather volume over a finely split wall clips one
    /// polygon, not hundreds.
    #[default]
    Merged,
    /// Every face (and proxy polygon) as it is, one polygon each.
    PerFace,
}

/// One map's polygons and their bounds.
#[derive(Clone, Debug)]
pub(super) struct MapPolygons {
    pub(super) polygons: PolygonSet,
    pub(super) bounds: Aabb,
}

/// The polygons of a map of `parts`, stored as `kind` says.
pub(super) fn map_polygons(scene: &Scene, parts: &[PartId], kind: MapGeometry) -> MapPolygons {
    let mut geometry = PolygonSet::new();
    let bounds = match kind {
        MapGeometry::PerFace => {
            let mut bounds = Aabb::EMPTY;
            for &part in parts {
                scene.for_each_part_polygon(part, |polygon| {
                    if geometry.push(polygon).is_some() {
                        bounds = bounds.union(Aabb::from_points(polygon));
                    }
                });
            }
            bounds
        }
        MapGeometry::Merged => {
            let mut merger = CoplanarMerger::new(MergeOptions::DEFAULT);
            for &part in parts {
                scene.for_each_part_polygon(part, |polygon| {
                    merger.push(polygon);
                });
            }
            merger.merge(|polygon| {
                geometry.push(polygon);
            });
            // The pushed faces' bounds: the merged outlines keep their extreme vertices.
            merger.bounds()
        }
    };
    geometry.build_index();
    MapPolygons {
        polygons: geometry,
        bounds,
    }
}

/// Refuses an assignment made for a scene of another part count.
pub(super) fn check_assignment(scene: &Scene, assignment: &MapAssignment) -> Result<(), MapError> {
    if assignment.part_count() != scene.part_count() {
        return Err(TraceError::AssignmentMismatch {
            assigned: assignment.part_count(),
            parts: scene.part_count(),
        }
        .into());
    }
    Ok(())
}

/// Every map's polygons for an assignment of a scene, each built the first time it is asked
/// for and kept: the same polygons and bounds, bit for bit, as [`PhotonMaps`](super::PhotonMaps)
/// builds for every map at once.
///
/// A renderer reads a map's polygons only where it estimates, and a camera sees few of a
/// finely split scene's maps: of the 16,854 contact maps of a modelled kitchen (57k triangles),
/// a 320×180 view estimates in 1,090, which hold 6,575 of the 51,927 merged polygons. Threads
/// asking for different maps build them at once; one asking for a map another is building
/// waits for it. What is built never depends on which thread asks first.
///
/// ```
/// # use pm_trace::{CreaseAngle, MapGeometry, MapGeometryOnDemand, Partitioner, scenes};
/// let (scene, assignment, _) = CreaseAngle::default()
///     .partition(scenes::build("cornell-box")?)?
///     .into_parts();
/// let geometry = MapGeometryOnDemand::new(&scene, &assignment, MapGeometry::Merged)?;
/// assert_eq!(geometry.built_count(), 0);
/// let polygons = geometry.polygons(0).expect("map 0 exists");
/// assert!(!polygons.is_empty());
/// assert_eq!(geometry.built_count(), 1);
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
#[derive(Debug)]
pub struct MapGeometryOnDemand<'s> {
    scene: &'s Scene,
    parts: Vec<Vec<PartId>>,
    kind: MapGeometry,
    built: Vec<OnceLock<MapPolygons>>,
}

impl<'s> MapGeometryOnDemand<'s> {
    /// Nothing built yet: the maps of `assignment` (made for `scene`), stored as `kind` says.
    /// Refused when the assignment was made for another part count.
    pub fn new(scene: &'s Scene, assignment: &MapAssignment, kind: MapGeometry) -> Result<Self, MapError> {
        check_assignment(scene, assignment)?;
        let parts = assignment.parts_per_map();
        let built = (0..parts.len()).map(|_| OnceLock::new()).collect();
        Ok(MapGeometryOnDemand {
            scene,
            parts,
            kind,
            built,
        })
    }

    /// Map `map`'s polygons, built now if no one asked before; `None` when there is no such
    /// map.
    pub fn polygons(&self, map: u32) -> Option<&PolygonSet> {
        self.get(map).map(|m| &m.polygons)
    }

    /// Bounds of map `map`'s polygons (building them if no one asked before); `None` when
    /// there is no such map.
    pub fn bounds(&self, map: u32) -> Option<Aabb> {
        self.get(map).map(|m| m.bounds)
    }

    fn get(&self, map: u32) -> Option<&MapPolygons> {
        let cell = self.built.get(map as usize)?;
        Some(cell.get_or_init(|| map_polygons(self.scene, &self.parts[map as usize], self.kind)))
    }

    /// Number of maps.
    pub fn len(&self) -> usize {
        self.built.len()
    }

    /// True when the assignment has no maps.
    pub fn is_empty(&self) -> bool {
        self.built.is_empty()
    }

    /// How many maps' polygons have been built so far.
    pub fn built_count(&self) -> usize {
        self.built.iter().filter(|cell| cell.get().is_some()).count()
    }

    /// How the maps store their polygons.
    pub fn kind(&self) -> MapGeometry {
        self.kind
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::partition::{Contact, Partitioner};
    use crate::photons::{PhotonMaps, TraceOptions, trace_photons};
    use crate::scenes;

    /// Polygons built on demand, in any order and on any thread, are those every map of
    /// [`PhotonMaps`] holds, vertex for vertex, with the same bounds; and only the maps asked
    /// about are built.
    #[test]
    fn on_demand_polygons_are_the_photon_maps_polygons() {
        for kind in [MapGeometry::Merged, MapGeometry::PerFace] {
            let scene = scenes::build("solid-rooms-pierce").unwrap();
            let (scene, assignment, _) = Contact::default().partition(scene).unwrap().into_parts();
            let traced = trace_photons(
                &scene,
                &assignment,
                &TraceOptions {
                    photons: 2_000,
                    seed: 1,
                    ..TraceOptions::default()
                },
            )
            .unwrap();
            let maps = PhotonMaps::build_with(&scene, &assignment, traced, kind).unwrap();
            let lazy = MapGeometryOnDemand::new(&scene, &assignment, kind).unwrap();
            assert_eq!(lazy.len(), maps.len());
            assert!(maps.len() > 10, "{} maps", maps.len());
            // Every other map, from the last, on the rayon pool.
            use rayon::prelude::*;
            let asked: Vec<u32> = (0..maps.len() as u32).rev().step_by(2).collect();
            asked.par_iter().for_each(|&m| {
                lazy.polygons(m).unwrap();
            });
            assert_eq!(lazy.built_count(), asked.len());
            for &m in &asked {
                let (eager, built) = (maps.map(m).geometry(), lazy.polygons(m).unwrap());
                assert_eq!(eager.len(), built.len(), "map {m}");
                for i in 0..eager.len() as u32 {
                    assert_eq!(eager.polygon(i), built.polygon(i), "map {m} polygon {i}");
                }
                assert_eq!(maps.map(m).bounds(), lazy.bounds(m).unwrap(), "map {m}");
            }
            assert!(lazy.polygons(maps.len() as u32).is_none());
        }
    }
}
