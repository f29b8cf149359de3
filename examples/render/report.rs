//! What a render reports: the one-line summary on stdout and the JSON object of its figures.

use super::{Args, Variant};
use photon_maps::render::{RenderSettings, RenderStats};
use photon_maps::trace::ContactRecord;
use std::fmt::Write as _;

/// The figures of one finished render, for the summary and the JSON.
pub struct Record<'a> {
    pub args: &'a Args,
    pub scene: &'a str,
    pub variant: &'a Variant,
    pub settings: &'a RenderSettings,
    pub stats: RenderStats,
    pub mean: [f32; 3],
    /// [`contacts_summary`] and [`contacts_json`] of the partition rendered.
    pub contacts: (String, String),
    /// The world point the scene was re-centred on (`Scene::origin_offset`), metres.
    pub origin_offset: [f64; 3],
    /// What `--save-cache` / `--load-cache` did, if given.
    pub cache: Option<super::cache::CacheUse>,
    /// The time before rendering.
    pub setup: Setup,
}

/// Wall-clock seconds before rendering: reading the scene (once per run, whatever the
/// variants) and partitioning it into photon maps (`None` where nothing is partitioned: SPPM's
/// one map). The contact partition's steps are in `contacts.phases`.
#[derive(Clone, Copy, Debug)]
pub struct Setup {
    pub load: f64,
    pub partition: Option<f64>,
}

impl Setup {
    /// As a JSON object.
    pub fn json(&self) -> String {
        format!(
            "{{\"load\": {}, \"partition\": {}}}",
            json_number(self.load),
            self.partition.map_or_else(|| "null".to_owned(), json_number)
        )
    }
}

/// The re-centring offset for the summary: empty for a scene that was not moved.
pub fn origin_summary(offset: [f64; 3]) -> String {
    if offset == [0.0; 3] {
        return String::new();
    }
    format!(
        ", re-centred: scene coordinates are relative to ({}, {}, {}) m in the file",
        offset[0], offset[1], offset[2]
    )
}

/// The same as a JSON array `[x, y, z]` (zeros for a scene that was not moved).
pub fn origin_json(offset: [f64; 3]) -> String {
    format!(
        "[{}, {}, {}]",
        json_number(offset[0]),
        json_number(offset[1]),
        json_number(offset[2])
    )
}

/// What the contact partition found where faces meet, for the summary: empty when the scene
/// was not split.
pub fn contacts_summary(record: Option<&ContactRecord>) -> String {
    let Some(record) = record else {
        return String::new();
    };
    let c = record.counts();
    format!(
        ", faces meeting: {} piercing, {} in-plane, {} coplanar, {} near-contact ({} hidden copies dropped, {} pieces sealed in solids; {:.3} s)",
        c.piercing,
        c.in_plane,
        c.coplanar_overlap,
        c.near_contact,
        c.duplicate_pieces,
        c.sealed_pieces,
        record.seconds()
    )
}

/// The same as a JSON value: `null` when the scene was not split.
pub fn contacts_json(record: Option<&ContactRecord>) -> String {
    let Some(record) = record else {
        return "null".to_owned();
    };
    let c = record.counts();
    let p = record.phases();
    let a = p.arrangement;
    format!(
        "{{\"piercing\": {}, \"in_plane\": {}, \"coplanar_overlap\": {}, \"near_contact\": {}, \"duplicate_pieces\": {}, \"sealed_pieces\": {}, \"candidate_pairs\": {}, \"seconds\": {}, \"phases\": {{\"faces\": {}, \"meetings\": {}, \"cutting\": {}, \"copies_and_sealing\": {}, \"rebuild\": {}, \"faces_as_given\": {}, \"fill\": {}}}}}",
        c.piercing,
        c.in_plane,
        c.coplanar_overlap,
        c.near_contact,
        c.duplicate_pieces,
        c.sealed_pieces,
        c.candidate_pairs,
        json_number(record.seconds()),
        json_number(p.faces + a.faces),
        json_number(a.meetings),
        json_number(a.cutting),
        json_number(a.copies_and_sealing),
        json_number(p.rebuild),
        json_number(p.faces_as_given),
        json_number(p.fill)
    )
}

pub fn summary(r: &Record<'_>) -> String {
    let s = &r.stats;
    // Path tracing reads no photon maps: say so rather than "crease (0), estimator cube".
    let lighting = if s.photons_emitted == 0 {
        "no photon maps".to_string()
    } else {
        format!(
            "maps {} ({}), estimator {}",
            r.variant.maps, s.map_count, r.variant.estimator
        )
    };
    // Channels too dim for their map's power codes (over 10¹² below its brightest): say so.
    let below = match s.photon_channels_below_range {
        0 => String::new(),
        n => format!(", {n} power channels below the map's range stored as zero"),
    };
    // The final gather's costs: its precomputation, its cache and its gather rays.
    let gather = if s.cache_points == 0 {
        String::new()
    } else {
        format!(
            ", precompute {:.3} s ({} cache points, {:.1} MB), {} gather rays ({:.2} M/s)",
            s.precompute.as_secs_f64(),
            s.cache_points,
            s.cache_bytes as f64 / 1e6,
            s.gather_rays,
            s.gather_rays_per_second() / 1e6
        )
    };
    // Power that hit a surface within a millimetre of its light: a light facing into a wall
    // (the JSON has the figure however small).
    let near = match s.near_light_fraction {
        f if f >= 0.01 => format!(
            ", {:.1} % of the emitted power hit a surface within 1 mm of its light (facing into a wall? an area light faces edge_u × edge_v)",
            100.0 * f
        ),
        _ => String::new(),
    };
    // A loaded cache traced and built nothing: say so, and how long the file took.
    let cache = match &r.cache {
        Some(c) if c.what == "loaded" => format!(
            ", photons and cache loaded from the cache file in {:.3} s (no tracing or building)",
            c.seconds
        ),
        Some(c) => format!(", cache file {} in {:.3} s", c.what, c.seconds),
        None => String::new(),
    };
    let auto = super::auto::summary(&s.auto_photons);
    let emission = super::emission::summary(s.emission.as_ref(), s.photons_emitted, s.photons_traced);
    format!(
        "{} [{}]: {lighting}{}{}{cache}, mode {}, {}x{}, {} photons ({} stored{below}{near}{auto}{emission}): trace {:.3} s, build {:.3} s{gather}, render {:.3} s, total {:.3} s, mean rgb ({:.4}, {:.4}, {:.4})",
        r.scene,
        r.variant.label,
        r.contacts.0,
        origin_summary(r.origin_offset),
        r.settings.mode,
        r.settings.width,
        r.settings.height,
        s.photons_emitted,
        s.photons_stored,
        s.trace.as_secs_f64(),
        s.build.as_secs_f64(),
        s.render.as_secs_f64(),
        s.total().as_secs_f64(),
        r.mean[0],
        r.mean[1],
        r.mean[2],
    )
}

