//! A photon map's polygons for the geometry-based estimators: the scene's faces of the map's
//! parts, coplanar neighbours merged ([`MapGeometry`]), built the first time the map is read.
//!
//! A renderer reads a map's polygons only where it estimates, and a camera sees few of a
//! finely split scene's maps: of the 16,854 contact maps of a modelled kitchen (57k triangles),
//! a 320×180 view estimates in 1,090, which hold 6,575 of the 51,927 merged polygons. So the
//! maps copy their faces from the scene once (a copy of the scene's face corners, without the
//! merging and the overlap index) and merge and index a map's when it is first read.

use crate::error::{MapError, TraceError};
use crate::partition::assignment::MapAssignment;
use crate::scene::Scene;
use glam::Vec3;
use pm_geom::{Aabb, CoplanarMerger, MergeOptions, PolygonSet, polygon_vector_area};
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

/// Every map's faces as the scene gives them (analytic parts as their proxy polygons), in one
/// vertex table, and each map's [`MapPolygons`] built from them the first time it is read.
/// Threads reading different maps build them at once; one reading a map another is building
/// waits for it. What is built never depends on which thread reads first.
#[derive(Clone, Debug)]
pub(super) struct MapPolygonTable {
    kind: MapGeometry,
    vertices: Vec<Vec3>,
    /// Where each face ends in `vertices` (it starts where the one before ends).
    face_ends: Vec<usize>,
    /// Map `m`'s faces are `face_ends[map_first[m]..map_first[m + 1]]`.
    map_first: Vec<usize>,
    built: Vec<OnceLock<MapPolygons>>,
}

impl MapPolygonTable {
    /// The faces of each map of `assignment` (made for `scene`: the caller checks), copied
    /// in the order the scene gives them, part by part, nothing built yet.
    pub(super) fn new(scene: &Scene, assignment: &MapAssignment, kind: MapGeometry) -> Self {
        let parts = assignment.parts_per_map();
        let (mut vertices, mut face_ends) = (Vec::new(), Vec::new());
        let mut map_first = Vec::with_capacity(parts.len() + 1);
        for parts in &parts {
            map_first.push(face_ends.len());
            for &part in parts {
                scene.for_each_part_polygon(part, |polygon| {
                    vertices.extend_from_slice(polygon);
                    face_ends.push(vertices.len());
                });
            }
        }
        map_first.push(face_ends.len());
        vertices.shrink_to_fit();
        face_ends.shrink_to_fit();
        let built = (0..parts.len()).map(|_| OnceLock::new()).collect();
        MapPolygonTable {
            kind,
            vertices,
            face_ends,
            map_first,
            built,
        }
    }

    /// How the maps store their polygons.
    pub(super) fn kind(&self) -> MapGeometry {
        self.kind
    }

    /// Number of maps.
    pub(super) fn len(&self) -> usize {
        self.built.len()
    }

