//! The pixels the errors are measured over: all but those whose centre sees a light (directly
//! or through mirrors and glass) and their neighbours two pixels around. With one jittered
//! sample per pass, a pixel on a light's outline is the light (tens of times brighter than
//! the scene's mean) in some passes and its surround in others: its noise would dominate every
//! method's RMSE alike and says nothing about the indirect light the methods differ in.

use photon_maps::render::Image;
use photon_maps::render::glam::{DVec3, Vec3};
use photon_maps::trace::{Material, RayKind, Scene};

/// Per pixel, row by row: true where the error counts.
pub struct Mask(Vec<bool>);

impl Mask {
    /// The mask of a `width × height` image of `scene`.
    pub fn new(scene: &Scene, width: u32, height: u32) -> Self {
        let camera = scene.camera();
        let aspect = width as f32 / height as f32;
        let sees_light: Vec<bool> = (0..width * height)
            .map(|i| {
                let (x, y) = ((i % width) as f32 + 0.5, (i / width) as f32 + 0.5);
                let mut ray = camera.ray(x / width as f32, y / height as f32, aspect);
                for _ in 0..8 {
                    let Some(hit) = scene.intersect(&ray, f32::INFINITY, RayKind::Camera) else {
                        return false;
                    };
                    if scene.emission(&hit) != Vec3::ZERO {
                        return true;
                    }
                    match scene.material(&hit) {
                        Material::Mirror { .. } => {
                            let d = ray.direction;
                            ray = scene.spawn_ray(&hit, d - 2.0 * d.dot(hit.normal) * hit.normal);
                        }
                        Material::Glass { .. } => return true,
                        _ => return false,
                    }
                }
                false
            })
            .collect();
        let (w, h) = (width as i64, height as i64);
        let near = |x: i64, y: i64| {
            (-2..=2).any(|dy| {
                (-2..=2).any(|dx| {
                    let (u, v) = (x + dx, y + dy);
                    u >= 0 && v >= 0 && u < w && v < h && sees_light[(v * w + u) as usize]
                })
            })
        };
        Mask((0..w * h).map(|i| !near(i % w, i / w)).collect())
    }

    /// Every pixel of a `width × height` image counts.
    pub fn all(width: u32, height: u32) -> Self {
        Mask(vec![true; (width * height) as usize])
    }

    /// Share of the pixels that count.
    pub fn coverage(&self) -> f64 {
        self.0.iter().filter(|&&m| m).count() as f64 / self.0.len().max(1) as f64
    }

    /// RMSE over the counted pixels and channels, over the reference's mean there.
    pub fn relative_rmse(&self, image: &Image, reference: &Image) -> f64 {
        let (mut squares, mut truth, mut n) = (0.0f64, 0.0f64, 0usize);
        for ((p, r), _) in image
            .pixels()
            .iter()
            .zip(reference.pixels())
            .zip(&self.0)
            .filter(|(_, m)| **m)
        {
            let (p, r): (DVec3, DVec3) = (p.as_dvec3(), r.as_dvec3());
            squares += (p - r).length_squared();
            truth += r.element_sum();
            n += 3;
        }
        if n == 0 || truth <= 0.0 {
            return 0.0;
        }
        (squares / n as f64).sqrt() / (truth / n as f64)
    }
}
