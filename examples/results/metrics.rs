//! What is measured against the reference: masked RMS error, the leak into the unlit room,
//! and the error near the accordion's creases against inside its facets.

use super::*;

/// True when the eye path of `ray` (first hit `hit`), followed through mirrors, meets an
/// emitter or glass.
pub fn sees_emitter(scene: &Scene, mut ray: Ray, mut hit: Hit) -> bool {
    for _ in 0..8 {
        if scene.emission(&hit) != Vec3::ZERO {
            return true;
        }
        match scene.material(&hit) {
            Material::Mirror { .. } => {
                let d = ray.direction;
                ray = scene.spawn_ray(&hit, d - 2.0 * d.dot(hit.normal) * hit.normal);
                match scene.intersect(&ray, f32::INFINITY, RayKind::Camera) {
                    Some(next) => hit = next,
                    None => return false,
                }
            }
            Material::Glass { .. } => return true,
            _ => return false,
        }
    }
    false
}

/// Pixels that count in the fidelity figures: all but those that see an emitter through their
/// centre or next to it. At one sample per pixel a pixel on a light's outline is either the
/// light or its surround (two pixels of margin), while the reference averages both: a large error that says
/// nothing about the estimators, which never see emitters.
pub fn fidelity_mask(scene: &Scene, config: &Config) -> Vec<bool> {
    let hits = first_hits(scene, config);
    let (w, h) = (config.width as i64, config.height as i64);
    let emits = |x: i64, y: i64| {
        x >= 0 && y >= 0 && x < w && y < h && hits[(y * w + x) as usize].is_some_and(|(_, e)| e)
    };
    let mut mask = Vec::with_capacity(hits.len());
    for y in 0..h {
        for x in 0..w {
            let near = (-2..=2).any(|dy| (-2..=2).any(|dx| emits(x + dx, y + dy)));
            mask.push(!near);
        }
    }
    mask
}

/// RMS over the masked pixels and their channels of `a − b`.
pub fn masked_rmse(a: &Image, b: &Image, mask: &[bool]) -> f32 {
    let (sum, n) = a
        .pixels()
        .iter()
        .zip(b.pixels())
        .zip(mask)
        .filter(|(_, m)| **m)
        .fold((0.0f64, 0usize), |(s, n), ((p, q), _)| {
            (s + (p.as_dvec3() - q.as_dvec3()).length_squared(), n + 1)
        });
    (sum / (3 * n.max(1)) as f64).sqrt() as f32
}

/// Mean over the masked pixels and channels.
pub fn masked_mean(a: &Image, mask: &[bool]) -> f32 {
    let (sum, n) = a
        .pixels()
        .iter()
        .zip(mask)
        .filter(|(_, m)| **m)
        .fold((0.0f64, 0usize), |(s, n), (p, _)| {
            (s + p.as_dvec3().element_sum(), n + 1)
        });
    (sum / (3 * n.max(1)) as f64) as f32
}

pub fn luminance(c: Vec3) -> f64 {
    (0.2126 * c.x + 0.7152 * c.y + 0.0722 * c.z) as f64
}

/// The first surface seen through each pixel centre, row by row (`None` for a miss), and
/// whether the eye path, followed through mirrors, reaches an emitter or glass.
pub fn first_hits(scene: &Scene, config: &Config) -> Vec<Option<(Vec3, bool)>> {
    let camera = scene.camera();
    let aspect = config.width as f32 / config.height as f32;
    let mut out = Vec::with_capacity((config.width * config.height) as usize);
    for y in 0..config.height {
        for x in 0..config.width {
            let u = (x as f32 + 0.5) / config.width as f32;
            let v = (y as f32 + 0.5) / config.height as f32;
            let ray = camera.ray(u, v, aspect);
            out.push(
                scene
                    .intersect(&ray, f32::INFINITY, RayKind::Camera)
                    .map(|h| (h.position, sees_emitter(scene, ray, h))),
            );
        }
    }
    out
}

/// Which room of `lit-unlit-rooms` a pixel shows.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Room {
    Lit,
    Dark,
    Neither,
}

/// The lit room spans x ∈ [0, 1], the dark one x ∈ [1.02, 2.02] (pm-trace's rooms scene); a
/// pixel belongs to the room its camera ray's first hit lies in.
pub fn room_classes(scene: &Scene, config: &Config) -> Vec<Room> {
    first_hits(scene, config)
        .into_iter()
        .map(|hit| match hit.map(|(p, _)| p) {
            Some(p) if p.x < 1.0 - 1e-4 => Room::Lit,
            Some(p) if p.x > 1.02 + 1e-4 => Room::Dark,
            _ => Room::Neither,
        })
        .collect()
}

