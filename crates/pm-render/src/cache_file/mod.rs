//! A persistent photon cache: the photon maps and the final gather's irradiance cache in one
//! file, saved once and loaded by later renders (other cameras, other frames) instead of tracing.
//!
//! A render from a loaded cache is bit-identical to the render that built it, in every mode
//! that reads photons: each photon tree is stored as it is held (photon order, packed
//! payloads, split values and axes, power scale), so lookups see the same photons in the same
//! order; the irradiance points likewise (their index tree, normals and irradiances in full
//! precision). What follows deterministically from those and the scene is rebuilt on load,
//! not stored: each map's polygons (from the scene, as the maps' build makes them) and the
//! caustic trees (from the maps' caustic photons, as the cache's build makes them), so the
//! file cannot contradict the maps, and a hostile file cannot smuggle in a caustic tree.
//!
//! # Format (version 1, little-endian)
//!
//! | bytes | field |
//! |---|---|
//! | 8 | magic number [`MAGIC`] |
//! | 4 | format version [`FORMAT_VERSION`] |
//! | 8 | payload length (at most [`MAX_PAYLOAD_BYTES`]) |
//! | 8 | payload checksum ([`payload_checksum`], a 64-bit word hash) |
//! | … | payload: identity, figures, maps, radiance cache |
//!
//! The payload: the identity ([`CacheIdentity`]: entry count, then key and value as
//! length-prefixed UTF-8); the photons emitted (u64) and the near-light fraction (f64); the
//! map count (u32) and each map's tree; a flag (0 or 1) and, when 1, per map the irradiance
//! points' index tree, then their normals and irradiances (3 × f32 each). A tree is its photon
//! count (u64), power scale (f32, watts), channels below range (u64), x, y and z arrays (f32),
//! packed payloads (u64), then its [`PhotonTree::inner_slots`](pm_kdtree::PhotonTree::inner_slots)
//! split values (f32) and axes (u8).
//!
//! # What is checked
//!
//! The magic number, the version, the payload's length against the bytes there are and its
//! checksum; then every count against the bytes that remain before anything is allocated for
//! it (a file of N bytes allocates O(N) however its counts lie), every tree's invariants
//! ([`PhotonTree::from_arrays`](pm_kdtree::PhotonTree::from_arrays)), every photon within its
//! map's bounds ([`PhotonMaps::validate`]) and no bytes after the payload. A bad file is a
//! [`CacheFileError`] naming the section, byte offset and field; nothing panics. A cache for
//! another scene or other settings is refused by the first [`CacheIdentity`] entry that
//! differs, with the file's value and the run's.

mod error;
mod hash;
mod identity;
mod read;
mod write;

pub use error::CacheFileError;
pub use hash::{Hash64, payload_checksum};
pub use identity::CacheIdentity;

use crate::cache::RadianceCache;
use crate::cache::points::IrradiancePoints;
use crate::estimator::Estimator;
use crate::image::atomic::write_atomically;
use crate::image::input::check_input_file;
use crate::renderer::{PhotonCache, Renderer};
use pm_trace::{MapGeometry, Partitioned, PhotonMaps};
use read::Fields;
use std::io::{Read, Write};
use std::path::Path;

/// The first 8 bytes of every cache file.
pub const MAGIC: [u8; 8] = *b"PMCACHE\0";
/// The format version written and read.
pub const FORMAT_VERSION: u32 = 1;
/// Bytes before the payload: magic, version, payload length, checksum.
pub const HEADER_BYTES: usize = 28;
/// The largest payload read or written (1 TiB).
pub const MAX_PAYLOAD_BYTES: u64 = 1 << 40;

/// Writes `cache`, made by `renderer` for `partitioned`, to `writer` with the identity of that
/// run ([`CacheIdentity::of_run`]).
pub fn save_cache<E: Estimator>(
    mut writer: impl Write,
    renderer: &Renderer<E>,
    partitioned: &Partitioned,
    cache: &PhotonCache,
) -> Result<(), CacheFileError> {
    let kind = match cache.maps.geometry_kind() {
        MapGeometry::Merged => "merged",
        MapGeometry::PerFace => "per-face",
    };
    let identity = CacheIdentity::of_run(renderer, partitioned).with_entry("map_geometry", kind);
    let payload = write::payload(cache, &identity);
    let io = |e: std::io::Error| CacheFileError::Io {
        path: "the writer".into(),
        message: e.to_string(),
    };
    writer.write_all(&MAGIC).map_err(io)?;
    writer.write_all(&FORMAT_VERSION.to_le_bytes()).map_err(io)?;
    writer
        .write_all(&(payload.len() as u64).to_le_bytes())
        .map_err(io)?;
    writer
        .write_all(&payload_checksum(&payload).to_le_bytes())
        .map_err(io)?;
    writer.write_all(&payload).map_err(io)?;
    writer.flush().map_err(io)
}

