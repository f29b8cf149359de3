//! A mesh as handed to the [`SceneBuilder`](super::SceneBuilder): its faces stored flat and
//! bounded before anything is copied, and the scene-wide triangle limit.

use super::shading::MeshShading;
use crate::material::Surface;
use glam::Vec3;

// The traversal packs leaf primitive indices into 29 bits; the scene builder's triangle limit
// keeps every scene inside that.
const _: () = assert!(MAX_SCENE_TRIANGLES <= crate::bvh::traverse::MAX_PRIMITIVES);

/// The surfaces of a mesh's faces: one for all, or one per face given.
#[derive(Clone)]
pub(super) enum FaceSurfaces {
    One(Surface),
    PerFace(Vec<Surface>),
}

/// The most triangles (after fan triangulation of every face) a scene may hold: 2²⁷, about
/// 134 million. A built scene holds 80–94 bytes per triangle and building it peaks near
/// 400, so this limit is about 54 GB of building; smaller budgets are the caller's (the glTF
/// loader has `GltfOptions::max_scene_bytes`).
pub const MAX_SCENE_TRIANGLES: usize = 1 << 27;

/// A mesh as given to the builder, its faces' indices stored flat.
///
/// Nothing is copied that [`SceneBuilder::build`] would refuse anyway, so the builder never
/// allocates by a count the caller merely declared: a mesh of more than
/// [`MAX_SCENE_TRIANGLES`] triangles keeps no faces (only their counts), and faces are kept
/// only up to the first one with fewer than 3 vertices (the mesh builder reports it, after
/// the same checks of the faces before it). Faces may be zero-sized values, so their number
/// alone bounds nothing.
#[derive(Clone)]
pub(super) struct MeshInput {
    pub(super) positions: Vec<Vec3>,
    /// The kept faces' vertex indices, one face after another.
    pub(super) indices: Vec<u32>,
    /// Kept face `f` is `indices[starts[f]..starts[f + 1]]`.
    pub(super) starts: Vec<usize>,
    /// Faces given.
    pub(super) face_count: usize,
    /// Triangles of a fan triangulation of every face given (saturating).
    pub(super) triangle_count: usize,
    pub(super) surfaces: FaceSurfaces,
    pub(super) shading: Option<Box<MeshShading>>,
}

impl MeshInput {
    pub(super) fn new<F: AsRef<[u32]>>(positions: &[Vec3], faces: &[F], surfaces: FaceSurfaces) -> Self {
        let (triangle_count, kept) = kept_faces(faces.iter().map(|f| f.as_ref().len()));
        let faces_kept = &faces[..kept];
        let mut starts = Vec::with_capacity(kept + 1);
        starts.push(0);
        let mut indices = Vec::with_capacity(faces_kept.iter().map(|f| f.as_ref().len()).sum());
        for f in faces_kept {
            indices.extend_from_slice(f.as_ref());
            starts.push(indices.len());
        }
        MeshInput {
            positions: positions.to_vec(),
            indices,
            starts,
            face_count: faces.len(),
            triangle_count,
            surfaces,
            shading: None,
        }
    }

    /// A mesh whose faces are already flat (face `f` is `indices[starts[f]..starts[f + 1]]`,
    /// `starts` beginning at 0 and rising to `indices.len()`), taken without a copy, keeping
    /// the faces [`MeshInput::new`] would ([`kept_faces`]).
    pub(super) fn from_flat(
        positions: Vec<Vec3>,
        mut indices: Vec<u32>,
        mut starts: Vec<usize>,
        surfaces: FaceSurfaces,
    ) -> Self {
        debug_assert!(starts.first() == Some(&0) && starts.last() == Some(&indices.len()));
        let face_count = starts.len().saturating_sub(1);
        let (triangle_count, kept) = kept_faces(starts.windows(2).map(|w| w[1] - w[0]));
        starts.truncate(kept + 1);
        if starts.is_empty() {
            starts.push(0);
        }
        indices.truncate(starts[kept.min(starts.len() - 1)]);
        MeshInput {
            positions,
            indices,
            starts,
            face_count,
            triangle_count,
            surfaces,
            shading: None,
        }
    }

    pub(super) fn face_count(&self) -> usize {
        self.face_count
    }

    /// The kept faces as index slices.
    pub(super) fn faces(&self) -> Vec<&[u32]> {
        self.starts
            .windows(2)
            .map(|w| &self.indices[w[0]..w[1]])
            .collect()
    }

    /// Triangles of a fan triangulation of every face given.
    pub(super) fn triangle_count(&self) -> usize {
        self.triangle_count
    }
}

/// The triangles faces of vertex counts `lengths` make, and how many faces a mesh input keeps:
/// none past [`MAX_SCENE_TRIANGLES`] (the scene builder refuses the mesh by its count), else the
/// faces up to and including the first with fewer than 3 vertices (which the mesh build then
/// refuses, naming it). Counted from the lengths alone, so that nothing unbounded is copied
/// before it is checked.
fn kept_faces(lengths: impl Iterator<Item = usize> + Clone) -> (usize, usize) {
    let triangle_count = lengths
        .clone()
        .fold(0usize, |n, length| n.saturating_add(length.saturating_sub(2)));
    if triangle_count > MAX_SCENE_TRIANGLES {
        return (triangle_count, 0);
    }
    let mut kept = 0;
    for length in lengths {
        kept += 1;
        if length < 3 {
            break;
        }
    }
    (triangle_count, kept)
}
