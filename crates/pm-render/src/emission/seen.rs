//! What the camera sees, for camera-driven emission: the photon map and a grid cell of every
//! point where a grid of camera rays is first read (after mirror and glass bounces), and, for
//! a final gather, of where gather rays from those points are read. A photon is *seen* when
//! its map and cell hold such a point: nearness on the same side of a wall, never through it
//! (a photon behind a wall lies in another map). At most 128 × 128 camera points and 4 gather
//! points each: the set holds at most 81,920 entries.

use crate::core::follow_delta_bounces_from;
use glam::{DVec3, Vec2, Vec3};
use pm_trace::sampling::cosine_hemisphere;
use pm_trace::{Camera, Hit, MapAssignment, Ray, RayKind, Rng, Scene};
use std::collections::HashSet;

/// Most camera rays across the image's longer side, for one camera; `n` cameras take
/// `CAMERA_GRID / ⌈√n⌉` each (at least 8), so that they hold about as many points as one.
pub const CAMERA_GRID: u32 = 128;

/// Most cameras read: more are thinned to this many, evenly spaced.
pub const MAX_CAMERAS: usize = 256;

/// Rays from each camera point that find where a final gather reads the maps.
pub const GATHER_RAYS_PER_POINT: u32 = 4;

/// Whether the maps are read where the camera's rays land, or one diffuse bounce further.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum ReadAt {
    /// At the camera rays' first non-delta hits (photon-map, shadow-rays, progressive, SPPM).
    CameraHits,
    /// At the hits of gather rays from those points too (the final gather).
    GatherHits,
}

/// The (map, cell) pairs near points where the maps are read.
#[derive(Clone, Debug)]
pub struct SeenSurfaces {
    cells: HashSet<(u32, [i64; 3])>,
    origin: DVec3,
    cell: f64,
    points: usize,
}

impl SeenSurfaces {
    /// The points of `cameras` (each on a grid of at most [`CAMERA_GRID`] rays across an image
    /// of `width × height`, fewer for several cameras; at most [`MAX_CAMERAS`] cameras, evenly
    /// spaced); the cell is twice the median spacing of the camera rays where they land.
    pub fn of_cameras(
        scene: &Scene,
        assignment: &MapAssignment,
        cameras: &[Camera],
        (width, height): (u32, u32),
        read_at: ReadAt,
        seed: u64,
    ) -> Self {
        let step = cameras.len().div_ceil(MAX_CAMERAS).max(1);
        let cameras: Vec<Camera> = cameras.iter().step_by(step).copied().collect();
        let side = (f64::from(CAMERA_GRID) / (cameras.len() as f64).sqrt().ceil().max(1.0)).max(8.0);
        let scale = side / f64::from(width.max(height).max(1));
        let (gw, gh) = if scale < 1.0 {
            (
                ((f64::from(width) * scale).round() as u32).max(1),
                ((f64::from(height) * scale).round() as u32).max(1),
            )
        } else {
            (width.max(1), height.max(1))
        };
        let aspect = width.max(1) as f32 / height.max(1) as f32;
        let mut points: Vec<(u32, Vec3)> = Vec::new();
        let mut spacing: Vec<f32> = Vec::new();
        for (c, camera) in cameras.iter().enumerate() {
            let angle = camera.pixel_angle(gh);
            for j in 0..gh {
                for i in 0..gw {
                    let stream = (c as u64) << 40 | u64::from(j) << 20 | u64::from(i);
                    let mut rng = Rng::for_pass(seed, u64::MAX - 1, stream);
                    let u = (i as f32 + 0.5) / gw as f32;
                    let v = (j as f32 + 0.5) / gh as f32;
                    let ray = camera.ray(u, v, aspect);
                    let Some(vertex) = follow_delta_bounces_from(
                        scene,
                        None,
                        ray,
                        RayKind::Camera,
                        &mut rng,
                        |_, _, _, _| {},
                    ) else {
                        continue;
                    };
                    points.push((assignment.map_of(vertex.hit.part), vertex.hit.position));
                    spacing.push(vertex.distance * angle);
                    if read_at == ReadAt::GatherHits {
                        gather_points(scene, assignment, &vertex.hit, &vertex.ray, &mut rng, &mut points);
                    }
                }
            }
        }
        let bounds = scene.bounds();
        let floor = f64::from((bounds.max - bounds.min).length()) * 1e-6;
        spacing.sort_by(f32::total_cmp);
        let median = spacing.get(spacing.len() / 2).map_or(0.0, |&s| f64::from(s));
        let cell = (2.0 * median).max(floor).max(f64::MIN_POSITIVE);
        let origin = bounds.min.as_dvec3();
        // Camera points lie about half a cell apart, so the cells they fill cover what they see
        // without marking neighbours (which would hold 27 entries a point).
        let cells: HashSet<(u32, [i64; 3])> = points
            .iter()
            .map(|&(map, p)| (map, cell_of(p, origin, cell)))
            .collect();
        SeenSurfaces {
            cells,
            origin,
            cell,
            points: points.len(),
        }
    }

    /// True when a point of map `map` at `position` is near a point where the maps are read.
    #[inline]
    pub fn sees(&self, map: u32, position: Vec3) -> bool {
        self.cells
            .contains(&(map, cell_of(position, self.origin, self.cell)))
    }

    /// Points where the maps are read (camera and gather hits).
    pub fn points(&self) -> usize {
        self.points
    }

    /// The side of the grid's cells, metres.
    pub fn cell(&self) -> f64 {
        self.cell
    }
}

/// The integer cell of `p` (clamped far outside any scene: a non-finite point lands in a cell
/// no point fills).
#[inline]
fn cell_of(p: Vec3, origin: DVec3, cell: f64) -> [i64; 3] {
    let t = (p.as_dvec3() - origin) / cell;
    t.to_array().map(|x| x.floor().clamp(-1e15, 1e15) as i64)
}

/// Where [`GATHER_RAYS_PER_POINT`] cosine-weighted rays from `hit` (on the side `ray` came
/// from) are first read.
fn gather_points(
    scene: &Scene,
    assignment: &MapAssignment,
    hit: &Hit,
    ray: &Ray,
    rng: &mut Rng,
    points: &mut Vec<(u32, Vec3)>,
) {
    let normal = if hit.normal.dot(ray.direction) > 0.0 {
        -hit.normal
    } else {
        hit.normal
    };
    for _ in 0..GATHER_RAYS_PER_POINT {
        let direction = cosine_hemisphere(normal, Vec2::new(rng.next_f32(), rng.next_f32()));
        let gather = scene.spawn_ray(hit, direction);
        if let Some(v) =
            follow_delta_bounces_from(scene, Some(hit), gather, RayKind::Other, rng, |_, _, _, _| {})
        {
            points.push((assignment.map_of(v.hit.part), v.hit.position));
        }
    }
}
