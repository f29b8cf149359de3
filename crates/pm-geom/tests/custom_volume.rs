//! Proves that `GatherVolume` is an extension point: a volume defined outside the crate (a
//! slab, a disc flattened along the normal of a floor) plugs into a generic gather loop
//! over a `PolygonSet`, next to the built-in cube and ball.

use pm_geom::glam::{Vec3, vec3};
use pm_geom::{
    Aabb, Ball, ClipScratch, GatherVolume, Plane, PolygonSet, polygon_area, split_convex_polygon_by_plane,
};

/// The points within `half_thickness` of `plane`, cut to `extent`: a thick, bounded slab.
struct Slab {
    plane: Plane,
    half_thickness: f32,
    extent: Aabb,
}

impl GatherVolume for Slab {
    fn bounds(&self) -> Aabb {
        self.extent
    }

    fn polygon_area_inside(&self, polygon: &[Vec3], normal: Vec3, scratch: &mut ClipScratch) -> f32 {
        let _ = normal;
        let above = Plane {
            offset: self.plane.offset + self.half_thickness,
            ..self.plane
        };
        let below = Plane {
            offset: self.plane.offset - self.half_thickness,
            ..self.plane
        };
        let (mut front, mut back, mut middle) = (Vec::new(), Vec::new(), Vec::new());
        split_convex_polygon_by_plane(polygon, &above, &mut front, &mut back);
        split_convex_polygon_by_plane(&back, &below, &mut middle, &mut front);
        polygon_area(pm_geom::clip_polygon_to_aabb(&middle, &self.extent, scratch))
    }
}

/// The generic loop an estimator runs: candidates by bounds, then exact areas.
fn gathered_area<V: GatherVolume>(set: &PolygonSet, volume: &V) -> f32 {
    let mut scratch = ClipScratch::new();
    let mut total = 0.0;
    set.for_each_overlapping(&volume.bounds(), |i| {
        total += volume.polygon_area_inside(set.polygon(i), set.normal(i), &mut scratch);
    });
    total
}

/// A room corner: a 4 × 4 floor (y = 0) and a 4 × 4 wall (x = 0), each as 16 unit quads.
fn room_corner() -> PolygonSet {
    let mut set = PolygonSet::new();
    for i in 0..4 {
        for j in 0..4 {
            let (a, b) = (i as f32, j as f32);
            set.push(&[
                vec3(a, 0., b),
                vec3(a, 0., b + 1.),
                vec3(a + 1., 0., b + 1.),
                vec3(a + 1., 0., b),
            ]);
            set.push(&[
                vec3(0., a, b),
                vec3(0., a + 1., b),
                vec3(0., a + 1., b + 1.),
                vec3(0., a, b + 1.),
            ]);
        }
    }
    set.build_index();
    set
}

#[test]
fn slab_defined_outside_the_crate_gathers_exact_areas() {
    let set = room_corner();
    assert_eq!(set.len(), 32);
    // A horizontal slab 0.2 thick around y = 1, over x, z in [0, 2]: it holds no floor and
    // a 2 × 0.2 band of the wall.
    let slab = Slab {
        plane: Plane::from_point_normal(vec3(0., 1., 0.), Vec3::Y),
        half_thickness: 0.1,
        extent: Aabb::new(vec3(0., 0.9, 0.), vec3(2., 1.1, 2.)),
    };
    assert!((gathered_area(&set, &slab) - 0.4).abs() < 1e-5);
    // A slab around the floor, y in [-0.1, 0.1], over [0.5, 2.5]²: a 2 × 2 floor patch, and
    // the wall is outside the extent in x.
    let floor = Slab {
        plane: Plane::from_point_normal(Vec3::ZERO, Vec3::Y),
        half_thickness: 0.1,
        extent: Aabb::new(vec3(0.5, -0.1, 0.5), vec3(2.5, 0.1, 2.5)),
    };
    assert!((gathered_area(&set, &floor) - 4.0).abs() < 1e-5);
}

#[test]
fn built_in_volumes_go_through_the_same_generic_loop() {
    let set = room_corner();
    // A cube of half-size 0.5 at the corner's edge: a 1 × 0.5 rectangle of each plane.
    let cube = Aabb::cube(vec3(0., 0., 2.), 0.5);
    assert!((gathered_area(&set, &cube) - 1.0).abs() < 1e-5);
    // A ball on the floor away from the wall: a full disc.
    let ball = Ball::new(vec3(2., 0.3, 2.), 0.5);
    assert!((gathered_area(&set, &ball) - std::f32::consts::PI * 0.16).abs() < 1e-5);
    // A ball centred on the corner edge: half a disc on each plane.
    let edge = Ball::new(vec3(0., 0., 2.), 0.5);
    assert!((gathered_area(&set, &edge) - std::f32::consts::PI * 0.25).abs() < 1e-5);
}
