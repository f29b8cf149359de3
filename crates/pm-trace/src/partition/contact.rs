//! Contact-aware partition: the crease-angle partition, made to see faces that meet without
//! sharing an edge — walls standing on or running through floor slabs, duplicated floors, boxes
//! sunk into or resting on others, and gaps narrower than an estimate's reach — so that no
//! photon map spans both sides of such a meeting. Ball & Stejko's future work ("light bleeding
//! would still occur if the floor were one rectangle across both boxes"), taken to solids.

use super::Partitioner;
use super::assignment::MapAssignment;
use super::flood::flood_fill;
use super::partitioned::{PartitionError, Partitioned};
use super::record::{ContactRecord, ContactSeconds};
use crate::error::SceneError;
use crate::material::Surface;
use crate::part::{PartId, PartSource, SourceFace};
use crate::scene::Scene;
use glam::Vec3;
use pm_geom::{
    ArrangementOptions, BarrierSet, FaceId, HalfEdgeMesh, MeshOptions, StepTimer,
    split_polygons_at_intersections,
};

/// Crease-angle maps over all meshes of a scene welded together, after cutting faces where
/// other faces meet them. The render example's default, and the partition to use unless you
/// reproduce the report's crease-angle maps.
///
/// [`Partitioner::partition`] first finds every pair of mesh faces that pierce each other,
/// where an edge of one lies in the other (a wall standing on a floor), that overlap in one
/// plane (duplicated or stacked floors), or that come closer than the gap tolerance without
/// meeting, and cuts each such face into convex pieces along those segments (a near-contact
/// along the outline of the surface that comes close, not along each of its triangles; a slit
/// between a barrier's end and the face's border closed only where it is narrow next to that
/// barrier: see `pm_geom::split_polygons_at_intersections`); the
/// [`Partitioned`] it returns holds that split scene, whose rays still meet the faces as given
/// (a hit on a cut face is located among its pieces for its part; only hidden copies of
/// coincident faces, which the split drops, let a ray pass to the copy kept at the same
/// distance), so the split decides maps and never what a ray meets. Then it flood-fills across edges with a
/// crease angle below `max_angle` over one half-edge mesh of *all* mesh faces, never across a
/// segment where faces meet (or an edge of three or more faces), and never into a piece that
/// lies inside a closed solid (the floor slab's top under a wall box: no light reaches it).
/// Where a cut line runs beyond the meeting (a doorway, the floor around a box) the pieces stay
/// in one map, because light really passes there. Of faces overlapping in one plane and facing
/// the same way only the first is kept. What the split found is [`Partitioned::record`].
///
/// On a scene where no faces meet, the scene is left as it is and the maps are the
/// crease-angle maps, except that faces of different meshes join when they share a flat edge.
/// Analytic parts each get a map of their own, as with [`crate::CreaseAngle`].
///
/// Tolerances scale with the scene's bounding-box diagonal: a point lies on a plane, a line or
/// another point within `relative_tolerance × diagonal` (default `1e-5`: 10 µm in a 1 m room),
/// and faces closer than `relative_gap × diagonal` (default `2e-3`: 2 mm in the 0.55 m Cornell
/// box) count as touching. The gap is what it costs: light that really passes through a slit
/// that narrow reaches the far side's surfaces, but their maps are cut off from the near side,
/// so the estimate there sees only the few photons that came through (measured on a wall 0.1 %
/// of the diagonal short of floor and ceiling: see the repository's `docs/results.md`). In a
/// large scene of small objects (6 cm cubes over a 10 m floor) the default gap is coarse and
/// finds many near-contacts; give such scenes a smaller `relative_gap`.
///
/// **Cost.** The split's work grows with the pairs of faces whose bounds touch, not with the
/// meetings it finds. On an exported interior (the obvhs crate's kitchen: 56,939 triangles,
/// every vertex repeated per face) it takes 0.47–0.52 s on two threads with `relative_gap:
/// 1e-4` (28,086 meetings among 1.2 million candidate pairs) and 1.1–1.4 s with the default
/// (76,822 among 7.4 million). [`crate::CreaseAngle`] takes 7–9 ms there, and loading the
/// scene 59–70 ms (the repository's `benches/kitchen.rs`). The split uses about 1.65 of two
/// cores, where photon tracing uses 1.9, so it weighs more in wall time than in CPU time.
/// These times come from a shared two-core machine whose speed changed by up to 2× from day
/// to day; compare builds only when they are measured alternately in one run.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Contact {
    /// Largest crease angle (between face normals, 0 = flat) that still joins, radians.
    pub max_angle: f32,
    /// Contact and welding tolerance as a fraction of the scene's bounding-box diagonal.
    pub relative_tolerance: f32,
    /// Widest gap between faces that still counts as touching, as a fraction of the scene's
    /// bounding-box diagonal (at least the tolerance).
    pub relative_gap: f32,
}

