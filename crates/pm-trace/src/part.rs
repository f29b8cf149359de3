//! The parts of a scene: every mesh face, sphere and ring side is one, identified by a
//! [`PartId`]; photon maps are assigned per part. A mesh part keeps the face the user gave
//! ([`SourceFace`]), also after the contact partition has cut it into pieces.

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

/// A mesh face as the user gave it to [`SceneBuilder`](crate::scene::SceneBuilder): the
/// index of its mesh in the order meshes were added (an
/// [`area_light_quad`](crate::scene::SceneBuilder::area_light_quad) adds one too) and the
/// index of the face in that mesh's face list as given (faces dropped for zero area still
/// count). Per-face data kept beside the scene — a material id, an object id — is found with
/// it. Every part of a mesh has one, and so does every piece the contact partition cuts a
/// face into ([`Partitioned::source_face`](crate::partition::Partitioned::source_face)): the
/// pieces of a face tile it exactly and keep its surface.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub struct SourceFace {
    /// The mesh, in the order meshes were added to the builder.
    pub mesh: u32,
    /// The face, in that mesh's face list.
    pub face: u32,
}
