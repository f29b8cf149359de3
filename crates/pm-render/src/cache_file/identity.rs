//! What a cache file was made for: the settings that change its photons and cache, and a
//! fingerprint of the partitioned scene. A load is refused by the first entry that differs.

use super::error::CacheFileError;
use super::hash::Hash64;
use crate::estimator::Estimator;
use crate::mode::Mode;
use crate::renderer::Renderer;
use pm_trace::{PartId, Partitioned, Scene};

/// Entries (`key=value`) naming what a cache's photons and irradiance cache depend on.
///
/// Settings: `photons`, `seed`, `radiance_cache` (`yes` in final-gather mode, which saves its
/// irradiance cache) and, with one, what the cache's estimates read: `estimator`, `k`,
/// `max_distance` (the distance in effect, in metres), `reject_behind` and `cache_every`. The
/// image size, samples, camera, threads and tiles are not entries: one cache renders any
/// camera at any size.
///
/// Scene: `parts`, `maps` and `assignment` (the partition's [`Partitioned::identity`]),
/// `geometry` (a hash of every part's polygons, vertex coordinates bit for bit: mesh faces as
/// they are, spheres and rings by their proxies), `surfaces` (a hash of each part's surface:
/// material, emission, visibility, sides, every number's exact value), `lights` (a hash of
/// each light's parameters as its `Debug` text prints them, which holds every parameter of
/// the built-in lights in exact decimal; a textured light's texels only as far as its `Debug`
/// shows them), `appearance` (a hash of every mesh's vertex attributes and textures, texel
/// for texel: [`Scene::feed_appearance`]) and `map_geometry`. Not covered: a custom BSDF's
/// parameters beyond what its `Debug` prints.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct CacheIdentity {
    entries: Vec<(String, String)>,
}

impl CacheIdentity {
    /// The identity a run of `renderer` on `partitioned` expects of a cache.
    pub fn of_run<E: Estimator>(renderer: &Renderer<E>, partitioned: &Partitioned) -> Self {
        let s = renderer.settings();
        let estimator = renderer.estimator();
        let scene = partitioned.scene();
        // The scene's entries first: a cache for another scene is named as such, not by a
        // setting that follows from the scene (the default maximum distance).
        let mut entries = Vec::new();
        for token in partitioned.identity().split_whitespace() {
            if let Some((key, value)) = token.split_once('=') {
                entries.push((key.to_owned(), value.to_owned()));
            }
        }
        entries.extend([
            ("geometry".to_owned(), format!("{:016x}", geometry_hash(scene))),
            ("surfaces".to_owned(), format!("{:016x}", surfaces_hash(scene))),
            (
                "appearance".to_owned(),
                format!("{:016x}", appearance_hash(scene)),
            ),
            ("lights".to_owned(), format!("{:016x}", lights_hash(scene))),
            ("map_geometry".to_owned(), "merged".to_owned()),
            ("photons".to_owned(), s.photons.to_string()),
            ("seed".to_owned(), s.seed.to_string()),
        ]);
        if let Some(emission) = s.emission.identity() {
            entries.push(("emission".to_owned(), emission));
        }
        if s.mode == Mode::FinalGather {
            let options = s.estimator_options(&scene.bounds());
            entries.extend([
                ("radiance_cache".to_owned(), "yes".to_owned()),
                ("estimator".to_owned(), estimator.identity()),
                ("k".to_owned(), s.k.to_string()),
                ("max_distance".to_owned(), format!("{:?}", options.max_distance)),
                ("reject_behind".to_owned(), s.reject_behind.to_string()),
                ("cache_every".to_owned(), s.final_gather.cache_every.to_string()),
            ]);
        } else {
            entries.push(("radiance_cache".to_owned(), "no".to_owned()));
        }
        CacheIdentity { entries }
    }

    /// This identity with `key` set to `value` (added when missing).
    pub fn with_entry(mut self, key: &str, value: &str) -> Self {
        match self.entries.iter_mut().find(|(k, _)| k == key) {
            Some(entry) => entry.1 = value.to_owned(),
            None => self.entries.push((key.to_owned(), value.to_owned())),
        }
        self
    }

    /// An identity of these entries (as a file holds them).
    pub fn from_entries(entries: Vec<(String, String)>) -> Self {
        CacheIdentity { entries }
    }

    /// The entries, in order.
    pub fn entries(&self) -> &[(String, String)] {
        &self.entries
    }

    /// The value of `key`, if any.
    pub fn get(&self, key: &str) -> Option<&str> {
        self.entries
            .iter()
            .find(|(k, _)| k == key)
            .map(|(_, v)| v.as_str())
    }

    /// `Ok` when `file` (a cache file's identity) has this run's entries, and no others;
    /// otherwise the first entry that differs, with both values.
    pub fn check_file(&self, file: &CacheIdentity) -> Result<(), CacheFileError> {
        let none = || "(none)".to_owned();
        for (key, run) in &self.entries {
            let found = file.get(key);
            if found != Some(run.as_str()) {
                return Err(CacheFileError::IdentityMismatch {
                    key: key.clone(),
                    file: found.map_or_else(none, str::to_owned),
                    run: run.clone(),
                });
            }
        }
        if let Some((key, value)) = file.entries.iter().find(|(k, _)| self.get(k).is_none()) {
            return Err(CacheFileError::IdentityMismatch {
                key: key.clone(),
                file: value.clone(),
                run: none(),
            });
        }
        Ok(())
    }
}

/// Every part's polygons, in part order, vertex coordinates bit for bit.
fn geometry_hash(scene: &Scene) -> u64 {
    let mut hash = Hash64::new();
    hash.write_u64(scene.part_count() as u64);
    for part in 0..scene.part_count() as u32 {
        scene.for_each_part_polygon(PartId(part), |polygon| {
            hash.write_u64(polygon.len() as u64);
            for v in polygon {
                for c in v.to_array() {
                    hash.write(&c.to_bits().to_le_bytes());
                }
            }
        });
    }
    hash.finish()
}

/// Every part's surface by its `Debug` text (exact values), each distinct run of equal
/// surfaces formatted once.
fn surfaces_hash(scene: &Scene) -> u64 {
    let mut hash = Hash64::new();
    let mut last: Option<(pm_trace::Surface, u64)> = None;
    for part in 0..scene.part_count() as u32 {
        let surface = *scene.part_surface(PartId(part));
        let text_hash = match last {
            Some((s, h)) if s == surface => h,
            _ => {
                let mut one = Hash64::new();
                one.write_text(&format!("{surface:?}"));
                let h = one.finish();
                last = Some((surface, h));
                h
            }
        };
        hash.write_u64(text_hash);
    }
    hash.finish()
}

/// Every mesh's vertex attributes and textures ([`Scene::feed_appearance`]): a texel or a
/// texture coordinate changes where photons land and what they carry.
fn appearance_hash(scene: &Scene) -> u64 {
    let mut hash = Hash64::new();
    scene.feed_appearance(&mut |bytes| hash.write(bytes));
    hash.finish()
}

/// Every light by its `Debug` text.
fn lights_hash(scene: &Scene) -> u64 {
    let mut hash = Hash64::new();
    hash.write_u64(scene.lights().len() as u64);
    for light in scene.lights() {
        hash.write_text(&format!("{light:?}"));
    }
    hash.finish()
}
