//! Building a [`HalfEdgeMesh`] from index lists: input checks, welding, dropping degenerate
//! faces, and linking twins through a hash map on each edge's vertex pair.

use super::weld::weld;
use super::{HalfEdgeMesh, MeshOptions, NO_TWIN, NON_MANIFOLD};
use crate::error::MeshError;
use crate::fast_hash::{FastHashMap, fast_map_with_capacity};
use crate::polygon::polygon_vector_area;
use glam::Vec3;
use std::cmp::Ordering::Greater;

/// The half-edges seen on one undirected edge: the first two, and how many in all.
#[derive(Clone, Copy)]
struct EdgeUse {
    first: u32,
    second: u32,
    count: u32,
}

impl HalfEdgeMesh {
    /// Builds the mesh from `positions` and convex planar `faces` given as index lists.
    ///
    /// Steps: every position must be finite and every face must have ≥ 3 in-range indices
    /// (else an error naming the culprit); vertices within `options.weld_tolerance` (at most
    /// [`MeshOptions::MAX_RELATIVE_WELD`] of the mesh's own size) are welded, copies of one
    /// position always into one vertex; in each face, consecutive duplicate vertices are removed; faces left with
    /// fewer than 3 vertices or (near) zero area are dropped and counted
    /// ([`HalfEdgeMesh::dropped_face_count`]); a face in which welding brought two vertices
    /// that are not neighbours together (a pinch) is kept as its simple loops that have area,
    /// several faces with the same [`HalfEdgeMesh::source_face`], so welding moves a face's
    /// outline by at most the weld distance and never removes more of it. Two half-edges on the same vertex pair
    /// with opposite directions become twins; an edge with more than two half-edges, or with
    /// two of the same direction (inconsistent winding), links none and counts as
    /// non-manifold.
    pub fn build<F: AsRef<[u32]>>(
        positions: &[Vec3],
        faces: &[F],
        options: &MeshOptions,
    ) -> Result<Self, MeshError> {
        check_input(positions, faces)?;
        let (welded, remap) = weld(positions, options.tolerance_for(positions));
        let mut mesh = HalfEdgeMesh {
            positions: welded,
            face_starts: vec![0],
            he_origin: Vec::new(),
            he_twin: Vec::new(),
            source_faces: Vec::new(),
            input_face_count: faces.len(),
            dropped_faces: 0,
            boundary_edges: 0,
            non_manifold_edges: 0,
        };
        let mut ring: Vec<u32> = Vec::new();
        let mut polygon: Vec<Vec3> = Vec::new();
        // `seen[v] == stamp` when vertex v already occurs in the face being added.
        let mut seen = vec![0usize; mesh.positions.len()];
        for (source, face) in faces.iter().enumerate() {
            ring.clear();
            for &i in face.as_ref() {
                let v = remap[i as usize];
                if ring.last() != Some(&v) {
                    ring.push(v);
                }
            }
            while ring.len() > 1 && ring.first() == ring.last() {
                ring.pop();
            }
            let stamp = source + 1;
            let repeats = ring
                .iter()
                .any(|&v| std::mem::replace(&mut seen[v as usize], stamp) == stamp);
            if !repeats {
                polygon.clear();
                polygon.extend(ring.iter().map(|&v| mesh.positions[v as usize]));
                match (ring.len() >= 3)
                    .then(|| face_normal_and_area(&polygon))
                    .flatten()
                {
                    Some(_) => mesh.push_face(&ring, source),
                    None => mesh.dropped_faces += 1,
                }
                continue;
            }
            // Welding brought two vertices of the face together that are not neighbours (a
            // sliver corner of a cut piece): the ring is pinched there. Its simple loops are
            // the face, moved by at most the weld distance as its neighbours are; the loops
            // that have no area (the collapsed sliver) or turn against the face are left out.
            polygon.clear();
            polygon.extend(ring.iter().map(|&v| mesh.positions[v as usize]));
            let facing = polygon_vector_area(&polygon);
            let mut kept = false;
            for simple in simple_loops(&ring) {
                polygon.clear();
                polygon.extend(simple.iter().map(|&v| mesh.positions[v as usize]));
                let faces_along = face_normal_and_area(&polygon).is_some_and(|(n, _)| n.dot(facing) > 0.0);
                if simple.len() >= 3 && faces_along {
                    mesh.push_face(&simple, source);
                    kept = true;
                }
            }
            if !kept {
                mesh.dropped_faces += 1;
            }
        }
        mesh.link_twins();
        mesh.shrink_to_fit();
        Ok(mesh)
    }

    fn push_face(&mut self, ring: &[u32], source: usize) {
        self.he_origin.extend_from_slice(ring);
        self.face_starts.push(self.he_origin.len() as u32);
        self.source_faces.push(source as u32);
    }

