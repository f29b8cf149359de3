//! What a render reports: the one-line summary on stdout and the JSON object of its figures.

use super::{Args, Variant};
use photon_maps::render::{RenderSettings, RenderStats};
use photon_maps::trace::Scene;
use std::fmt::Write as _;

/// The figures of one finished render, for the summary and the JSON.
pub struct Record<'a> {
    pub args: &'a Args,
    pub scene: &'a str,
    pub variant: &'a Variant,
    pub settings: &'a RenderSettings,
    pub stats: RenderStats,
    pub mean: [f32; 3],
    /// [`contacts_summary`] and [`contacts_json`] of the scene rendered.
    pub contacts: (String, String),
}

/// What the contact partition found where faces meet, for the summary: empty when the scene
/// was not split.
pub fn contacts_summary(scene: &Scene) -> String {
    let Some(record) = scene.contact_record() else {
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
pub fn contacts_json(scene: &Scene) -> String {
    let Some(record) = scene.contact_record() else {
        return "null".to_owned();
    };
    let c = record.counts();
    format!(
        "{{\"piercing\": {}, \"in_plane\": {}, \"coplanar_overlap\": {}, \"near_contact\": {}, \"duplicate_pieces\": {}, \"sealed_pieces\": {}, \"seconds\": {}}}",
        c.piercing,
        c.in_plane,
        c.coplanar_overlap,
        c.near_contact,
        c.duplicate_pieces,
        c.sealed_pieces,
        json_number(record.seconds())
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
    format!(
        "{} [{}]: {lighting}{}, mode {}, {}x{}, {} photons ({} stored{below}): trace {:.3} s, build {:.3} s, render {:.3} s, total {:.3} s, mean rgb ({:.4}, {:.4}, {:.4})",
        r.scene,
        r.variant.label,
        r.contacts.0,
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
        "\"scene\": {}, \"variant\": {}, \"maps\": {}, \"estimator\": {}, \"mode\": {}, ",
        json_string(r.scene),
        json_string(r.variant.label),
        json_string(&r.variant.maps.to_string()),
        json_string(r.variant.estimator.name()),
        json_string(r.settings.mode.name()),
    );
    let _ = write!(
        o,
        "\"width\": {}, \"height\": {}, \"spp\": {}, \"k\": {}, \"photons_emitted\": {}, \"photons_stored\": {}, \"photon_channels_below_range\": {}, \"map_count\": {}, \"threads\": {}, \"seed\": {}, ",
        r.settings.width,
        r.settings.height,
        r.settings.samples_per_pixel,
        r.settings.k,
        s.photons_emitted,
        s.photons_stored,
        s.photon_channels_below_range,
        s.map_count,
        s.threads,
        r.args.seed,
    );
    let _ = write!(
        o,
        "\"contacts\": {}, \"seconds\": {{\"trace\": {}, \"build\": {}, \"render\": {}, \"total\": {}}}, \"mean_rgb\": [{}, {}, {}]}}",
        r.contacts.1,
        json_number(s.trace.as_secs_f64()),
        json_number(s.build.as_secs_f64()),
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