impl Default for Contact {
    /// 30°, a tolerance of `1e-5` and a gap of `2e-3` of the diagonal.
    fn default() -> Self {
        Contact {
            max_angle: 30f32.to_radians(),
            relative_tolerance: 1e-5,
            relative_gap: 2e-3,
        }
    }
}

impl Contact {
    /// The absolute tolerance (metres) for `scene`.
    pub fn tolerance(&self, scene: &Scene) -> f32 {
        (self.relative_tolerance * scene.bounds().diagonal()).max(f32::MIN_POSITIVE)
    }

    /// The absolute gap (metres) for `scene`: faces closer than this count as touching.
    pub fn gap(&self, scene: &Scene) -> f32 {
        (self.relative_gap * scene.bounds().diagonal()).max(self.tolerance(scene))
    }

    /// `scene` rebuilt with every mesh face cut where other faces meet it, its ray queries
    /// searching the faces as given (`Scene::trace_faces_as_given`), and what was found. Each piece keeps its
    /// face's surface and its vertex attributes (texture coordinates, colours and normals,
    /// interpolated over the original triangle, so [`Scene::albedo_at`] and
    /// [`Scene::shading_normal_at`] give what they gave before the split); lights, analytic
    /// shapes and the camera are unchanged, and so is the total area of every face except the
    /// hidden copies of duplicated faces. A scene where no faces meet (and none lies inside a solid) comes back unchanged.
    ///
    /// The split runs on the caller's rayon pool and gives the same scene on any number of
    /// threads.
    ///
    /// Fails with [`SceneError::Arrangement`] when the faces meet in more places than the
    /// bounds of [`ArrangementOptions`] allow (for example a thousand overlapping copies of a
    /// mesh), before allocating past them.
    fn split(&self, scene: Scene) -> Result<(Scene, ContactRecord), SceneError> {
        let mut timer = StepTimer::start();
        let mut phases = ContactSeconds::default();
        let tolerance = self.tolerance(&scene);
        let options = ArrangementOptions::new(tolerance, self.gap(&scene));
        let faces = mesh_faces(&scene);
        phases.faces = timer.lap();
        let mut split = split_polygons_at_intersections(&faces.polygons, &faces.solids, &options)?;
        timer.lap();
        phases.arrangement = split.seconds;
        let counts = split.counts;
        if counts.meetings() == 0 && counts.duplicate_pieces == 0 && counts.sealed_pieces == 0 {
            let record = ContactRecord {
                source_faces: (0..scene.part_count() as u32)
                    .map(|p| scene.source_face(PartId(p)))
                    .collect(),
                seconds: phases.faces + phases.arrangement.total(),
                phases,
                ..ContactRecord::default()
            };
            return Ok((scene, record));
        }

        // One rebuilt mesh per original mesh, holding that mesh's pieces.
        let mesh_count = scene.meshes().len();
        // Each mesh's vectors are sized exactly first (doubling growth would leave up to half
        // of them unused at the split's peak).
        let mut sizes = vec![(0usize, 0usize); mesh_count];
        for (piece, &source) in split.polygons.iter().zip(&split.source) {
            let size = &mut sizes[faces.mesh_of[source]];
            *size = (size.0 + piece.len(), size.1 + 1);
        }
        fn with_pieces<T>(sizes: &[(usize, usize)], extra: usize) -> Vec<Vec<T>> {
            sizes.iter().map(|s| Vec::with_capacity(s.1 + extra)).collect()
        }
        let mut positions: Vec<Vec<Vec3>> = sizes.iter().map(|s| Vec::with_capacity(s.0)).collect();
        let mut starts: Vec<Vec<usize>> = with_pieces(&sizes, 1);
        for s in &mut starts {
            s.push(0);
        }
        let mut face_surfaces: Vec<Vec<Surface>> = with_pieces(&sizes, 0);
        let mut piece_faces: Vec<Vec<FaceId>> = with_pieces(&sizes, 0);
        let mut piece_index: Vec<Vec<usize>> = with_pieces(&sizes, 0);
        let mut piece_sources: Vec<Vec<SourceFace>> = with_pieces(&sizes, 0);
        // Each piece is freed once copied, so the pieces are not held twice.
        let pieces = std::mem::take(&mut split.polygons);
        for (index, (piece, &source)) in pieces.into_iter().zip(&split.source).enumerate() {
            let m = faces.mesh_of[source];
            positions[m].extend_from_slice(&piece);
            starts[m].push(positions[m].len());
            face_surfaces[m].push(*scene.part_surface(faces.parts[source]));
            piece_faces[m].push(faces.face_of[source]);
            piece_index[m].push(index);
            piece_sources[m].push(SourceFace {
                mesh: m as u32,
                face: faces.user_face[source],
            });
        }
        // Rays will meet the faces as given: their triangles and faces, before the scene goes.
        let original = scene.mesh_triangle_sources();
        let loaded_rays = scene.ray_search();
        // Vertex attributes (texture coordinates, colours, normals) carry over: each piece is
        // shaded by interpolating over the whole original triangle it lies in.
        let shading: Vec<_> = scene
            .meshes()
            .iter()
            .zip(&piece_faces)
            .map(|(mesh, pieces)| mesh.shading_for_pieces(pieces))
            .collect();
        let weld = MeshOptions {
            weld_tolerance: tolerance,
        };
        let mut builder = scene
            .into_builder_without_meshes()
            .mesh_options(weld)
            .defer_ray_triangles();
        drop(piece_faces);
        let mut built_meshes = Vec::new();
        let meshes = positions.into_iter().zip(starts).zip(face_surfaces).zip(shading);
        for (m, (((positions, starts), surfaces), shading)) in meshes.enumerate() {
            if !surfaces.is_empty() {
                // The builder takes the pieces over: they are held once while it builds.
                builder = builder.mesh_of_listed_polygons(positions, starts, surfaces, shading);
                built_meshes.push(m);
            }
        }
        let mut rebuilt = builder.build()?;
        drop(faces);
        let mut sealed_parts = vec![false; rebuilt.part_count()];
        let mut source_faces = vec![None; rebuilt.part_count()];
        for (mesh, &m) in rebuilt.meshes().iter().zip(&built_meshes) {
            for face in mesh.half_edge_mesh().faces() {
                let k = mesh.half_edge_mesh().source_face(face);
                let part = mesh.part_of_face(face).0 as usize;
                sealed_parts[part] = split.sealed[piece_index[m][k]];
                source_faces[part] = Some(piece_sources[m][k]);
            }
        }
        let barriers = BarrierSet::new(split.barriers, tolerance);
        drop((piece_index, piece_sources));
        phases.rebuild = timer.lap();
        rebuilt.trace_faces_as_given(&original, &source_faces, tolerance, loaded_rays);
        phases.faces_as_given = timer.lap();
        let record = ContactRecord {
            barriers,
            sealed_parts,
            source_faces,
            counts,
            seconds: phases.total(),
            phases,
        };
        Ok((rebuilt, record))
    }
}