/// Mean luminance over the dark room's pixels divided by the lit room's (the truth is 0).
pub fn leak_ratio(image: &Image, classes: &[Room]) -> f64 {
    let mean = |room: Room| {
        let (sum, count) = image
            .pixels()
            .iter()
            .zip(classes)
            .filter(|(_, c)| **c == room)
            .fold((0.0, 0usize), |(s, n), (p, _)| (s + luminance(*p), n + 1));
        sum / count.max(1) as f64
    };
    mean(Room::Dark) / mean(Room::Lit)
}

/// Where a pixel of the accordion lies relative to the creases.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Facet {
    /// Within one search radius of an interior crease.
    Crease,
    /// Farther than one search radius from every crease and from the strip's border.
    Interior,
    /// Near the border only, or off the strip.
    Other,
}

/// The accordion's facets are 0.25 m wide at ±45°: its folds lie at x = i·STEP, along z
/// (pm-trace's accordion scene; checked against the scene bounds).
pub const ACCORDION_STEP: f32 = 0.25 * std::f32::consts::FRAC_1_SQRT_2;
pub const ACCORDION_FACETS: usize = 8;

/// Classifies each pixel by the distance of its first hit to the nearest crease, measured
/// against that point's own search radius: the distance to its k-th nearest photon in the
/// single map (the disc estimator's radius).
pub fn accordion_classes(scene: &Scene, config: &Config) -> Result<Vec<Facet>, String> {
    let width = scene.bounds().max.x - scene.bounds().min.x;
    let expected = ACCORDION_FACETS as f32 * ACCORDION_STEP;
    if (width - expected).abs() > 0.05 * expected {
        return Err(format!(
            "accordion is {width} m wide, expected {expected} m: update ACCORDION_STEP"
        ));
    }
    let s = settings(config, Mode::PhotonMap, 1, 0);
    let renderer = Renderer::new(EstimatorKind::Disc, s);
    let partitioned = SingleMap.partition(scene.clone()).map_err(|e| e.to_string())?;
    let maps = renderer
        .build_maps(scene, partitioned.assignment(), &(), &mut RenderStats::default())
        .map_err(|e| e.to_string())?;
    let tree = maps.map(0).tree();
    let max_distance = s.estimator_options(&scene.bounds()).max_distance;
    let fold = |i: usize| {
        let y = if i.is_multiple_of(2) { 0.0 } else { ACCORDION_STEP };
        glam::Vec2::new(i as f32 * ACCORDION_STEP, y)
    };
    let mut neighbours = Neighbours::new();
    Ok(first_hits(scene, config)
        .into_iter()
        .map(|hit| {
            let Some((p, _)) = hit else { return Facet::Other };
            tree.nearest_k::<Euclidean>(p, config.k, max_distance, KindMask::ALL, &mut neighbours);
            let r = neighbours.extent();
            let xy = glam::Vec2::new(p.x, p.y);
            let crease = (1..ACCORDION_FACETS)
                .map(|i| xy.distance(fold(i)))
                .fold(f32::INFINITY, f32::min);
            let border = xy
                .distance(fold(0))
                .min(xy.distance(fold(ACCORDION_FACETS)))
                .min(p.z)
                .min(1.0 - p.z);
            if crease < r {
                Facet::Crease
            } else if border >= r {
                Facet::Interior
            } else {
                Facet::Other
            }
        })
        .collect())
}

pub fn edge_error(image: &Image, reference: &Image, classes: &[Facet]) -> EdgeError {
    let stats = |class: Facet| {
        let (mut abs, mut signed, mut truth, mut n) = (0.0, 0.0, 0.0, 0usize);
        for ((p, r), c) in image.pixels().iter().zip(reference.pixels()).zip(classes) {
            if *c == class {
                let (e, t) = (luminance(*p), luminance(*r));
                abs += (e - t).abs();
                signed += e - t;
                truth += t;
                n += 1;
            }
        }
        let n = n.max(1) as f64;
        (abs / n, signed / truth.max(f64::MIN_POSITIVE))
    };
    let (edge_abs, edge_bias) = stats(Facet::Crease);
    let (interior_abs, interior_bias) = stats(Facet::Interior);
    EdgeError {
        edge_abs,
        interior_abs,
        edge_bias,
        interior_bias,
    }
}
