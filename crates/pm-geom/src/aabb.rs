//! Axis-aligned bounding boxes: the cube of the geometry estimator and the bounds of everything.

use glam::Vec3;

/// An axis-aligned box `[min, max]`. Empty when any `min > max` component.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Aabb {
    /// Smallest corner.
    pub min: Vec3,
    /// Largest corner.
    pub max: Vec3,
}

impl Aabb {
    /// The empty box (`min = +inf`, `max = -inf`); the identity of [`Aabb::union`].
    pub const EMPTY: Aabb = Aabb {
        min: Vec3::INFINITY,
        max: Vec3::NEG_INFINITY,
    };

    /// A box from its corners.
    pub const fn new(min: Vec3, max: Vec3) -> Self {
        Aabb { min, max }
    }

    /// The cube of half-size `half` centred at `center`.
    pub fn cube(center: Vec3, half: f32) -> Self {
        Aabb {
            min: center - Vec3::splat(half),
            max: center + Vec3::splat(half),
        }
    }

    /// The smallest box holding all `points` ([`Aabb::EMPTY`] for none).
    pub fn from_points(points: &[Vec3]) -> Self {
        points.iter().fold(Self::EMPTY, |b, &p| b.grow(p))
    }

    /// This box grown to hold `p`.
    pub fn grow(self, p: Vec3) -> Self {
        Aabb {
            min: self.min.min(p),
            max: self.max.max(p),
        }
    }

    /// The smallest box holding both.
    pub fn union(self, other: Aabb) -> Self {
        Aabb {
            min: self.min.min(other.min),
            max: self.max.max(other.max),
        }
    }

    /// True when the closed boxes share at least one point.
    pub fn overlaps(&self, other: &Aabb) -> bool {
        self.min.cmple(other.max).all() && other.min.cmple(self.max).all()
    }

    /// True when `p` lies in the closed box.
    pub fn contains_point(&self, p: Vec3) -> bool {
        self.min.cmple(p).all() && p.cmple(self.max).all()
    }

    /// True when the box holds no point.
    pub fn is_empty(&self) -> bool {
        self.min.cmpgt(self.max).any()
    }

    /// Centre point.
    pub fn center(&self) -> Vec3 {
        (self.min + self.max) * 0.5
    }

    /// Edge lengths (`max - min`).
    pub fn size(&self) -> Vec3 {
        self.max - self.min
    }

    /// The six faces as quads wound counter-clockwise seen from outside (normals pointing out):
    /// y min, y max, x min, x max, z min, z max.
    pub fn face_quads(&self) -> [[Vec3; 4]; 6] {
        let (lo, hi) = (self.min, self.max);
        let c = |i: u32| {
            Vec3::new(
                if i & 1 != 0 { hi.x } else { lo.x },
                if i & 2 != 0 { hi.y } else { lo.y },
                if i & 4 != 0 { hi.z } else { lo.z },
            )
        };
        [
            [0, 1, 5, 4],
            [2, 6, 7, 3],
            [0, 4, 6, 2],
            [1, 3, 7, 5],
            [0, 2, 3, 1],
            [4, 5, 7, 6],
        ]
        .map(|f| f.map(c))
    }

    /// Length of the diagonal (0 for an empty box).
    pub fn diagonal(&self) -> f32 {
        if self.is_empty() {
            0.0
        } else {
            self.size().length()
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use glam::vec3;

    #[test]
    fn closed_boxes_overlap_when_touching_and_empty_overlaps_nothing() {
        let a = Aabb::new(Vec3::ZERO, Vec3::ONE);
        assert!(a.overlaps(&Aabb::new(Vec3::ONE, Vec3::splat(2.0))));
        assert!(!a.overlaps(&Aabb::new(vec3(1.01, 0., 0.), Vec3::splat(2.0))));
        assert!(!a.overlaps(&Aabb::EMPTY) && !Aabb::EMPTY.overlaps(&a));
        assert!(Aabb::EMPTY.is_empty() && Aabb::EMPTY.diagonal() == 0.0);
        assert!(a.contains_point(Vec3::ONE) && !a.contains_point(Vec3::splat(1.0001)));
    }

    #[test]
    fn cube_and_points_give_expected_extent() {
        let c = Aabb::cube(vec3(1., 2., 3.), 0.5);
        assert_eq!(c.size(), Vec3::ONE);
        assert_eq!(c.center(), vec3(1., 2., 3.));
        assert!((c.diagonal() - 3f32.sqrt()).abs() < 1e-6);
        let b = Aabb::from_points(&[vec3(1., -1., 0.), vec3(-2., 3., 0.5)]);
        assert_eq!(b, Aabb::new(vec3(-2., -1., 0.), vec3(1., 3., 0.5)));
        assert_eq!(Aabb::from_points(&[]), Aabb::EMPTY);
        assert_eq!(b.union(Aabb::EMPTY), b);
    }
}