impl Contact {
    /// Whether the faces on the two sides of `he` may share a map: a crease below `max_angle`
    /// and no segment where faces meet along the edge.
    fn joins(&self, mesh: &HalfEdgeMesh, he: pm_geom::HalfEdgeId, barriers: &BarrierSet) -> bool {
        let positions = mesh.positions();
        mesh.crease_angle(he).is_some_and(|a| a < self.max_angle)
            && !barriers.covers_edge(
                positions[mesh.origin(he).0 as usize],
                positions[mesh.target(he).0 as usize],
            )
    }
}

impl Partitioner for Contact {
    /// Splits the scene where its faces meet, then assigns the maps of the split scene.
    fn partition(&self, scene: Scene) -> Result<Partitioned, PartitionError> {
        let (scene, mut record) = self.split(scene)?;
        // The fill is part of the partition's time, as the crease-angle partition's is all fill.
        let mut timer = StepTimer::start();
        let assignment = self.assign(&scene, &record);
        record.phases.fill = timer.lap();
        record.seconds += record.phases.fill;
        Ok(Partitioned::with_record(scene, assignment, record))
    }
}

impl Contact {
    /// The maps of a split scene: within each mesh, the shared flood fill (as the crease-angle
    /// maps) that never crosses a segment where faces meet nor enters a sealed piece; then the
    /// fills of different meshes joined across flat edges they share. Maps are numbered in
    /// order of each group's first part, as the crease-angle maps are; every analytic part is
    /// a map of its own.
    fn assign(&self, scene: &Scene, record: &ContactRecord) -> MapAssignment {
        let barriers = record.barriers();
        let sealed = |part: PartId| record.is_sealed(part);
        // The fill and the welding of the faces with an open edge need only the scene: the
        // weld (one sequential step, 0.07–0.09 s of a 0.5–0.7 s split on a modelled interior
        // whose meshes share no vertex) runs beside the fill's meshes.
        let (fill, open) = rayon::join(
            || {
                flood_fill(scene, |mesh, he, part, other| {
                    !sealed(part) && !sealed(other) && self.joins(mesh, he, barriers)
                })
            },
            || OpenFaces::welded(scene, self.tolerance(scene)),
        );
        let mut groups = UnionFind::new(scene.part_count());
        if let Some(open) = open {
            self.join_across_meshes(&open, &fill, &sealed, barriers, &mut groups);
        }
        let roots: Vec<u32> = fill.iter().map(|&f| groups.find(f)).collect();
        MapAssignment::from_roots(&roots)
    }

