//! The ring (a thick washer): two annuli and two cylinders, each a separate part, with exact
//! ray intersection and a polygonal proxy per part.

use glam::Vec3;
use pm_geom::Aabb;
use std::f32::consts::PI;

/// One of the four parts of a [`Ring`].
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum RingSide {
    /// The annulus at `height` along the axis; normal `+axis`.
    Top,
    /// The annulus at the base; normal `−axis`.
    Bottom,
    /// The inner cylinder; normal towards the axis.
    Inner,
    /// The outer cylinder; normal away from the axis.
    Outer,
}

impl RingSide {
    /// The four sides in part order.
    pub const ALL: [RingSide; 4] = [RingSide::Top, RingSide::Bottom, RingSide::Inner, RingSide::Outer];
}

/// A thick washer standing on `center` (the centre of its bottom annulus), extending `height`
/// along the unit `axis`, with radii `inner_radius < outer_radius`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Ring {
    /// Centre of the bottom annulus.
    pub center: Vec3,
    /// Unit axis (from bottom to top).
    pub axis: Vec3,
    /// Radius of the hole.
    pub inner_radius: f32,
    /// Outer radius.
    pub outer_radius: f32,
    /// Thickness along the axis.
    pub height: f32,
}

impl Ring {
    /// Bounds of one side.
    pub fn side_bounds(&self, side: RingSide) -> Aabb {
        // A disc of radius r with normal a spans r·sqrt(1 − a_i²) along axis i.
        let a = self.axis;
        let spread = (Vec3::ONE - a * a).max(Vec3::ZERO).map(f32::sqrt);
        let disc = |c: Vec3, r: f32| Aabb::new(c - spread * r, c + spread * r);
        let top = self.center + a * self.height;
        match side {
            RingSide::Top => disc(top, self.outer_radius),
            RingSide::Bottom => disc(self.center, self.outer_radius),
            RingSide::Inner => disc(self.center, self.inner_radius).union(disc(top, self.inner_radius)),
            RingSide::Outer => disc(self.center, self.outer_radius).union(disc(top, self.outer_radius)),
        }
    }

    /// The smallest `t` in `(t_min, t_max)` where the ray meets `side`, or `f32::INFINITY`.
    #[inline]
    pub fn intersect_side(
        &self,
        side: RingSide,
        origin: Vec3,
        direction: Vec3,
        t_min: f32,
        t_max: f32,
    ) -> f32 {
        let o = origin - self.center;
        let oa = o.dot(self.axis);
        let da = direction.dot(self.axis);
        match side {
            RingSide::Top | RingSide::Bottom => {
                let h = if side == RingSide::Top { self.height } else { 0.0 };
                if da == 0.0 {
                    return f32::INFINITY;
                }
                let t = (h - oa) / da;
                if !(t > t_min && t < t_max) {
                    return f32::INFINITY;
                }
                let p = o + direction * t;
                let r2 = (p - self.axis * p.dot(self.axis)).length_squared();
                if r2 >= self.inner_radius * self.inner_radius && r2 <= self.outer_radius * self.outer_radius
                {
                    t
                } else {
                    f32::INFINITY
                }
            }
            RingSide::Inner | RingSide::Outer => {
                let r = if side == RingSide::Inner {
                    self.inner_radius
                } else {
                    self.outer_radius
                };
                let op = o - self.axis * oa;
                let dp = direction - self.axis * da;
                let a = dp.length_squared();
                if a == 0.0 {
                    return f32::INFINITY;
                }
                let b = op.dot(dp);
                let c = op.length_squared() - r * r;
                let disc = b * b - a * c;
                if disc < 0.0 {
                    return f32::INFINITY;
                }
                let sq = disc.sqrt();
                // Stable roots of a t² + 2 b t + c.
                let q = -(b + sq.copysign(b));
                let (mut t0, mut t1) = (q / a, if q != 0.0 { c / q } else { q / a });
                if t0 > t1 {
                    std::mem::swap(&mut t0, &mut t1);
                }
                for t in [t0, t1] {
                    if t > t_min && t < t_max {
                        let h = oa + da * t;
                        if (0.0..=self.height).contains(&h) {
                            return t;
                        }
                    }
                }
                f32::INFINITY
            }
        }
    }

    /// The side's unit normal (see [`RingSide`]) at point `p` on it.
    #[inline]
    pub fn side_normal(&self, side: RingSide, p: Vec3) -> Vec3 {
        match side {
            RingSide::Top => self.axis,
            RingSide::Bottom => -self.axis,
            RingSide::Inner | RingSide::Outer => {
                let o = p - self.center;
                let radial = (o - self.axis * o.dot(self.axis))
                    .try_normalize()
                    .unwrap_or(Vec3::X);
                if side == RingSide::Inner { -radial } else { radial }
            }
        }
    }

