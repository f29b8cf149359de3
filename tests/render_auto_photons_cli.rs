//! The render example's `--auto-photons THRESHOLD`: the image is the bytes of a plain run with
//! the count reached, which the JSON states with each batch's change; refused where it does
//! not apply and for thresholds outside (0, 1).

#[path = "support/scratch.rs"]
mod scratch;
use scratch::Scratch;
#[path = "support/example.rs"]
mod example;
use example::{assert_ok, assert_refused, run};

#[test]
fn the_auto_count_renders_the_bytes_of_a_plain_run_and_is_reported() {
    let dir = Scratch::new("render-auto-photons-cli");
    let (auto, plain, json) = (dir.path("auto.exr"), dir.path("plain.exr"), dir.path("a.json"));
    let common = ["--size", "12x12", "--spp", "1", "--mode", "final-gather"];
    let mut args = common.to_vec();
    args.extend([
        "--photons",
        "4000",
        "--auto-photons",
        "0.5",
        "--auto-max-batches",
        "3",
        "--out",
        &auto,
        "--stats-json",
        &json,
    ]);
    let Some(output) = run(&args) else { return };
    assert_ok(&args, &output);
    assert!(String::from_utf8_lossy(&output.stdout).contains("auto photons"));
    let text = std::fs::read_to_string(&json).unwrap();
    let chosen: u32 = text
        .split("\"auto_photons\": {\"photons\": ")
        .nth(1)
        .and_then(|rest| rest.split(',').next())
        .and_then(|n| n.parse().ok())
        .unwrap_or_else(|| panic!("no auto_photons in {text}"));
    assert!([8_000, 16_000].contains(&chosen), "{text}");
    assert!(
        text.contains("\"batches\": [{\"photons\": 4000, \"change\": null}"),
        "{text}"
    );
    let count = chosen.to_string();
    let mut args = common.to_vec();
    args.extend(["--photons", &count, "--out", &plain]);
    let Some(output) = run(&args) else { return };
    assert_ok(&args, &output);
    assert!(std::fs::read(&auto).unwrap() == std::fs::read(&plain).unwrap());
}

#[test]
fn auto_photons_is_refused_where_it_does_not_apply() {
    let dir = Scratch::new("render-auto-photons-refused");
    let out = dir.path("r.exr");
    let cases: Vec<(Vec<&str>, &str)> = vec![
        (
            vec!["--mode", "path-trace", "--auto-photons", "0.1"],
            "--auto-photons",
        ),
        (vec!["--mode", "sppm", "--auto-photons", "0.1"], "--auto-photons"),
        (
            vec!["--mode", "progressive", "--auto-photons", "0.1"],
            "--auto-photons",
        ),
        (vec!["--compare", "--auto-photons", "0.1"], "--compare"),
        (vec!["--auto-photons", "0"], "threshold"),
        (vec!["--auto-photons", "1"], "threshold"),
        (vec!["--auto-photons", "NaN"], "threshold"),
        (
            vec!["--auto-photons", "0.1", "--auto-max-batches", "1"],
            "batches",
        ),
        (
            vec!["--auto-photons", "0.1", "--auto-max-photons", "10"],
            "maximum",
        ),
    ];
    for (args, needle) in cases {
        let mut all = vec!["--size", "8x8", "--out", &out];
        all.extend(args.iter().copied());
        let Some(output) = run(&all) else { return };
        assert_refused(&all, &output, needle);
    }
}
