//! The render example's `--contact-gap`: the contact partition's gap as a fraction of the
//! scene's diagonal. A smaller gap finds fewer near-contacts and makes fewer maps; values
//! outside (0, 0.1] and runs that build no contact maps refuse it with one line.

#[path = "support/scratch.rs"]
mod scratch;
use scratch::Scratch;

#[path = "support/example.rs"]
mod example;
use example::{assert_ok, assert_refused, run};

/// The number after the first `key` (with its quotes and colon) in the run's `--stats-json`.
fn number_after(json: &str, key: &str) -> f64 {
    let text = std::fs::read_to_string(json).unwrap();
    let key = format!("\"{key}\": ");
    let at = text.find(&key).unwrap_or_else(|| panic!("{key} in {text}")) + key.len();
    text[at..]
        .split([',', '}'])
        .next()
        .unwrap()
        .trim()
        .parse()
        .unwrap()
}

/// The map count the run's `--stats-json` reports.
fn map_count(json: &str) -> u64 {
    number_after(json, "map_count") as u64
}

#[test]
fn a_smaller_contact_gap_makes_fewer_maps_and_bad_gaps_are_refused() {
    let dir = Scratch::new("contact-gap");
    // solid-rooms-gap: a wall 0.1 % of the diagonal short of floor and ceiling, which the
    // default gap (0.2 %) counts as touching and a gap of 0.01 % does not.
    let count = |gap: Option<&str>, name: &str| -> Option<u64> {
        let (out, json) = (
            dir.path(&format!("{name}.exr")),
            dir.path(&format!("{name}.json")),
        );
        let mut args = vec![
            "--scene",
            "solid-rooms-gap",
            "--mode",
            "photon-map",
            "--size",
            "8x8",
            "--photons",
            "2000",
            "--out",
            &out,
            "--stats-json",
            &json,
        ];
        if let Some(gap) = gap {
            args.extend(["--contact-gap", gap]);
        }
        let output = run(&args)?;
        assert_ok(&args, &output);
        // The set-up's partition time holds the split's (cutting, rebuilding, the map fill),
        // whose steps make up its total.
        let partition = number_after(&json, "partition");
        let split = number_after(&json, "seconds");
        let steps = [
            "faces",
            "meetings",
            "cutting",
            "copies_and_sealing",
            "rebuild",
            "faces_as_given",
            "fill",
        ];
        let summed: f64 = steps.iter().map(|k| number_after(&json, k)).sum();
        assert!(
            partition >= split && split > 0.0,
            "partition {partition} s, split {split} s"
        );
        assert!(
            (summed - split).abs() <= 1e-9 * split.max(1.0),
            "steps {summed} s, split {split} s"
        );
        Some(map_count(&json))
    };
    let Some(default) = count(None, "default") else {
        return;
    };
    let fine = count(Some("0.0001"), "fine").unwrap();
    assert!(
        fine < default,
        "--contact-gap 0.0001: {fine} maps, default {default}"
    );
    let same = count(Some("0.002"), "same").unwrap();
    assert_eq!(same, default, "the default is 0.002");

    let out = dir.path("refused.exr");
    for gap in ["0", "-0.001", "NaN", "0.5", "inf"] {
        let given = format!("--contact-gap={gap}");
        let args = ["--scene", "cornell-box", "--size", "4x4", "--out", &out, &given];
        let Some(output) = run(&args) else { return };
        assert_refused(&args, &output, "--contact-gap");
    }
    for other in [
        &["--maps", "crease"][..],
        &["--mode", "path-trace"][..],
        &["--mode", "sppm", "--passes", "1"][..],
    ] {
        let mut args = vec![
            "--scene",
            "cornell-box",
            "--size",
            "4x4",
            "--out",
            &out,
            "--contact-gap",
            "0.001",
        ];
        args.extend_from_slice(other);
        let Some(output) = run(&args) else { return };
        assert_refused(&args, &output, "--contact-gap");
    }
}
