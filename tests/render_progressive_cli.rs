//! The render example's progressive shards as a user runs them: two shards merged with
//! `--merge` give the file one run of all their passes gives, byte for byte, the stats JSON
//! records the pass range, and shards of other settings are refused with one line naming the
//! problem.
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
    let (full_shard, merged_shard) = (Shard::read_exr(&full).unwrap(), Shard::read_exr(&merged).unwrap());
    assert_eq!(merged_shard.pass_range(), 0..5);
    assert_eq!(merged_shard.mean(), full_shard.mean());
    // The same file, byte for byte (mean, sums and header), and the same preview.
    assert!(
        std::fs::read(&merged).unwrap() == std::fs::read(&full).unwrap(),
        "merged EXR differs"
    );
    let png = |p: &Path| std::fs::read(p.with_extension("png")).unwrap();
    assert!(png(&merged) == png(&full), "merged PNG differs");

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
        ([&a, &a], "given twice"),
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
