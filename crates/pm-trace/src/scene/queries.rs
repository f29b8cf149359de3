//! The scene's ray queries: closest hits (one ray, or two interleaved), occlusion between two
//! points, and rays leaving a hit.

use super::offset::{interpolated_point_error, offset_point, point_error};
use super::{Hit, RayKind, Scene};
use crate::bvh::closest::Crossing;
use crate::bvh::{HitPrimitive, Leaving};
use crate::part::PartSurface;
use crate::ray::Ray;
use glam::Vec3;

/// Triangles from which [`Scene::prefers_ray_pairs`] (and [`Scene::intersect_pair`] interleaves
/// the two searches; below it, it casts the rays one after the other). Random rays cast in
/// pairs were 5–17 % faster at 240k triangles on a quiet machine and 20–26 % faster with the
/// other core busy (the misses they overlap are then slower), and 3–9 % slower at 2.4k and 21.6k,
/// where everything fits in the cache (one thread, the rooms with every face split;
/// `benches/raycast.rs`). On a modelled kitchen of 56,939 triangles, photon paths traced in
/// pairs were 8–31 % slower on one and two threads (`benches/kitchen.rs`, the threshold
/// lowered for the test), so the threshold stays above it.
pub const PAIRED_RAYS_MIN_TRIANGLES: usize = 65_536;

/// Crossings in dropped parts of cut faces a ray passes at most before it counts as meeting
/// nothing (each is a hidden copy of a face; a model with more copies stacked on one spot is
/// refused by the split's own bounds long before).
const MAX_PASSED: usize = 16;

impl Scene {
    /// The closest hit with `0 < t < t_max`. Rays leaving a surface should start at
    /// [`Scene::spawn_ray`]'s offset origin.
    ///
    /// Camera rays skip surfaces hidden from the camera and the backs of
    /// [`crate::Sides::Single`] surfaces (back-face culling, as glTF viewers do); other rays
    /// see every side of every surface.
    #[inline]
    pub fn intersect(&self, ray: &Ray, t_max: f32, kind: RayKind) -> Option<Hit> {
        let (t, index) = self.closest_of_kind(ray, t_max, kind, &[])?;
        match self.hit_at(ray, t, index) {
            Some(hit) => Some(hit),
            None => self.intersect_past_dropped(ray, t_max, kind, &[index]),
        }
    }

    /// [`Scene::intersect`] for a ray that leaves the surface point `from` (a ray of
    /// [`Scene::spawn_ray`]): the triangle `from` lies on is not searched. A ray leaving a
    /// triangle's plane cannot meet it again, but the triangle test's own rounding, large on a
    /// sliver (its distance errs by the triangle's condition `L² / 2A` times its corners'
    /// rounding, more than the offset off a sliver), would now and then say it does, and the
    /// path would lose a bounce there. Shapes are searched as usual (a ray leaving a sphere's
    /// inside meets it again).
    #[inline]
    pub fn intersect_from(&self, from: &Hit, ray: &Ray, t_max: f32, kind: RayKind) -> Option<Hit> {
        let leaving = match from.primitive {
            HitPrimitive::Triangle(_) => from.primitive,
            HitPrimitive::Shape(_) => return self.intersect(ray, t_max, kind),
        };
        let (t, index) = self.closest_of_kind(ray, t_max, kind, &[leaving])?;
        match self.hit_at(ray, t, index) {
            Some(hit) => Some(hit),
            None => self.intersect_past_dropped(ray, t_max, kind, &[leaving, index]),
        }
    }

    /// The closest crossing a ray of `kind` takes, skipping the triangles in `passed`.
    #[inline(always)]
    fn closest_of_kind(
        &self,
        ray: &Ray,
        t_max: f32,
        kind: RayKind,
        passed: &[HitPrimitive],
    ) -> Option<(f32, HitPrimitive)> {
        match kind {
            RayKind::Other => match passed {
                [] => self.bvh.closest(ray, 0.0, t_max, |_| true),
                &[left] => self.bvh.closest(ray, 0.0, t_max, |c| c.primitive != left),
                _ => self
                    .bvh
                    .closest(ray, 0.0, t_max, |c| !passed.contains(&c.primitive)),
            },
            RayKind::Camera if self.has_culling => self.closest_camera_hit_culling(ray, t_max, passed),
            RayKind::Camera => self.bvh.closest(ray, 0.0, t_max, |c| {
                self.surfaces[c.surface as usize].camera_visible && !passed.contains(&c.primitive)
            }),
        }
    }