    /// Joins the fills of different meshes: the faces with an open edge, welded together
    /// (`open`), join across flat edges they share (unless sealed or across a barrier).
    fn join_across_meshes(
        &self,
        open: &OpenFaces,
        fill: &[u32],
        sealed: &impl Fn(PartId) -> bool,
        barriers: &BarrierSet,
        groups: &mut UnionFind,
    ) {
        let welded = &open.mesh;
        for face in welded.faces() {
            let part = open.parts[welded.source_face(face)];
            for (he, other) in welded.neighbours(face) {
                let other_part = open.parts[welded.source_face(other)];
                if !sealed(part) && !sealed(other_part) && self.joins(welded, he, barriers) {
                    groups.union(fill[part.0 as usize], fill[other_part.0 as usize]);
                }
            }
        }
    }
}

/// The mesh faces of a scene that have an open edge (a half-edge with no twin in its own
/// mesh), welded into one mesh, where faces of different meshes that share an edge become
/// neighbours; with each welded face's part.
struct OpenFaces {
    mesh: HalfEdgeMesh,
    parts: Vec<PartId>,
}

impl OpenFaces {
    /// `None` when no face has an open edge.
    fn welded(scene: &Scene, tolerance: f32) -> Option<Self> {
        let mut positions = Vec::new();
        let mut polygons = Vec::new();
        let mut parts = Vec::new();
        for m in scene.meshes() {
            let mesh = m.half_edge_mesh();
            for face in mesh.faces() {
                if mesh.face_half_edges(face).all(|he| mesh.twin(he).is_some()) {
                    continue;
                }
                let start = positions.len() as u32;
                positions.extend(mesh.face_polygon(face));
                polygons.push((start..positions.len() as u32).collect::<Vec<u32>>());
                parts.push(m.part_of_face(face));
            }
        }
        if polygons.is_empty() {
            return None;
        }
        let options = MeshOptions {
            weld_tolerance: tolerance,
        };
        // The faces were welded once already, so welding them again cannot fail; if it ever did,
        // meshes would only not join each other.
        let mesh = HalfEdgeMesh::build(&positions, &polygons, &options).ok()?;
        Some(OpenFaces { mesh, parts })
    }
}