    /// Drops the spare capacity of the growing tables.
    fn shrink_to_fit(&mut self) {
        self.positions.shrink_to_fit();
        self.face_starts.shrink_to_fit();
        self.he_origin.shrink_to_fit();
        self.source_faces.shrink_to_fit();
    }

    fn link_twins(&mut self) {
        let count = self.he_origin.len();
        self.he_twin = vec![NO_TWIN; count];
        // Each half-edge's vertex pair, made walking the faces: asking each half-edge for its
        // target searches the face starts for its face, which on the kitchen's split cost
        // as much again as the hashing (182 M instructions of the run's 5.95 G).
        let mut keys: Vec<(u32, u32)> = Vec::with_capacity(count);
        for face in self.face_starts.windows(2) {
            let (start, end) = (face[0], face[1]);
            for he in start..end {
                let next = if he + 1 == end { start } else { he + 1 };
                let (a, b) = (self.he_origin[he as usize], self.he_origin[next as usize]);
                keys.push((a.min(b), a.max(b)));
            }
        }
        let mut edges: FastHashMap<(u32, u32), EdgeUse> = fast_map_with_capacity(count);
        for (he, &key) in keys.iter().enumerate() {
            let he = he as u32;
            edges
                .entry(key)
                .and_modify(|e| {
                    if e.count == 1 {
                        e.second = he;
                    }
                    e.count += 1;
                })
                .or_insert(EdgeUse {
                    first: he,
                    second: NO_TWIN,
                    count: 1,
                });
        }
        for edge in edges.values() {
            match edge.count {
                1 => self.boundary_edges += 1,
                2 if self.he_origin[edge.first as usize] != self.he_origin[edge.second as usize] => {
                    self.he_twin[edge.first as usize] = edge.second;
                    self.he_twin[edge.second as usize] = edge.first;
                }
                _ => self.non_manifold_edges += 1,
            }
        }
        if self.non_manifold_edges > 0 {
            for (he, key) in keys.iter().enumerate() {
                let edge = edges[key];
                let twinned = edge.count == 2 && self.he_twin[he] != NO_TWIN;
                if edge.count >= 2 && !twinned {
                    self.he_twin[he] = NON_MANIFOLD;
                }
            }
        }
    }

    /// Origin and target vertex of half-edge `he`.
    pub(super) fn endpoints(&self, he: u32) -> (u32, u32) {
        (
            self.he_origin[he as usize],
            self.he_origin[self.next_index(he) as usize],
        )
    }
}

/// The simple loops of a closed ring of vertex ids in which a vertex may occur more than
/// once: cut off at each repeat (the part between the two occurrences is a loop of its own),
/// in order. Loops of fewer than 3 vertices are included; the caller drops them.
fn simple_loops(ring: &[u32]) -> Vec<Vec<u32>> {
    let mut loops = Vec::new();
    let mut stack: Vec<u32> = Vec::with_capacity(ring.len());
    for &v in ring {
        if let Some(k) = stack.iter().position(|&u| u == v) {
            let mut closed = stack.split_off(k + 1);
            closed.insert(0, v);
            loops.push(closed);
        } else {
            stack.push(v);
        }
    }
    loops.push(stack);
    loops
}

/// The unit normal and area of a face polygon, `None` when its area is zero up to the
/// rounding of the cross products (below `4 ε L²`, `L` its longest edge).
pub(super) fn face_normal_and_area(polygon: &[Vec3]) -> Option<(Vec3, f32)> {
    let vector_area = polygon_vector_area(polygon);
    let area = vector_area.length();
    let longest2 = polygon
        .iter()
        .zip(polygon.iter().cycle().skip(1))
        .map(|(a, b)| a.distance_squared(*b))
        .fold(0.0f32, f32::max);
    if !area.is_finite() || area.partial_cmp(&(4.0 * f32::EPSILON * longest2)) != Some(Greater) {
        return None;
    }
    Some((vector_area.try_normalize()?, area))
}

fn check_input<F: AsRef<[u32]>>(positions: &[Vec3], faces: &[F]) -> Result<(), MeshError> {
    if let Some((vertex, p)) = positions.iter().enumerate().find(|(_, p)| !p.is_finite()) {
        return Err(MeshError::NonFinitePosition {
            vertex,
            position: p.to_array(),
        });
    }
    for (face, indices) in faces.iter().enumerate() {
        let indices = indices.as_ref();
        if indices.len() < 3 {
            return Err(MeshError::TooFewVertices {
                face,
                count: indices.len(),
            });
        }
        if let Some(&index) = indices.iter().find(|&&i| i as usize >= positions.len()) {
            return Err(MeshError::IndexOutOfRange {
                face,
                index,
                vertex_count: positions.len(),
            });
        }
    }
    Ok(())
}