/// [`save_cache`] to the file `path`, atomically (a failed write keeps the old file).
pub fn save_cache_file<E: Estimator>(
    path: &Path,
    renderer: &Renderer<E>,
    partitioned: &Partitioned,
    cache: &PhotonCache,
) -> Result<(), CacheFileError> {
    let mut failure = None;
    write_atomically(path, |w| {
        save_cache(w, renderer, partitioned, cache).map_err(|e| {
            let message = e.to_string();
            failure = Some(e);
            std::io::Error::other(message)
        })
    })
    .map_err(|e| {
        failure.take().unwrap_or_else(|| CacheFileError::Io {
            path: path.display().to_string(),
            message: e.to_string(),
        })
    })
}

/// Reads a cache from `reader` for a render of `renderer` on `partitioned`: refused unless the
/// file was made by a run with the same [`CacheIdentity`]. The maps' polygons and the caustic
/// trees are rebuilt from the scene and the photons (on the current rayon pool); the result
/// renders ([`Renderer::render_from_cache`]) the bits the run that saved it rendered.
pub fn load_cache<E: Estimator>(
    mut reader: impl Read,
    renderer: &Renderer<E>,
    partitioned: &Partitioned,
) -> Result<PhotonCache, CacheFileError> {
    let payload = read_payload(&mut reader)?;
    let mut fields = Fields::new(&payload, HEADER_BYTES as u64);
    let identity = fields.identity()?;
    CacheIdentity::of_run(renderer, partitioned).check_file(&identity)?;
    fields.section = "figures";
    let photons_emitted = fields.u64("photons emitted")?;
    let near_light_fraction = fields.f64("near-light fraction")?;
    let maps = read_maps(&mut fields, partitioned)?;
    fields.section = "radiance cache";
    let offset = fields.offset();
    let radiance = match fields.u8("radiance cache flag")? {
        0 => None,
        1 => Some(read_radiance(&mut fields, renderer, partitioned, &maps)?),
        flag => {
            return Err(fields.invalid(offset, "radiance cache flag", format!("{flag}, expected 0 or 1")));
        }
    };
    if radiance.is_some() != (identity.get("radiance_cache") == Some("yes")) {
        return Err(fields.invalid(
            offset,
            "radiance cache flag",
            "disagrees with the identity".into(),
        ));
    }
    if fields.remaining() > 0 {
        return Err(CacheFileError::TrailingBytes {
            offset: fields.offset(),
        });
    }
    Ok(PhotonCache {
        maps,
        radiance,
        photons_emitted,
        near_light_fraction,
    })
}

/// [`load_cache`] from the file `path`, refused unless it is a regular file (a FIFO or a
/// device is never opened) of at most [`HEADER_BYTES`] + [`MAX_PAYLOAD_BYTES`] bytes.
pub fn load_cache_file<E: Estimator>(
    path: &Path,
    renderer: &Renderer<E>,
    partitioned: &Partitioned,
) -> Result<PhotonCache, CacheFileError> {
    let io = |message: String| CacheFileError::Io {
        path: path.display().to_string(),
        message,
    };
    check_input_file(path, HEADER_BYTES as u64 + MAX_PAYLOAD_BYTES).map_err(|e| io(e.to_string()))?;
    let file = std::fs::File::open(path).map_err(|e| io(e.to_string()))?;
    load_cache(std::io::BufReader::new(file), renderer, partitioned)
}

