//! The parts of a scene: every mesh face, sphere and ring side is one, identified by a
//! [`PartId`]; photon maps are assigned per part.

use crate::shape::ring::RingSide;
use pm_geom::FaceId;

/// Identifies one part of the scene: a mesh face, a sphere, or one side of a ring. Photon
/// maps are assigned per part.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub struct PartId(pub u32);

/// What a part is made of.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum PartSource {
    /// Face `face` of mesh `mesh` (indices into [`Scene::meshes`](crate::scene::Scene::meshes)).
    MeshFace {
        /// Mesh index.
        mesh: u32,
        /// Face of that mesh.
        face: FaceId,
    },
    /// A sphere (index into [`Scene::shapes`](crate::scene::Scene::shapes)).
    Sphere {
        /// Shape index.
        shape: u32,
    },
    /// One side of a ring (index into [`Scene::shapes`](crate::scene::Scene::shapes)).
    Ring {
        /// Shape index.
        shape: u32,
        /// Which side.
        side: RingSide,
    },
}

/// A primitive's part and the index of its part's surface.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) struct PartSurface {
    pub(crate) part: PartId,
    pub(crate) surface: u32,
}