/// Disjoint sets of parts, with path halving.
struct UnionFind(Vec<u32>);

impl UnionFind {
    fn new(n: usize) -> Self {
        UnionFind((0..n as u32).collect())
    }

    fn find(&mut self, mut i: u32) -> u32 {
        while self.0[i as usize] != i {
            let parent = self.0[i as usize];
            self.0[i as usize] = self.0[parent as usize];
            i = parent;
        }
        i
    }

    fn union(&mut self, a: u32, b: u32) {
        let (a, b) = (self.find(a), self.find(b));
        // The smaller root wins, so a group's root is its first part.
        match a.cmp(&b) {
            std::cmp::Ordering::Less => self.0[b as usize] = a,
            std::cmp::Ordering::Greater => self.0[a as usize] = b,
            std::cmp::Ordering::Equal => {}
        }
    }
}

/// Every mesh face of a scene as a polygon, in part order, with what the split needs of it.
struct MeshFaces {
    polygons: Vec<Vec<Vec3>>,
    /// The face's part (its surface is the scene's, looked up when a piece needs it).
    parts: Vec<PartId>,
    mesh_of: Vec<usize>,
    face_of: Vec<FaceId>,
    /// The face's index in its mesh's face list as the user gave it.
    user_face: Vec<u32>,
    /// The mesh's index when the mesh is a closed solid (every edge shared by two faces).
    solids: Vec<Option<u32>>,
}

fn mesh_faces(scene: &Scene) -> MeshFaces {
    // Sized once: the tables are as long as the scene's faces, and doubling growth would hold
    // up to twice that through the split.
    let count: usize = scene
        .meshes()
        .iter()
        .map(|m| m.half_edge_mesh().face_count())
        .sum();
    let mut out = MeshFaces {
        polygons: Vec::with_capacity(count),
        parts: Vec::with_capacity(count),
        mesh_of: Vec::with_capacity(count),
        face_of: Vec::with_capacity(count),
        user_face: Vec::with_capacity(count),
        solids: Vec::with_capacity(count),
    };
    for (m, mesh) in scene.meshes().iter().enumerate() {
        let half_edges = mesh.half_edge_mesh();
        let closed = half_edges.boundary_edge_count() == 0 && half_edges.non_manifold_edge_count() == 0;
        for face in half_edges.faces() {
            out.polygons.push(half_edges.face_polygon(face).collect());
            out.parts.push(mesh.part_of_face(face));
            out.mesh_of.push(m);
            out.face_of.push(face);
            out.user_face.push(half_edges.source_face(face) as u32);
            out.solids.push(closed.then_some(m as u32));
        }
    }
    debug_assert!(
        (0..scene.part_count() as u32)
            .filter(|&p| matches!(scene.part_source(PartId(p)), PartSource::MeshFace { .. }))
            .count()
            == out.polygons.len()
    );
    out
}