/// The header checked and the payload read (no more bytes than there are: it grows as bytes
/// arrive) and checked against its checksum, with nothing after it.
fn read_payload(reader: &mut impl Read) -> Result<Vec<u8>, CacheFileError> {
    let io = |e: std::io::Error| CacheFileError::Io {
        path: "the reader".into(),
        message: e.to_string(),
    };
    let mut header = Vec::with_capacity(HEADER_BYTES);
    reader
        .by_ref()
        .take(HEADER_BYTES as u64)
        .read_to_end(&mut header)
        .map_err(io)?;
    if header.len() < MAGIC.len() || header[..8] != MAGIC {
        return Err(CacheFileError::NotACacheFile {
            found: header[..header.len().min(8)].to_vec(),
            expected: MAGIC,
        });
    }
    let mut fields = Fields::new(&header, 0);
    fields.section = "header";
    fields.u64("magic number")?;
    let version = fields.u32("format version")?;
    if version != FORMAT_VERSION {
        return Err(CacheFileError::UnsupportedVersion {
            found: version,
            supported: FORMAT_VERSION,
        });
    }
    let offset = fields.offset();
    let len = fields.u64("payload length")?;
    let stored = fields.u64("payload checksum")?;
    if len > MAX_PAYLOAD_BYTES {
        return Err(fields.too_large(offset, "payload length", len, MAX_PAYLOAD_BYTES));
    }
    let mut payload = Vec::new();
    reader.by_ref().take(len).read_to_end(&mut payload).map_err(io)?;
    if (payload.len() as u64) < len {
        return Err(CacheFileError::Truncated {
            section: "payload",
            offset: HEADER_BYTES as u64,
            field: "payload",
            needed: len,
            remaining: payload.len() as u64,
        });
    }
    let mut extra = [0u8; 1];
    if reader.read(&mut extra).map_err(io)? > 0 {
        return Err(CacheFileError::TrailingBytes {
            offset: HEADER_BYTES as u64 + len,
        });
    }
    let computed = payload_checksum(&payload);
    if computed != stored {
        return Err(CacheFileError::ChecksumMismatch { stored, computed });
    }
    Ok(payload)
}

/// The maps: their count (the partition's), each tree, then the maps rebuilt on the scene and
/// checked (every photon within its map's bounds).
fn read_maps(fields: &mut Fields<'_>, partitioned: &Partitioned) -> Result<PhotonMaps, CacheFileError> {
    fields.section = "maps";
    let offset = fields.offset();
    let count = fields.u32("map count")?;
    let expected = partitioned.assignment().map_count();
    if count != expected {
        return Err(fields.invalid(
            offset,
            "map count",
            format!("{count}, but the partition has {expected} maps"),
        ));
    }
    // A tree takes at least 20 bytes before its photons.
    fields.check_room("maps", u64::from(count), 20)?;
    let mut trees = Vec::with_capacity(count as usize);
    for _ in 0..count {
        trees.push(fields.tree()?);
    }
    let invalid = |what: String| CacheFileError::Invalid {
        section: "maps",
        offset,
        field: "photon maps",
        what,
    };
    let maps = PhotonMaps::from_trees(
        partitioned.scene(),
        partitioned.assignment(),
        trees,
        MapGeometry::Merged,
    )
    .map_err(|e| invalid(e.to_string()))?;
    maps.validate().map_err(|e| invalid(e.to_string()))?;
    Ok(maps)
}

/// The irradiance points of every map, made into the cache the run would build.
fn read_radiance<E: Estimator>(
    fields: &mut Fields<'_>,
    renderer: &Renderer<E>,
    partitioned: &Partitioned,
    maps: &PhotonMaps,
) -> Result<RadianceCache, CacheFileError> {
    let start = fields.offset();
    fields.check_room("irradiance points", maps.len() as u64, 20)?;
    let mut points = Vec::with_capacity(maps.len());
    for _ in 0..maps.len() {
        let offset = fields.offset();
        let index = fields.tree()?;
        let n = index.len() as u64;
        let normals = fields.vec3s("normals", n)?;
        let irradiance = fields.vec3s("irradiances", n)?;
        let indexed = IrradiancePoints::from_indexed(index, normals, irradiance)
            .map_err(|e| fields.invalid(offset, "irradiance points", e.to_string()))?;
        points.push(indexed);
    }
    let settings = renderer.settings();
    let max_distance = settings
        .estimator_options(&partitioned.scene().bounds())
        .max_distance;
    RadianceCache::from_points(points, maps, settings.final_gather.cache_every, max_distance)
        .map_err(|e| fields.invalid(start, "radiance cache", e.to_string()))
}
