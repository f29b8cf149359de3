//! Where an estimate is taken (a surface point and the side it is seen from) and the photon
//! map it reads (photons and polygons).

use glam::Vec3;
use pm_geom::PolygonSet;
use pm_kdtree::PhotonTree;

/// A point on a surface seen by the camera: where to estimate, and the side it is seen from.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SurfacePoint {
    /// Position (metres).
    pub position: Vec3,
    /// Unit geometric normal on the viewed side.
    pub normal: Vec3,
    /// True when the viewed side is the side the surface's own (polygon) normal points to.
    /// When false — a closed surface seen from inside its outward normals, such as a sphere —
    /// the geometry estimators flip the map's polygon normals so that they face its photons.
    pub front_face: bool,
}

impl SurfacePoint {
    /// A point seen from the side its polygons' normals point to.
    pub const fn front(position: Vec3, normal: Vec3) -> Self {
        SurfacePoint {
            position,
            normal,
            front_face: true,
        }
    }
}

/// One photon map as the estimators see it: its photons and the area geometry of its surfaces.
#[derive(Clone, Copy, Debug)]
pub struct MapView<'a> {
    /// The map's photons.
    pub tree: &'a PhotonTree,
    /// The map's polygons (with their overlap index built), used by the geometry estimators.
    pub polygons: &'a PolygonSet,
}

impl SurfacePoint {
    /// True when a photon travelling along `direction` arrives from behind the viewed side
    /// (`direction · normal ≥ 0`): it lit the other side of the surface. `direction` may have
    /// any positive length.
    #[inline]
    pub fn arrives_from_behind(&self, direction: Vec3) -> bool {
        direction.dot(self.normal) >= 0.0
    }
}
