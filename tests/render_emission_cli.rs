//! The render example's `--emission camera`: reported in the summary and the JSON (paths
//! emitted, paths traced on, the guide's figures); refused in path-trace mode, its guide
//! options refused without it, and bad guide options refused with what was wrong.

#[path = "support/scratch.rs"]
mod scratch;
use scratch::Scratch;
#[path = "support/example.rs"]
mod example;
use example::{assert_ok, assert_refused, run};

/// The number after `"key": ` in `json`.
fn number(json: &str, key: &str) -> f64 {
    json.split(&format!("\"{key}\": "))
        .nth(1)
        .and_then(|rest| rest.split([',', '}']).next())
        .and_then(|n| n.trim().parse().ok())
        .unwrap_or_else(|| panic!("no {key} in {json}"))
}

#[test]
fn camera_driven_emission_is_reported() {
    let dir = Scratch::new("render-emission-cli");
    let (out, json) = (dir.path("c.exr"), dir.path("c.json"));
    let args = [
        "--scene",
        "doorway-rooms-4",
        "--maps",
        "crease",
        "--mode",
        "photon-map",
        "--size",
        "16x12",
        "--photons",
        "5000",
        "--emission",
        "camera",
        "--guide-pilot",
        "4096",
        "--out",
        &out,
        "--stats-json",
        &json,
    ];
    let Some(output) = run(&args) else { return };
    assert_ok(&args, &output);
    assert!(String::from_utf8_lossy(&output.stdout).contains("camera-driven:"));
    let text = std::fs::read_to_string(&json).unwrap();
    assert!(text.contains("\"emission\": \"camera\""), "{text}");
    let (emitted, traced) = (number(&text, "photons_emitted"), number(&text, "photons_traced"));
    assert!(traced < 0.6 * emitted, "{text}");
    assert!((traced / 5000.0 - 1.0).abs() < 0.1, "{text}");
    assert_eq!(number(&text, "pilot_photons"), 4096.0);
    let keep = number(&text, "keep_rate");
    assert!(keep > 0.125 && keep < 0.6, "{text}");
}

#[test]
fn camera_driven_emission_is_refused_where_it_does_not_apply() {
    let base = [
        "--scene",
        "doorway-rooms-2",
        "--size",
        "8x8",
        "--out",
        "/nonexistent/never.exr",
    ];
    let mut args = base.to_vec();
    args.extend(["--mode", "path-trace", "--emission", "camera"]);
    let Some(output) = run(&args) else { return };
    assert_refused(&args, &output, "--emission does not apply to --mode path-trace");
    let mut args = base.to_vec();
    args.extend(["--guide-floor", "0.5"]);
    let Some(output) = run(&args) else { return };
    assert_refused(&args, &output, "--guide-floor does not apply");
    let mut args = base.to_vec();
    args.extend(["--emission", "camera", "--guide-floor", "0"]);
    let Some(output) = run(&args) else { return };
    assert_refused(&args, &output, "guide floor 0 is outside (0, 1]");
    let mut args = base.to_vec();
    args.extend([
        "--emission",
        "camera",
        "--auto-photons",
        "0.5",
        "--mode",
        "final-gather",
    ]);
    let Some(output) = run(&args) else { return };
    assert_refused(&args, &output, "automatic photon count");
}
