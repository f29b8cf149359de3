//! `--auto-photons THRESHOLD`: photons traced in doubling batches from `--photons` until the
//! cache's estimate changes less than THRESHOLD between batches (`pm_render::auto_photons`);
//! the render is the bits of a plain run with the count reached.

use super::Args;
use super::report::json_number;
use photon_maps::render::{AutoPhotons, AutoPhotonsReport, EstimatorKind, Progress, Rendered, Renderer};
use photon_maps::trace::Partitioned;

/// The options of an automatic photon count.
#[derive(clap::Args, Debug)]
pub struct AutoArgs {
    /// Single-pass modes that read photons: choose the photon count automatically. Photons are
    /// traced in doubling batches from --photons until the irradiance estimated at probe points
    /// changes less than this relative threshold (0 < t < 1, e.g. 0.02) between batches; the
    /// render is the bits of one with --photons set to the count reached.
    #[arg(long, value_name = "THRESHOLD")]
    pub auto_photons: Option<f64>,
    /// With --auto-photons: the most photon paths (no batch goes past it) [default: 2^25].
    #[arg(long, requires = "auto_photons")]
    pub auto_max_photons: Option<u32>,
    /// With --auto-photons: the most batches (at least 2) [default: 12].
    #[arg(long, requires = "auto_photons")]
    pub auto_max_batches: Option<u32>,
}

impl AutoArgs {
    /// The typed settings of `--auto-photons`, checked (`None` without it).
    pub fn settings(&self, start: u32) -> Result<Option<AutoPhotons>, String> {
        let Some(threshold) = self.auto_photons else {
            return Ok(None);
        };
        let defaults = AutoPhotons::new(start, threshold);
        let auto = AutoPhotons {
            max_photons: self.auto_max_photons.unwrap_or(defaults.max_photons),
            max_batches: self.auto_max_batches.unwrap_or(defaults.max_batches),
            ..defaults
        };
        auto.validate().map_err(|e| format!("--auto-photons: {e}"))?;
        Ok(Some(auto))
    }
}

/// Refuses `--auto-photons` where it does not apply among the single-pass photon modes:
/// `--compare`, `--load-cache` (it traces nothing) and fly-throughs.
pub fn refuse_conflicts(args: &Args) -> Result<(), String> {
    if args.auto.auto_photons.is_none() {
        return Ok(());
    }
    let conflict = if args.compare {
        "--compare"
    } else if args.load_cache.is_some() {
        "--load-cache (a loaded cache traces nothing)"
    } else if args.frames.is_some() || args.orbit.is_some() {
        "--frames and --orbit"
    } else {
        return Ok(());
    };
    Err(format!("--auto-photons does not apply with {conflict}: drop one"))
}

/// The render of `partitioned` with the photon count `--auto-photons` chooses, or with
/// `--photons` without it.
pub fn render(
    args: &Args,
    renderer: &Renderer<EstimatorKind>,
    partitioned: &Partitioned,
    progress: &dyn Progress,
) -> Result<Rendered, String> {
    match args.auto.settings(args.photons)? {
        Some(auto) => renderer.render_auto(partitioned, &auto, progress),
        None => renderer.render(partitioned, progress),
    }
    .map_err(|e| e.to_string())
}

/// The summary's clause: the count chosen, why it stopped, and each batch's change.
pub fn summary(report: &Option<AutoPhotonsReport>) -> String {
    let Some(r) = report else {
        return String::new();
    };
    let changes: Vec<String> = r
        .batches
        .iter()
        .map(|b| match b.change {
            Some(c) => format!("{} {:.4}", b.photons, c),
            None => format!("{} -", b.photons),
        })
        .collect();
    format!(
        ", auto photons {} ({} below {} over {} probes; batch change: {})",
        r.photons,
        if r.converged {
            "change"
        } else {
            "stopped by a bound, change not"
        },
        r.threshold,
        r.probes,
        changes.join(", ")
    )
}

/// The JSON member `"auto_photons": {...}, ` (empty without it).
pub fn json(report: &Option<AutoPhotonsReport>) -> String {
    let Some(r) = report else {
        return String::new();
    };
    let batches: Vec<String> = r
        .batches
        .iter()
        .map(|b| {
            let change = b.change.map_or("null".to_string(), json_number);
            format!("{{\"photons\": {}, \"change\": {change}}}", b.photons)
        })
        .collect();
    format!(
        "\"auto_photons\": {{\"photons\": {}, \"threshold\": {}, \"converged\": {}, \"probes\": {}, \"batches\": [{}]}}, ",
        r.photons,
        json_number(r.threshold),
        r.converged,
        r.probes,
        batches.join(", ")
    )
}
