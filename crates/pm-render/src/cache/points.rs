//! One photon map's irradiance points: where irradiance was precomputed, the surface normal
//! there and the irradiance, in full precision, with a kd-tree over their positions.

use crate::error::RenderError;
use glam::Vec3;
use pm_kdtree::{Euclidean, KindMask, Neighbours, Photon, PhotonKind, PhotonTree};

/// Candidates examined per lookup for one whose normal agrees with the query's: the nearest
/// this many points within the lookup distance.
pub const CANDIDATES: usize = 8;

/// The smallest cosine between a cache point's normal and the query's for the point to answer
/// (about 25°): the nearest point on the other side of a thin sheet, or across a sharp fold of
/// one map's surface, is passed over.
pub const NORMAL_AGREEMENT: f32 = 0.9;

/// An irradiance estimate at a surface point.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct IrradiancePoint {
    /// Where (metres).
    pub position: Vec3,
    /// The unit geometric normal of the surface there, on the side the light arrived from.
    pub normal: Vec3,
    /// The irradiance (W/m² per channel).
    pub irradiance: Vec3,
}

/// One map's irradiance points, looked up by position.
///
/// The positions are kept in a [`PhotonTree`] used as a spatial index only (its entries carry
/// no power); the normals and irradiances are `f32` fields in the tree's order. The tree
/// reorders what it is given, so the fields are matched to its slots by position (the tree
/// keeps positions exactly), ties broken by input order: points at one position are
/// interchangeable answers to a query there.
#[derive(Clone, Debug, Default)]
pub struct IrradiancePoints {
    index: PhotonTree,
    normals: Vec<Vec3>,
    irradiance: Vec<Vec3>,
}

impl IrradiancePoints {
    /// The points, indexed. Non-finite or out-of-range positions are refused (by the tree).
    pub fn new(points: Vec<IrradiancePoint>) -> Result<Self, RenderError> {
        let located: Vec<Photon> = points
            .iter()
            .map(|p| Photon {
                position: p.position,
                power: Vec3::ZERO,
                direction: Vec3::Z,
                kind: PhotonKind::Direct,
            })
            .collect();
        let index = PhotonTree::build(located).map_err(|e| RenderError::BadFinalGather(e.to_string()))?;
        let key = |p: Vec3| p.to_array().map(f32::to_bits);
        let mut given: Vec<usize> = (0..points.len()).collect();
        given.sort_by_key(|&i| (key(points[i].position), i));
        let mut slots: Vec<u32> = (0..index.len() as u32).collect();
        slots.sort_by_key(|&s| (key(index.position(s)), s));
        let mut normals = vec![Vec3::ZERO; points.len()];
        let mut irradiance = vec![Vec3::ZERO; points.len()];
        for (&i, &slot) in given.iter().zip(&slots) {
            normals[slot as usize] = points[i].normal;
            irradiance[slot as usize] = points[i].irradiance;
        }
        Ok(IrradiancePoints {
            index,
            normals,
            irradiance,
        })
    }

    /// The points as they are held: the index (positions in its order) and the normals and
    /// irradiances in the index's order. With [`IrradiancePoints::from_indexed`] they give
    /// these points back, bit for bit.
    pub fn indexed(&self) -> (&PhotonTree, &[Vec3], &[Vec3]) {
        (&self.index, &self.normals, &self.irradiance)
    }

    /// Points as [`IrradiancePoints::indexed`] gave them: `index` a tree over their positions,
    /// `normals` and `irradiance` in its order. Refused (naming the point): lengths that
    /// differ, a normal that is not finite (irradiances are kept as they are).
    pub fn from_indexed(
        index: PhotonTree,
        normals: Vec<Vec3>,
        irradiance: Vec<Vec3>,
    ) -> Result<Self, RenderError> {
        let bad = |what: String| Err(RenderError::BadFinalGather(format!("irradiance points: {what}")));
        if normals.len() != index.len() || irradiance.len() != index.len() {
            return bad(format!(
                "{} positions, {} normals, {} irradiances",
                index.len(),
                normals.len(),
                irradiance.len()
            ));
        }
        if let Some(i) = normals.iter().position(|n| !n.is_finite()) {
            return bad(format!("point {i} has a normal that is not finite"));
        }
        Ok(IrradiancePoints {
            index,
            normals,
            irradiance,
        })
    }

    /// Number of points.
    pub fn len(&self) -> usize {
        self.index.len()
    }

    /// True when there are none.
    pub fn is_empty(&self) -> bool {
        self.index.is_empty()
    }

    /// Every point, in the index's order.
    pub fn iter(&self) -> impl ExactSizeIterator<Item = IrradiancePoint> + '_ {
        (0..self.len() as u32).map(|slot| self.point(slot))
    }

    fn point(&self, slot: u32) -> IrradiancePoint {
        IrradiancePoint {
            position: self.index.position(slot),
            normal: self.normals[slot as usize],
            irradiance: self.irradiance[slot as usize],
        }
    }

    /// The irradiance of the nearest point within `radius` of `position` whose normal agrees
    /// with `normal` (cosine at least [`NORMAL_AGREEMENT`]), or `None`. Allocation-free once
    /// `neighbours` is warm.
    pub fn nearest_agreeing(
        &self,
        position: Vec3,
        normal: Vec3,
        radius: f32,
        neighbours: &mut Neighbours,
    ) -> Option<Vec3> {
        self.nearest_agreeing_point(position, normal, radius, neighbours)
            .map(|p| p.irradiance)
    }

    /// The point [`IrradiancePoints::nearest_agreeing`] answers with: the nearest within
    /// `radius` of `position`, or when its normal does not agree with `normal` the nearest
    /// that agrees among the [`CANDIDATES`] nearest; `None` when none of them agrees (a
    /// position that is not finite finds none). Allocation-free once `neighbours` is warm.
    pub fn nearest_agreeing_point(
        &self,
        position: Vec3,
        normal: Vec3,
        radius: f32,
        neighbours: &mut Neighbours,
    ) -> Option<IrradiancePoint> {
        if self.index.is_empty() {
            return None;
        }
        let agrees = |slot: u32| self.normals[slot as usize].dot(normal) >= NORMAL_AGREEMENT;
        // The nearest point first (almost always the answer), then more candidates.
        self.index
            .nearest_k::<Euclidean>(position, 1, radius, KindMask::ALL, neighbours);
        match neighbours.as_slice().first().map(|n| n.index) {
            None => return None,
            Some(slot) if agrees(slot) => return Some(self.point(slot)),
            Some(_) => {}
        }
        self.index
            .nearest_k::<Euclidean>(position, CANDIDATES, radius, KindMask::ALL, neighbours);
        neighbours.sort_by_distance();
        neighbours
            .as_slice()
            .iter()
            .map(|n| n.index)
            .find(|&slot| agrees(slot))
            .map(|slot| self.point(slot))
    }

    /// Bytes held: the index's and the two fields'.
    pub fn memory_bytes(&self) -> usize {
        self.index.memory_bytes() + (self.normals.capacity() + self.irradiance.capacity()) * size_of::<Vec3>()
    }
}