    /// Calls `f` with each polygon of `side`'s proxy (`segments` around the axis), wound
    /// counter-clockwise seen from the side its normal points to.
    pub fn for_each_proxy_polygon(&self, side: RingSide, segments: u32, mut f: impl FnMut(&[Vec3])) {
        let (u, v) = crate::sampling::orthonormal_frame(self.axis);
        let dir = |j: u32| {
            let phi = 2.0 * PI * j as f32 / segments as f32;
            u * phi.cos() + v * phi.sin()
        };
        let top = self.center + self.axis * self.height;
        for j in 0..segments {
            let (d0, d1) = (dir(j), dir(j + 1));
            // (u, v, axis) is right-handed, so increasing phi turns counter-clockwise about +axis.
            let quad = match side {
                RingSide::Top => [
                    top + d0 * self.inner_radius,
                    top + d0 * self.outer_radius,
                    top + d1 * self.outer_radius,
                    top + d1 * self.inner_radius,
                ],
                RingSide::Bottom => [
                    self.center + d0 * self.inner_radius,
                    self.center + d1 * self.inner_radius,
                    self.center + d1 * self.outer_radius,
                    self.center + d0 * self.outer_radius,
                ],
                RingSide::Outer => [
                    self.center + d0 * self.outer_radius,
                    self.center + d1 * self.outer_radius,
                    top + d1 * self.outer_radius,
                    top + d0 * self.outer_radius,
                ],
                RingSide::Inner => [
                    self.center + d0 * self.inner_radius,
                    top + d0 * self.inner_radius,
                    top + d1 * self.inner_radius,
                    self.center + d1 * self.inner_radius,
                ],
            };
            f(&quad);
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn ring() -> Ring {
        Ring {
            center: Vec3::ZERO,
            axis: Vec3::Y,
            inner_radius: 1.0,
            outer_radius: 2.0,
            height: 0.5,
        }
    }

    #[test]
    fn rays_hit_the_expected_side_at_the_expected_distance() {
        let r = ring();
        let down = Vec3::NEG_Y;
        assert!(
            (r.intersect_side(RingSide::Top, Vec3::new(1.5, 3.0, 0.0), down, 0.0, 10.0) - 2.5).abs() < 1e-5
        );
        assert_eq!(
            r.intersect_side(RingSide::Top, Vec3::new(0.5, 3.0, 0.0), down, 0.0, 10.0),
            f32::INFINITY
        );
        assert!(
            (r.intersect_side(RingSide::Bottom, Vec3::new(1.5, 3.0, 0.0), down, 0.0, 10.0) - 3.0).abs()
                < 1e-5
        );
        // From the axis outwards: inner cylinder at 1, outer at 2.
        let o = Vec3::new(0.0, 0.25, 0.0);
        assert!((r.intersect_side(RingSide::Inner, o, Vec3::X, 0.0, 10.0) - 1.0).abs() < 1e-5);
        assert!((r.intersect_side(RingSide::Outer, o, Vec3::X, 0.0, 10.0) - 2.0).abs() < 1e-5);
        // Above the ring the cylinders are missed.
        assert_eq!(
            r.intersect_side(RingSide::Outer, Vec3::new(0.0, 0.6, 0.0), Vec3::X, 0.0, 10.0),
            f32::INFINITY
        );
    }

    #[test]
    fn proxy_normals_match_side_normals_and_areas_approach_the_exact_ones() {
        let r = Ring {
            axis: Vec3::new(0.3, 1.0, 0.2).normalize(),
            ..ring()
        };
        for side in RingSide::ALL {
            let mut area = 0.0;
            r.for_each_proxy_polygon(side, 64, |p| {
                let va = pm_geom::polygon_vector_area(p);
                let centroid = p.iter().copied().sum::<Vec3>() / 4.0;
                assert!(
                    va.normalize().dot(r.side_normal(side, centroid)) > 0.99,
                    "{side:?}"
                );
                area += va.length();
            });
            let exact = match side {
                RingSide::Top | RingSide::Bottom => PI * (4.0 - 1.0),
                RingSide::Inner => 2.0 * PI * 0.5,
                RingSide::Outer => 2.0 * PI * 2.0 * 0.5,
            };
            assert!(
                area <= exact * 1.0001 && area > 0.99 * exact,
                "{side:?}: {area} vs {exact}"
            );
        }
    }
}