pub fn json_object(r: &Record<'_>) -> String {
    let s = &r.stats;
    let mut o = String::from("{");
    let _ = write!(
        o,
        "\"scene\": {}, \"variant\": {}, ",
        json_string(r.scene),
        json_string(r.variant.label),
    );
    // Only what applied: a path-traced render reads no photon maps, so it has no maps,
    // estimator or k to record.
    let photon_maps = r.settings.mode.uses_photons();
    if photon_maps {
        let _ = write!(
            o,
            "\"maps\": {}, \"estimator\": {}, ",
            json_string(&r.variant.maps.to_string()),
            json_string(r.variant.estimator.name()),
        );
    }
    let _ = write!(
        o,
        "\"mode\": {}, \"width\": {}, \"height\": {}, \"spp\": {}, ",
        json_string(r.settings.mode.name()),
        r.settings.width,
        r.settings.height,
        r.settings.samples_per_pixel,
    );
    if photon_maps {
        let _ = write!(o, "\"k\": {}, ", r.settings.k);
    }
    let _ = write!(
        o,
        "\"photons_emitted\": {}, \"photons_stored\": {}, \"photon_channels_below_range\": {}, \"near_light_fraction\": {}, \"map_count\": {}, \"threads\": {}, \"seed\": {}, ",
        s.photons_emitted,
        s.photons_stored,
        s.photon_channels_below_range,
        json_number(s.near_light_fraction),
        s.map_count,
        s.threads,
        r.args.seed,
    );
    if photon_maps {
        o.push_str(&super::emission::json(s.emission.as_ref(), s.photons_traced));
    }
    if photon_maps && s.occupancy.maps > 0 {
        let m = &s.occupancy;
        let _ = write!(
            o,
            "\"map_occupancy\": {{\"k\": {}, \"maps\": {}, \"empty\": {}, \"below_k\": {}, \"photons_below_k\": {}, \"photons_per_map_p10_p50_p90_max\": [{}, {}, {}, {}], \"area\": {}, \"area_share_below_k\": {}}}, ",
            m.k,
            m.maps,
            m.empty,
            m.below_k,
            m.photons_below_k,
            m.photons_per_map[0],
            m.photons_per_map[1],
            m.photons_per_map[2],
            m.photons_per_map[3],
            json_number(m.area),
            json_number(m.area_share_below_k()),
        );
    }
    if r.settings.mode == photon_maps::render::Mode::FinalGather {
        let _ = write!(
            o,
            "\"gather_rays\": {}, \"gather_rays_per_sample\": {}, \"cache_every\": {}, \"cache_points\": {}, \"cache_bytes\": {}, \"gather_rays_per_second\": {}, ",
            s.gather_rays,
            r.settings.final_gather.gather_rays,
            r.settings.final_gather.cache_every,
            s.cache_points,
            s.cache_bytes,
            json_number(s.gather_rays_per_second()),
        );
    }
    o.push_str(&super::auto::json(&s.auto_photons));
    if let Some(c) = &r.cache {
        let _ = write!(
            o,
            "\"cache\": {}, \"cache_file_seconds\": {}, ",
            json_string(c.what),
            json_number(c.seconds)
        );
    }
    let _ = write!(
        o,
        "\"contacts\": {}, \"origin_offset\": {}, \"setup_seconds\": {}, \"seconds\": {{\"trace\": {}, \"build\": {}, \"precompute\": {}, \"render\": {}, \"total\": {}}}, \"mean_rgb\": [{}, {}, {}]}}",
        r.contacts.1,
        origin_json(r.origin_offset),
        r.setup.json(),
        json_number(s.trace.as_secs_f64()),
        json_number(s.build.as_secs_f64()),
        json_number(s.precompute.as_secs_f64()),
        json_number(s.render.as_secs_f64()),
        json_number(s.total().as_secs_f64()),
        json_number(r.mean[0] as f64),
        json_number(r.mean[1] as f64),
        json_number(r.mean[2] as f64),
    );
    o
}

pub fn json_string(s: &str) -> String {
    let mut out = String::from("\"");
    for c in s.chars() {
        match c {
            '"' => out.push_str("\\\""),
            '\\' => out.push_str("\\\\"),
            c if (c as u32) < 0x20 => {
                let _ = write!(out, "\\u{:04x}", c as u32);
            }
            c => out.push(c),
        }
    }
    out.push('"');
    out
}

/// JSON has no NaN or infinity: write them as null.
pub fn json_number(x: f64) -> String {
    if x.is_finite() {
        format!("{x}")
    } else {
        "null".to_owned()
    }
}
