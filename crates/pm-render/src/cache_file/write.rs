//! Writing a cache file's payload: the identity, the trace's figures, every map's photon tree
//! and the irradiance points, as little-endian fields in the order `read.rs` reads them.

use super::identity::CacheIdentity;
use crate::cache::RadianceCache;
use crate::renderer::PhotonCache;
use glam::Vec3;
use pm_kdtree::PhotonTree;

/// The payload of `cache` made for `identity`.
pub(crate) fn payload(cache: &PhotonCache, identity: &CacheIdentity) -> Vec<u8> {
    let mut out = Vec::new();
    let entries = identity.entries();
    put_u32(&mut out, entries.len() as u32);
    for (key, value) in entries {
        put_text(&mut out, key);
        put_text(&mut out, value);
    }
    put_u64(&mut out, cache.photons_emitted);
    out.extend_from_slice(&cache.near_light_fraction.to_le_bytes());
    put_u32(&mut out, cache.maps.len() as u32);
    for map in cache.maps.iter() {
        put_tree(&mut out, map.tree());
    }
    match &cache.radiance {
        None => out.push(0),
        Some(radiance) => {
            out.push(1);
            put_radiance(&mut out, radiance);
        }
    }
    out
}

fn put_radiance(out: &mut Vec<u8>, radiance: &RadianceCache) {
    for map in 0..radiance.map_count() as u32 {
        let points = radiance.points(map).map(|p| p.indexed());
        let empty = PhotonTree::default();
        let (index, normals, irradiance) = points.unwrap_or((&empty, &[], &[]));
        put_tree(out, index);
        put_vec3s(out, normals);
        put_vec3s(out, irradiance);
    }
}

fn put_u32(out: &mut Vec<u8>, x: u32) {
    out.extend_from_slice(&x.to_le_bytes());
}

fn put_u64(out: &mut Vec<u8>, x: u64) {
    out.extend_from_slice(&x.to_le_bytes());
}

fn put_text(out: &mut Vec<u8>, text: &str) {
    put_u32(out, text.len() as u32);
    out.extend_from_slice(text.as_bytes());
}

fn put_f32s(out: &mut Vec<u8>, xs: &[f32]) {
    out.reserve(xs.len() * 4);
    for x in xs {
        out.extend_from_slice(&x.to_le_bytes());
    }
}

fn put_vec3s(out: &mut Vec<u8>, vs: &[Vec3]) {
    out.reserve(vs.len() * 12);
    for v in vs {
        put_f32s(out, &v.to_array());
    }
}

/// A tree: photon count, scale, channels below range, the three coordinate arrays, the
/// payloads, then the split values and axes of its [`PhotonTree::inner_slots`] slots.
fn put_tree(out: &mut Vec<u8>, tree: &PhotonTree) {
    let a = tree.arrays();
    put_u64(out, a.xs.len() as u64);
    out.extend_from_slice(&a.scale_watts.to_le_bytes());
    put_u64(out, a.below_range);
    put_f32s(out, a.xs);
    put_f32s(out, a.ys);
    put_f32s(out, a.zs);
    out.reserve(a.payload.len() * 8);
    for p in a.payload {
        put_u64(out, *p);
    }
    put_f32s(out, a.splits);
    out.extend_from_slice(a.axes);
}
