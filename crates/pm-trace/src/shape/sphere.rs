//! The sphere: exact ray intersection and a latitude–longitude polygon proxy.

use glam::Vec3;
use pm_geom::Aabb;
use std::f32::consts::PI;

/// A sphere; its normal points outwards.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Sphere {
    /// Centre (metres).
    pub center: Vec3,
    /// Radius (metres, > 0).
    pub radius: f32,
}

impl Sphere {
    /// Bounds.
    pub fn bounds(&self) -> Aabb {
        Aabb::new(
            self.center - Vec3::splat(self.radius),
            self.center + Vec3::splat(self.radius),
        )
    }

    /// The smallest `t` in `(t_min, t_max)` where `origin + t·direction` (unit direction)
    /// meets the sphere, or `f32::INFINITY`.
    #[inline]
    pub fn intersect(&self, origin: Vec3, direction: Vec3, t_min: f32, t_max: f32) -> f32 {
        let oc = origin - self.center;
        let b = oc.dot(direction);
        // Numerically stable: c via the distance from the centre to the closest approach.
        let closest = oc - b * direction;
        let disc = self.radius * self.radius - closest.length_squared();
        if disc < 0.0 {
            return f32::INFINITY;
        }
        let sq = disc.sqrt();
        let near = -b - sq;
        if near > t_min && near < t_max {
            return near;
        }
        let far = -b + sq;
        if far > t_min && far < t_max {
            far
        } else {
            f32::INFINITY
        }
    }

    /// Outward unit normal at a point on the sphere.
    #[inline]
    pub fn normal_at(&self, p: Vec3) -> Vec3 {
        ((p - self.center) / self.radius).normalize()
    }

    /// Calls `f` with each polygon of a latitude–longitude proxy (`stacks × 2·stacks` cells,
    /// triangles at the poles), wound counter-clockwise seen from outside.
    pub fn for_each_proxy_polygon(&self, stacks: u32, mut f: impl FnMut(&[Vec3])) {
        let slices = 2 * stacks;
        let point = |i: u32, j: u32| {
            let theta = PI * i as f32 / stacks as f32;
            let phi = 2.0 * PI * j as f32 / slices as f32;
            self.center
                + self.radius * Vec3::new(theta.sin() * phi.cos(), theta.cos(), -theta.sin() * phi.sin())
        };
        for i in 0..stacks {
            for j in 0..slices {
                let (a, b, c, d) = (point(i, j), point(i + 1, j), point(i + 1, j + 1), point(i, j + 1));
                if i == 0 {
                    f(&[a, b, c]);
                } else if i + 1 == stacks {
                    f(&[a, b, d]);
                } else {
                    f(&[a, b, c, d]);
                }
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn ray_through_centre_hits_at_distance_minus_radius_and_from_inside_at_radius() {
        let s = Sphere {
            center: Vec3::new(1.0, 2.0, 3.0),
            radius: 0.5,
        };
        let t = s.intersect(Vec3::new(1.0, 2.0, 0.0), Vec3::Z, 0.0, f32::INFINITY);
        assert!((t - 2.5).abs() < 1e-5);
        let t = s.intersect(s.center, Vec3::X, 0.0, f32::INFINITY);
        assert!((t - 0.5).abs() < 1e-5);
        assert_eq!(
            s.intersect(Vec3::new(3.0, 2.0, 0.0), Vec3::Z, 0.0, f32::INFINITY),
            f32::INFINITY
        );
    }

    #[test]
    fn proxy_area_and_orientation_approach_the_sphere() {
        let s = Sphere {
            center: Vec3::ZERO,
            radius: 2.0,
        };
        let mut area = 0.0;
        s.for_each_proxy_polygon(16, |p| {
            let va = pm_geom::polygon_vector_area(p);
            let centroid = p.iter().copied().sum::<Vec3>() / p.len() as f32;
            assert!(va.dot(centroid) > 0.0, "proxy polygon faces inwards");
            area += va.length();
        });
        let exact = 4.0 * PI * 4.0;
        assert!(area < exact && area > 0.97 * exact, "{area} vs {exact}");
    }
}
