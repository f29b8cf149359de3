//! How a radiance cache's points are made: a map's photons split into cache points and the
//! photons their irradiance is estimated from (independent thinnings), then each estimated.

use super::points::IrradiancePoint;
use crate::error::RenderError;
use crate::estimator::point::SurfacePoint;
use crate::estimator::scratch::EstimatorScratch;
use glam::Vec3;
use pm_kdtree::PhotonTree;
use pm_trace::{Hit, Ray, RayKind, Scene};
use rayon::prelude::*;

/// Where [`super::RadianceCache::build_with`] asks for an irradiance estimate, and from what.
#[derive(Clone, Copy, Debug)]
pub struct CachePoint<'a> {
    /// The photon map (index into the trees given).
    pub map: usize,
    /// The cache point: a photon's position, with the normal and side of the surface it
    /// landed on.
    pub at: SurfacePoint,
    /// The map's photons that are not cache points, to estimate from. The estimate is
    /// scaled up by the cache for the photons set aside; estimating from these alone keeps it
    /// independent of where the cache points are (see [`super::RadianceCache`]).
    pub photons: &'a PhotonTree,
}

/// The cache points of map `m`: the photons of `tree` at `indices`, each on the surface it
/// landed on (found by a short cast back along its travel; a photon whose surface is not in
/// map `m` is skipped) with `irradiance` estimated there from `others`, times `set_aside`.
#[allow(clippy::too_many_arguments)]
pub(crate) fn cache_points<F>(
    scene: &Scene,
    map_of_part: &[u32],
    m: usize,
    tree: &PhotonTree,
    indices: &[u32],
    others: &PhotonTree,
    set_aside: f64,
    irradiance: &F,
) -> Vec<IrradiancePoint>
where
    F: Fn(CachePoint<'_>, &mut EstimatorScratch) -> Vec3 + Sync,
{
    indices
        .par_iter()
        .map_init(EstimatorScratch::new, |scratch, &i| {
            let (at, hit) = photon_surface_point(scene, tree, i, map_of_part, m as u32)?;
            let point = CachePoint {
                map: m,
                at,
                photons: others,
            };
            Some(IrradiancePoint {
                position: at.position,
                normal: hit.normal,
                irradiance: (irradiance(point, scratch).as_dvec3() * set_aside).as_vec3(),
            })
        })
        .flatten()
        .collect()
}

/// Splits `tree` into its cache points (the indices of the photons whose hash falls in the
/// lowest 1/`every` of its range: each photon independently, as far as a hash goes, so that
/// the two sets are independent thinnings of the photons) and a tree of the others.
///
/// The hash is of the photon's position as well as its index: by the index alone, the same
/// tree slots would be set aside in every tree of a size, whatever its photons, a share that
/// misses 1/`every` by a few tenths of a percent the same way in every pass.
pub(crate) fn split_cache_points(
    tree: &PhotonTree,
    every: u32,
) -> Result<(Vec<u32>, PhotonTree), RenderError> {
    let threshold = u64::MAX / u64::from(every);
    let scale = tree.power_scale();
    let mut points = Vec::with_capacity(tree.len() / every as usize + 1);
    let mut others = Vec::with_capacity(tree.len());
    for (i, photon) in tree.iter().enumerate() {
        let [x, y, z] = photon.position().to_array().map(|c| u64::from(c.to_bits()));
        let hash = mix(mix(mix(i as u64 ^ x) ^ (y << 32 | z)));
        if hash <= threshold {
            points.push(i as u32);
        } else {
            others.push(photon.decode(scale));
        }
    }
    let others = PhotonTree::build(others).map_err(|e| RenderError::BadFinalGather(e.to_string()))?;
    Ok((points, others))
}

/// Photon `i` of `tree` (of map `map`) placed on the surface it landed on: its position with
/// the normal and side of the surface a short cast back along its travel finds there (from
/// `4 ε` before it, the scene's rounding bound), with that hit; `None` when the surface is
/// in another map or none is found.
pub(crate) fn photon_surface_point(
    scene: &Scene,
    tree: &PhotonTree,
    i: u32,
    map_of_part: &[u32],
    map: u32,
) -> Option<(SurfacePoint, Hit)> {
    let back = 4.0 * scene.epsilon();
    let photon = tree.get(i);
    let (position, direction) = (photon.position(), photon.direction());
    let ray = Ray {
        origin: position - direction * back,
        direction,
    };
    let hit = scene.intersect(&ray, 2.0 * back, RayKind::Other)?;
    if map_of_part.get(hit.part.0 as usize) != Some(&map) {
        return None;
    }
    let at = SurfacePoint {
        position,
        normal: scene.shading_normal_at(&hit),
        front_face: hit.front_face,
    };
    Some((at, hit))
}

/// SplitMix64's finaliser: a well-mixed 64-bit hash of `x`.
fn mix(x: u64) -> u64 {
    let mut z = x.wrapping_add(0x9E37_79B9_7F4A_7C15);
    z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
    z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
    z ^ (z >> 31)
}
