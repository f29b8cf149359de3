//! Debug views of a photon cache, seen from the scene's camera at each pixel's first diffuse
//! hit (through mirrors and glass), drawn with the public query only.

use photon_maps::render::core::follow_delta_bounces;
use photon_maps::render::glam::Vec3;
use photon_maps::render::{CacheQuery, EstimatorScratch, Image, QueryMap, RadianceCache, RenderError};
use photon_maps::trace::{Hit, RayKind, Rng, Scene};

/// What a debug view shows.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum View {
    /// The cache points splatted: a pixel whose first hit lies within the splat radius of
    /// the cache point that answers there shows that point's irradiance (scaled by the
    /// image's mean), other pixels a dark grey; no answer: magenta.
    Points,
    /// The distance from each pixel's first hit to the cache point that answers there, from
    /// black (0) through blue and green to yellow (at four times the median distance); no
    /// answer: magenta. The footprint of each cache point, and where it is far.
    Radii,
    /// The photon map of each pixel's first hit, one colour per map id (a hash).
    Maps,
}

/// Magenta: no cache point answers.
const NO_ANSWER: Vec3 = Vec3::new(1.0, 0.0, 1.0);

/// What a view needs at a pixel: the hit, and the cache's answer there (point and distance).
struct Probe {
    hit: Hit,
    answer: Option<(Vec3, f32)>,
}

/// The view `view` of `cache` for `scene`, `width` × `height` pixels, one ray through each
/// pixel's centre; `splat` is the points view's radius (metres). Returns the image and, for
/// the radii view, the median distance it is scaled by.
pub fn render_view(
    scene: &Scene,
    cache: &RadianceCache,
    view: View,
    (width, height): (u32, u32),
    splat: f32,
) -> Result<(Image, f32), RenderError> {
    let probes = probe(scene, cache, width, height);
    let mut distances: Vec<f32> = probes
        .iter()
        .flatten()
        .filter_map(|p| p.answer.map(|a| a.1))
        .collect();
    distances.sort_by(f32::total_cmp);
    let median = distances.get(distances.len() / 2).copied().unwrap_or(0.0);
    let lit: Vec<f32> = probes
        .iter()
        .flatten()
        .filter_map(|p| p.answer.map(|a| a.0.max_element()))
        .collect();
    let mean_e = lit.iter().sum::<f32>() / lit.len().max(1) as f32;
    let pixels = probes
        .iter()
        .map(|probe| {
            let Some(probe) = probe else {
                return Vec3::ZERO;
            };
            match view {
                View::Maps => cache.map_of(probe.hit.part).map_or(NO_ANSWER, colour_of_id),
                View::Points => match probe.answer {
                    None => NO_ANSWER,
                    Some((e, d)) if d <= splat && mean_e > 0.0 => {
                        (e / (2.0 * mean_e)).min(Vec3::ONE).max(Vec3::splat(0.05))
                    }
                    Some(_) => Vec3::splat(0.02),
                },
                View::Radii => match probe.answer {
                    None => NO_ANSWER,
                    Some((_, d)) => ramp(if median > 0.0 { d / (4.0 * median) } else { 0.0 }),
                },
            }
        })
        .collect();
    Ok((Image::from_pixels(width, height, pixels)?, median))
}

/// Each pixel centre's first diffuse hit and the cache's answer there (its irradiance and the
/// distance to the answering point); `None` where the ray leaves the scene.
fn probe(scene: &Scene, cache: &RadianceCache, width: u32, height: u32) -> Vec<Option<Probe>> {
    let aspect = width as f32 / height as f32;
    let mut scratch = EstimatorScratch::new();
    let mut rng = Rng::new(0, 0);
    (0..height)
        .flat_map(|y| (0..width).map(move |x| (x, y)))
        .map(|(x, y)| {
            let ray = scene.camera().ray(
                (x as f32 + 0.5) / width as f32,
                (y as f32 + 0.5) / height as f32,
                aspect,
            );
            let vertex = follow_delta_bounces(scene, ray, RayKind::Camera, &mut rng, |_, _, _, _| {})?;
            let hit = vertex.hit;
            let query = CacheQuery {
                position: hit.position,
                normal: hit.normal,
                map: QueryMap::Part(hit.part),
                albedo: Vec3::ONE,
            };
            let answer = cache
                .radiance_at(&query, &mut scratch)
                .map(|a| (a.irradiance, a.distance_from(hit.position)));
            Some(Probe { hit, answer })
        })
        .collect()
}

/// A colour for map `id`: a hash of it to a hue, at full saturation and value 0.35–1.
fn colour_of_id(id: u32) -> Vec3 {
    let mut h = u64::from(id).wrapping_add(0x9E37_79B9_7F4A_7C15);
    h = (h ^ (h >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
    h = (h ^ (h >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
    h ^= h >> 31;
    let hue = (h & 0xFFFF) as f32 / 65536.0 * 6.0;
    let value = 0.35 + 0.65 * ((h >> 16) & 0xFF) as f32 / 255.0;
    let f = hue.fract();
    let rgb = match hue as u32 {
        0 => Vec3::new(1.0, f, 0.0),
        1 => Vec3::new(1.0 - f, 1.0, 0.0),
        2 => Vec3::new(0.0, 1.0, f),
        3 => Vec3::new(0.0, 1.0 - f, 1.0),
        4 => Vec3::new(f, 0.0, 1.0),
        _ => Vec3::new(1.0, 0.0, 1.0 - f),
    };
    rgb * value
}

/// Black → blue → green → yellow over `t` in [0, 1] (clamped).
fn ramp(t: f32) -> Vec3 {
    let t = t.clamp(0.0, 1.0) * 3.0;
    match t {
        t if t < 1.0 => Vec3::new(0.0, 0.0, t),
        t if t < 2.0 => Vec3::new(0.0, t - 1.0, 2.0 - t),
        t => Vec3::new(t - 2.0, 1.0, 0.0),
    }
}