    /// [`Scene::intersect`] after its closest crossing (the last of `skipped`, the rest being
    /// a triangle the ray leaves) fell where the contact split dropped a hidden copy of a
    /// coincident face: the search again without them (and without each such crossing after
    /// it), which finds the copy kept at the same distance. A point
    /// lies in a dropped part only of a split scene's cut faces, so this is rare and out of
    /// line; past [`MAX_PASSED`] such crossings in a row the ray counts as meeting nothing.
    #[cold]
    #[inline(never)]
    fn intersect_past_dropped(
        &self,
        ray: &Ray,
        t_max: f32,
        kind: RayKind,
        skipped: &[HitPrimitive],
    ) -> Option<Hit> {
        let mut passed = skipped.to_vec();
        while passed.len() <= MAX_PASSED {
            let (t, index) = self.closest_of_kind(ray, t_max, kind, &passed)?;
            match self.hit_at(ray, t, index) {
                Some(hit) => return Some(hit),
                None => passed.push(index),
            }
        }
        None
    }

    /// The closest camera hit in a scene with single-sided surfaces: the backs of those are
    /// skipped inside the search, so a culled back face never hides a front face at the same
    /// distance (two rooms modelled on one wall plane, each single-sided). Out of line, so
    /// scenes without single-sided surfaces pay nothing for it.
    #[inline(never)]
    fn closest_camera_hit_culling(
        &self,
        ray: &Ray,
        t_max: f32,
        passed: &[HitPrimitive],
    ) -> Option<(f32, HitPrimitive)> {
        self.bvh.closest(ray, 0.0, t_max, |c| {
            let surface = &self.surfaces[c.surface as usize];
            surface.camera_visible
                && !(surface.sides.culls_back() && self.faces_away(ray, c))
                && !passed.contains(&c.primitive)
        })
    }

    /// True when the ray meets `crossing`'s primitive from behind (its normal along the ray),
    /// the test [`Scene::hit_at`] makes for [`Hit::front_face`].
    #[inline]
    fn faces_away(&self, ray: &Ray, crossing: &Crossing) -> bool {
        let n = self.bvh.normal_at(crossing.primitive, ray.at(crossing.t));
        n.dot(ray.direction) >= 0.0
    }

    /// The closest hits of two rays of [`RayKind::Other`] with `0 < t < t_max`: the same hits
    /// as two calls of [`Scene::intersect`], found faster where rays are incoherent (photon
    /// paths), because the two searches are interleaved and their waits for memory overlap.
    #[inline]
    pub fn intersect_pair(&self, rays: [&Ray; 2], t_max: f32) -> [Option<Hit>; 2] {
        self.intersect_pair_from(rays, [None, None], t_max)
    }

    /// [`Scene::intersect_pair`] for rays that may leave surface points (`from`, as
    /// [`Scene::intersect_from`]).
    #[inline]
    pub fn intersect_pair_from(
        &self,
        rays: [&Ray; 2],
        from: [Option<&Hit>; 2],
        t_max: f32,
    ) -> [Option<Hit>; 2] {
        if !self.prefers_ray_pairs() {
            return [0, 1].map(|k| match from[k] {
                Some(f) => self.intersect_from(f, rays[k], t_max, RayKind::Other),
                None => self.intersect(rays[k], t_max, RayKind::Other),
            });
        }
        let leaving = from.map(|f| match f.map(|f| f.primitive) {
            Some(HitPrimitive::Triangle(i)) => Leaving::Triangle(i),
            _ => Leaving::Nothing,
        });
        let hits = self.bvh.closest_pair(rays, t_max, leaving);
        [0, 1].map(|k| {
            let (t, index) = hits[k]?;
            match self.hit_at(rays[k], t, index) {
                Some(hit) => Some(hit),
                None => {
                    let mut skipped: Vec<HitPrimitive> = from[k]
                        .map(|f| f.primitive)
                        .filter(|p| matches!(p, HitPrimitive::Triangle(_)))
                        .into_iter()
                        .collect();
                    skipped.push(index);
                    self.intersect_past_dropped(rays[k], t_max, RayKind::Other, &skipped)
                }
            }
        })
    }