    /// Map `map`'s faces as the scene gave them.
    fn faces(&self, map: usize) -> impl Iterator<Item = &[Vec3]> + '_ {
        let faces = self.map_first[map]..self.map_first[map + 1];
        faces.map(|f| {
            let start = if f == 0 { 0 } else { self.face_ends[f - 1] };
            &self.vertices[start..self.face_ends[f]]
        })
    }

    /// Map `map`'s polygons, built now if no one read them before. Panics when `map` is not
    /// below [`MapPolygonTable::len`], like slice indexing.
    pub(super) fn get(&self, map: usize) -> &MapPolygons {
        // The build runs on the calling thread and never enters the thread pool, so a rayon
        // worker waiting here cannot be asked to build the same map again (a re-entrant
        // initialisation, which would deadlock).
        self.built[map].get_or_init(|| self.build(map))
    }

    /// How many maps' polygons have been built so far.
    pub(super) fn built_count(&self) -> usize {
        self.built.iter().filter(|cell| cell.get().is_some()).count()
    }

    /// The area of map `map`'s faces (square metres; the area of its polygons up to rounding,
    /// without building them).
    pub(super) fn face_area(&self, map: usize) -> f64 {
        self.faces(map)
            .map(|face| f64::from(polygon_vector_area(face).length()))
            .filter(|a| a.is_finite())
            .sum()
    }

    /// The polygons of map `map`, stored as the table's kind says.
    fn build(&self, map: usize) -> MapPolygons {
        let mut geometry = PolygonSet::new();
        let bounds = match self.kind {
            MapGeometry::PerFace => {
                let mut bounds = Aabb::EMPTY;
                for face in self.faces(map) {
                    if geometry.push(face).is_some() {
                        bounds = bounds.union(Aabb::from_points(face));
                    }
                }
                bounds
            }
            MapGeometry::Merged => {
                let mut merger = CoplanarMerger::new(MergeOptions::DEFAULT);
                for face in self.faces(map) {
                    merger.push(face);
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

#[cfg(test)]
mod tests {
    use super::*;
    use crate::partition::{Contact, Partitioner};
    use crate::photons::{PhotonMaps, TraceOptions, trace_photons};
    use crate::scenes;
    use rayon::prelude::*;

    /// A map's polygons are the same bits whether read first in map order on one thread or
    /// in reverse on the rayon pool; only the maps read are built; per face they are the
    /// scene's faces of the map's parts, and merged they cover the faces' area.
    #[test]
    fn polygons_built_on_first_read_do_not_depend_on_the_order() {
        let scene = scenes::build("solid-rooms-pierce").unwrap();
        let (scene, assignment, _) = Contact::default().partition(scene).unwrap().into_parts();
        let options = TraceOptions {
            photons: 2_000,
            seed: 1,
            ..TraceOptions::default()
        };
        for kind in [MapGeometry::Merged, MapGeometry::PerFace] {
            let maps = || {
                let traced = trace_photons(&scene, &assignment, &options).unwrap();
                PhotonMaps::build_with(&scene, &assignment, traced, kind).unwrap()
            };
            let (in_order, reversed) = (maps(), maps());
            assert!(in_order.len() > 10, "{} maps", in_order.len());
            assert_eq!((in_order.maps_read(), reversed.maps_read()), (0, 0));
            let asked: Vec<u32> = (0..in_order.len() as u32).rev().step_by(2).collect();
            asked.par_iter().for_each(|&m| {
                reversed.map(m).geometry();
            });
            assert_eq!(reversed.maps_read(), asked.len());
            for &m in asked.iter().rev() {
                let (a, b) = (in_order.map(m).geometry(), reversed.map(m).geometry());
                assert_eq!(a.len(), b.len(), "map {m}");
                for i in 0..a.len() as u32 {
                    assert_eq!(a.polygon(i), b.polygon(i), "map {m} polygon {i}");
                }
                assert_eq!(in_order.map(m).bounds(), reversed.map(m).bounds(), "map {m}");
                let area: f64 = (0..a.len() as u32).map(|i| f64::from(a.area(i))).sum();
                let faces = in_order.face_area(m).unwrap();
                assert!((area - faces).abs() <= 1e-5 * faces, "map {m}: {area} vs {faces}");
                if kind == MapGeometry::PerFace {
                    let mut expected = Vec::new();
                    for &part in &assignment.parts_per_map()[m as usize] {
                        scene.for_each_part_polygon(part, |p| expected.push(p.to_vec()));
                    }
                    let got: Vec<Vec<Vec3>> = (0..a.len() as u32).map(|i| a.polygon(i).to_vec()).collect();
                    assert_eq!(got, expected, "map {m}");
                }
            }
            assert_eq!(reversed.maps_read(), asked.len(), "reading again builds nothing");
            assert_eq!(in_order.face_area(in_order.len() as u32), None);
        }
    }
}
