//! The render example's progressive shards as a user runs them: two shards merged with
//! `--merge` equal one run of all their passes (within 1e-4), the stats JSON records the pass
//! range, and shards of other settings are refused with one line naming the problem.
//!
//! Like `render_example_cli`, the test skips when the example was not built beside it.

#[path = "support/example.rs"]
mod example;

use example::run;
use photon_maps::render::progressive::Shard;
use std::path::{Path, PathBuf};

fn shard(dir: &Path, name: &str, extra: &[&str]) -> Option<PathBuf> {
    let path = dir.join(format!("{name}.exr"));
    let mut args = vec![
        "--scene",
        "accordion",
        "--mode",
        "progressive",
        "--size",
        "40x24",
        "--photons",
        "4000",
        "--out",
        path.to_str().unwrap(),
    ];
    args.extend_from_slice(extra);
    let output = run(&args)?;
    assert!(
        output.status.success(),
        "{}",
        String::from_utf8_lossy(&output.stderr)
    );
    Some(path)
}

#[test]
fn cli_shards_merge_into_the_single_run_and_mismatches_are_refused() {
    let dir = std::env::temp_dir().join(format!("pm-cli-shards-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let json = dir.join("full.json");
    let Some(full) = shard(
        &dir,
        "full",
        &["--passes", "5", "--stats-json", json.to_str().unwrap()],
    ) else {
        return;
    };
    let text = std::fs::read_to_string(&json).unwrap();
    assert!(text.contains("\"first_pass\": 0, \"end_pass\": 5"), "{text}");
    let a = shard(&dir, "a", &["--passes", "2"]).unwrap();
    let b = shard(&dir, "b", &["--first-pass", "2", "--passes", "3"]).unwrap();
    let merged = dir.join("merged.exr");
    let output = run(&[
        "--merge",
        b.to_str().unwrap(),
        a.to_str().unwrap(),
        "--out",
        merged.to_str().unwrap(),
    ])
    .unwrap();
    assert!(
        output.status.success(),
        "{}",
        String::from_utf8_lossy(&output.stderr)
    );
    let (full_shard, merged) = (Shard::read_exr(&full).unwrap(), Shard::read_exr(&merged).unwrap());
    assert_eq!(merged.pass_range(), 0..5);
    for (m, f) in merged.mean().pixels().iter().zip(full_shard.mean().pixels()) {
        for (m, f) in m.to_array().into_iter().zip(f.to_array()) {
            assert!((m - f).abs() <= 1e-4 * f.abs().max(1e-6), "{m} vs {f}");
        }
    }

    let other = shard(
        &dir,
        "other",
        &["--first-pass", "5", "--passes", "1", "--k", "20"],
    )
    .unwrap();
    // Shadow rays for direct light make another image: such a shard does not merge either.
    let shadow = shard(
        &dir,
        "shadow",
        &["--first-pass", "5", "--passes", "1", "--direct", "shadow-rays"],
    )
    .unwrap();
    let bad = dir.join("bad.exr");
    for (inputs, needle) in [
        ([&a, &other], "settings"),
        ([&a, &shadow], "settings"),
        ([&a, &a], "overlap"),
        ([&a, &full], "overlap"),
    ] {
        let output = run(&[
            "--merge",
            inputs[0].to_str().unwrap(),
            inputs[1].to_str().unwrap(),
            "--out",
            bad.to_str().unwrap(),
        ])
        .unwrap();
        let stderr = String::from_utf8_lossy(&output.stderr);
        assert!(!output.status.success());
        assert_eq!(stderr.trim().lines().count(), 1, "{stderr}");
        assert!(stderr.contains(needle), "{stderr:?} does not name {needle}");
    }
    std::fs::remove_dir_all(&dir).ok();
}
