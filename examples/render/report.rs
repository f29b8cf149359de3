//! What a render reports: the one-line summary on stdout and the JSON object of its figures.

use super::{Args, Variant};
use photon_maps::render::{RenderSettings, RenderStats};
use std::fmt::Write as _;

/// The figures of one finished render, for the summary and the JSON.
pub struct Record<'a> {
    pub args: &'a Args,
    pub scene: &'a str,
    pub variant: &'a Variant,
    pub settings: &'a RenderSettings,
    pub stats: RenderStats,
    pub mean: [f32; 3],
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
    // Power that hit a surface within a millimetre of its light: a light facing into a wall
    // (the JSON has the figure however small).
    let near = match s.near_light_fraction {
        f if f >= 0.01 => format!(
            ", {:.1} % of the emitted power hit a surface within 1 mm of its light (facing into a wall? an area light faces edge_u × edge_v)",
            100.0 * f
        ),
        _ => String::new(),
    };
    format!(
        "{} [{}]: {lighting}, mode {}, {}x{}, {} photons ({} stored{below}{near}): trace {:.3} s, build {:.3} s, render {:.3} s, total {:.3} s, mean rgb ({:.4}, {:.4}, {:.4})",
        r.scene,
        r.variant.label,
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
    let _ = write!(
        o,
        "\"seconds\": {{\"trace\": {}, \"build\": {}, \"render\": {}, \"total\": {}}}, \"mean_rgb\": [{}, {}, {}]}}",
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