    /// True when [`Scene::intersect_pair`] beats two calls of [`Scene::intersect`] on
    /// incoherent rays: scenes of at least [`PAIRED_RAYS_MIN_TRIANGLES`] triangles, whose
    /// BVH and triangles no longer fit in a core's cache.
    pub fn prefers_ray_pairs(&self) -> bool {
        self.bvh.triangle_count() >= PAIRED_RAYS_MIN_TRIANGLES
    }

    /// The hit of `ray` at distance `t` on primitive `index`; `None` where the point lies in
    /// a part of a cut face that the contact split dropped (a hidden copy of a coincident face).
    #[inline(always)]
    fn hit_at(&self, ray: &Ray, t: f32, index: HitPrimitive) -> Option<Hit> {
        // On a triangle the point is written in the triangle's own coordinates, so it lies on
        // the triangle's plane within rounding of the corners however thin the triangle is
        // (`origin + t · direction` carries t's error, which a sliver magnifies).
        // Of the two, the point with the smaller bound: the corner form rounds at the corners'
        // scale, the ray's point at the ray's, times the triangle's condition (a sliver
        // magnifies t's error). A ground plane kilometres wide seen from near the origin
        // keeps the ray's point; a sliver piece of the contact split takes the corner form.
        let on_ray = ray.at(t);
        let ray_error = point_error(ray.origin, on_ray, t);
        let (position, error) = match self.bvh.interpolated_point(ray, index, t) {
            Some((point, magnitude, condition)) => {
                let (corner_error, on_ray_error) = (
                    interpolated_point_error(magnitude),
                    ray_error * condition.max(1.0),
                );
                if corner_error <= on_ray_error {
                    (point, corner_error)
                } else {
                    (on_ray, on_ray_error)
                }
            }
            None => (on_ray, ray_error),
        };
        let (PartSurface { part, surface }, n) = self.bvh.part_and_normal(index, position)?;
        let front_face = n.dot(ray.direction) < 0.0;
        Some(Hit {
            t,
            position,
            normal: if front_face { n } else { -n },
            front_face,
            part,
            surface,
            error,
            primitive: index,
        })
    }

    /// True when a surface lies strictly between `from` and `to` (surfaces within the
    /// rounding error of either end do not count, so both may lie on surfaces).
    #[inline]
    pub fn occluded(&self, from: Vec3, to: Vec3) -> bool {
        let d = to - from;
        let dist = d.length();
        let error = point_error(from, to, dist);
        if !dist.is_finite() || dist <= 2.0 * error {
            return false;
        }
        let ray = Ray {
            origin: from,
            direction: d / dist,
        };
        self.bvh.any_hit(&ray, error, dist - error)
    }

    /// True when a surface lies between the surface point `hit` and `to`: the shadow ray
    /// starts off `hit`'s surface as [`Scene::spawn_ray`]'s do, and surfaces within the
    /// rounding error of `to` do not count (it may lie on a light's surface). The triangle
    /// `hit` lies on is not tested: a ray leaving its plane cannot meet it, and the triangle
    /// test's own rounding, large on a sliver, would now and then say it does.
    #[inline]
    pub fn occluded_from(&self, hit: &Hit, to: Vec3) -> bool {
        let side = if (to - hit.position).dot(hit.normal) >= 0.0 {
            hit.normal
        } else {
            -hit.normal
        };
        let from = offset_point(hit.position, side, hit.error);
        let d = to - from;
        let dist = d.length();
        let error = point_error(from, to, dist);
        if !dist.is_finite() || dist <= error {
            return false;
        }
        let ray = Ray {
            origin: from,
            direction: d / dist,
        };
        let leaving = match hit.primitive {
            HitPrimitive::Triangle(i) => Leaving::Triangle(i),
            HitPrimitive::Shape(_) => Leaving::Nothing,
        };
        self.bvh.any_hit_leaving(&ray, 0.0, dist - error, leaving)
    }

    /// A ray leaving `hit` along unit `direction`, its origin pushed off the surface to the
    /// side `direction` goes to by the hit's rounding error ([`Hit::error`]) and one float
    /// step more, so it neither re-hits the same surface nor starts beyond a thin wall.
    #[inline]
    pub fn spawn_ray(&self, hit: &Hit, direction: Vec3) -> Ray {
        let side = if direction.dot(hit.normal) >= 0.0 {
            hit.normal
        } else {
            -hit.normal
        };
        Ray {
            origin: offset_point(hit.position, side, hit.error),
            direction,
        }
    }
}
