//! The render example's progressive, SPPM and merge modes and its outputs against hostile
//! options, run as a user would: out-of-range times and passes, FIFOs and repeated shards,
//! outputs that name an input or each other in every mode (links, dangling links, PNG
//! siblings), permissions, options the mode would ignore, `--help`, and the same bytes from
//! the same inputs at any thread count.
//!
//! The example is built next to the test binaries by `cargo test --workspace`; when it is
//! missing the tests say so and skip.

#[path = "support/scratch.rs"]
mod scratch;
use scratch::Scratch;

#[path = "support/example.rs"]
mod example;

use example::{assert_ok, assert_refused, example, run};
use std::path::Path;
use std::process::{Command, Output, Stdio};
use std::time::{Duration, Instant};

/// Runs the example, killing it after `limit`: `None` when it had to be killed.
fn run_within(args: &[&str], limit: Duration) -> Option<Option<Output>> {
    let exe = example("render")?;
    let mut child = Command::new(exe)
        .args(args)
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .expect("the example starts");
    let start = Instant::now();
    while start.elapsed() < limit {
        if child.try_wait().unwrap().is_some() {
            return Some(Some(child.wait_with_output().unwrap()));
        }
        std::thread::sleep(Duration::from_millis(20));
    }
    let _ = child.kill();
    let _ = child.wait();
    Some(None)
}

const SMALL: [&str; 4] = ["--size", "12x8", "--photons", "300"];
/// For the path tracer, which takes no photon count.
const SMALL_PT: [&str; 2] = ["--size", "12x8"];

fn with<'a>(base: &[&'a str], extra: &[&'a str]) -> Vec<&'a str> {
    let mut v = base.to_vec();
    v.extend_from_slice(extra);
    v
}

#[test]
fn times_past_the_range_of_a_duration_are_refused_with_one_line() {
    let scratch = Scratch::new("time");
    let out = scratch.path("x.exr");
    for mode in ["progressive", "sppm"] {
        for time in ["1e20", "1e300", "inf", "nan", "-1"] {
            let args = with(&SMALL, &["--mode", mode, "--time", time, "--out", &out]);
            let Some(output) = run(&args) else { return };
            assert_refused(&args, &output, "--time");
        }
    }
}

#[test]
fn per_pixel_state_past_its_limit_is_refused_before_anything_is_allocated() {
    let scratch = Scratch::new("state");
    let out = scratch.path("x.exr");
    // SPPM's 48 bytes a pixel at 8192² (3 GiB) aborted; the progressive sums are as large.
    for mode in ["sppm", "progressive"] {
        for size in ["8192x8192", "6700x6700"] {
            let args = [
                "--mode",
                mode,
                "--size",
                size,
                "--photons",
                "100",
                "--passes",
                "1",
                "--out",
                &out,
            ];
            let Some(output) = run(&args) else { return };
            assert_refused(&args, &output, "per-pixel state");
        }
    }
    assert!(!Path::new(&out).exists());
}

#[test]
fn a_late_first_pass_costs_what_an_early_one_does_and_the_last_pass_is_kept() {
    let scratch = Scratch::new("first-pass");
    let out = scratch.path("x.exr");
    // The radius schedule looped to the pass index: minutes for 10^12, for ever near u64::MAX.
    for first in ["1000000000000", "18446744073709551614"] {
        let args = with(
            &SMALL,
            &[
                "--mode",
                "progressive",
                "--passes",
                "1",
                "--first-pass",
                first,
                "--out",
                &out,
            ],
        );
        let Some(output) = run_within(&args, Duration::from_secs(20)) else {
            return;
        };
        let output = output.unwrap_or_else(|| panic!("--first-pass {first} ran past 20 s"));
        assert_ok(&args, &output);
    }
    // Past the last pass, and wrapping past u64::MAX.
    for (first, passes) in [
        ("18446744073709551614", "2"),
        ("18446744073709551615", "1"),
        ("5", "18446744073709551615"),
    ] {
        let args = with(
            &SMALL,
            &[
                "--mode",
                "progressive",
                "--passes",
                passes,
                "--first-pass",
                first,
                "--out",
                &out,
            ],
        );
        let Some(output) = run(&args) else { return };
        assert_refused(&args, &output, "last pass");
    }
}

/// Renders a progressive shard of `passes` passes from `first` into `path`.
fn shard(path: &str, first: &str, passes: &str, threads: &str) -> Option<Output> {
    let args = with(
        &SMALL,
        &[
            "--mode",
            "progressive",
            "--first-pass",
            first,
            "--passes",
            passes,
            "--threads",
            threads,
            "--out",
            path,
        ],
    );
    let output = run(&args)?;
    assert_ok(&args, &output);
    Some(output)
}

#[cfg(unix)]
#[test]
fn merge_refuses_a_fifo_and_names_a_shard_given_twice() {
    let scratch = Scratch::new("merge");
    let (a, c, out) = (
        scratch.path("a.exr"),
        scratch.path("c.exr"),
        scratch.path("m.exr"),
    );
    if shard(&a, "0", "2", "0").is_none() {
        return;
    }
    shard(&c, "4", "2", "0");
    let args = ["--merge", &c, &a, &c, "--out", &out];
    let output = run(&args).unwrap();
    assert_refused(&args, &output, "given twice");
    assert!(String::from_utf8_lossy(&output.stderr).contains("c.exr"));

    let fifo = scratch.path("f.exr");
    if Command::new("mkfifo")
        .arg(&fifo)
        .status()
        .is_ok_and(|s| s.success())
    {
        let args = ["--merge", &a, &fifo, "--out", &out];
        let output = run_within(&args, Duration::from_secs(20)).unwrap();
        let output = output.expect("--merge of a FIFO blocked for 20 s");
        assert_refused(&args, &output, "not a regular file");
    }
    assert!(!Path::new(&out).exists());
}

#[test]
fn no_output_may_name_another_or_an_input_in_any_mode() {
    let scratch = Scratch::new("collide");
    let (a, b) = (scratch.path("a.exr"), scratch.path("b.exr"));
    if shard(&a, "0", "1", "0").is_none() {
        return;
    }
    shard(&b, "1", "1", "0");
    let keep = |path: &str| std::fs::read(path).unwrap();
    let (a_bytes, b_bytes) = (keep(&a), keep(&b));
    let out = scratch.path("x.exr");
    std::fs::write(&out, b"previous image").unwrap();
    let png = scratch.path("x.png");
    let modes: [&[&str]; 4] = [
        &["--photons", "300", "--mode", "visualize"],
        &["--photons", "300", "--mode", "progressive", "--passes", "1"],
        &["--photons", "300", "--mode", "sppm", "--passes", "1"],
        &["--mode", "path-trace"],
    ];
    for mode in modes {
        // --stats-json naming the image or its PNG sibling.
        for stats in [&out, &png] {
            let args = with(&with(&SMALL_PT, mode), &["--out", &out, "--stats-json", stats]);
            let output = run(&args).unwrap();
            assert_refused(&args, &output, "same file");
            assert_eq!(keep(&out), b"previous image");
        }
    }
    // The same through --merge, which also may not replace a shard it reads.
    for (stats, needle) in [(&out, "same file"), (&png, "same file")] {
        let args = ["--merge", &a, &b, "--out", &out, "--stats-json", stats];
        let output = run(&args).unwrap();
        assert_refused(&args, &output, needle);
    }
    let b_png = scratch.path("b.png");
    for target in [&a, &b_png] {
        let args = ["--merge", &a, &b, "--out", target];
        let output = run(&args).unwrap();
        assert_refused(&args, &output, "an output may not replace an input");
    }
    let json = scratch.path("m.json");
    let args = [
        "--merge",
        &a,
        &b,
        "--out",
        &scratch.path("m.exr"),
        "--stats-json",
        &b,
    ];
    let output = run(&args).unwrap();
    assert_refused(&args, &output, "input");
    assert_eq!((keep(&a), keep(&b)), (a_bytes, b_bytes), "a shard was changed");
    assert!(!Path::new(&json).exists());

    // --stats-json naming the --scene file.
    let scene = scratch.path("scene.gltf");
    let source = Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/data/gltf");
    // Outputs are checked before the scene is read, so any file will do.
    std::fs::copy(source.join("scenes/cycle.gltf"), &scene).unwrap();
    let scene_bytes = keep(&scene);
    let g = scratch.path("g.exr");
    for mode in [
        &["--mode", "visualize"][..],
        &["--mode", "progressive", "--passes", "1"],
    ] {
        let args = with(
            &with(&SMALL, mode),
            &["--scene", &scene, "--out", &g, "--stats-json", &scene],
        );
        let output = run(&args).unwrap();
        assert_refused(&args, &output, "input");
        assert_eq!(keep(&scene), scene_bytes);
    }

    // The files a .gltf reads besides itself: its buffer and its image.
    let deps = Scratch::new("deps");
    let gltf = deps.path("s.gltf");
    std::fs::write(
        &gltf,
        r#"{"asset":{"version":"2.0"},"buffers":[{"byteLength":4,"uri":"data.bin"}],"images":[{"uri":"tex.png"}]}"#,
    )
    .unwrap();
    std::fs::write(deps.path("data.bin"), b"abcd").unwrap();
    std::fs::write(deps.path("tex.png"), b"not really a png").unwrap();
    let (bin, tex) = (deps.path("data.bin"), deps.path("tex.png"));
    for extra in [
        ["--out", g.as_str(), "--stats-json", bin.as_str()],
        ["--out", tex.as_str(), "--stats-json", json.as_str()],
    ] {
        let args = with(&with(&SMALL, &["--scene", &gltf]), &extra);
        let output = run(&args).unwrap();
        assert_refused(&args, &output, "input");
    }
    assert_eq!(std::fs::read(&bin).unwrap(), b"abcd");
    assert_eq!(std::fs::read(&tex).unwrap(), b"not really a png");

    // A dangling link naming the image as --stats-json: the file it would create is the
    // image.
    #[cfg(unix)]
    {
        let fresh = scratch.path("fresh.exr");
        let link = scratch.path("s.json");
        std::os::unix::fs::symlink("fresh.exr", &link).unwrap();
        for mode in modes {
            let args = with(&with(&SMALL_PT, mode), &["--out", &fresh, "--stats-json", &link]);
            let output = run(&args).unwrap();
            assert_refused(&args, &output, "same file");
            assert!(!Path::new(&fresh).exists());
        }
    }
}

#[cfg(unix)]
#[test]
fn a_rewrite_keeps_the_permissions_and_a_read_only_output_is_refused() {
    use std::os::unix::fs::PermissionsExt;
    let scratch = Scratch::new("permissions");
    let out = scratch.path("x.exr");
    let args = with(&SMALL, &["--mode", "progressive", "--passes", "1", "--out", &out]);
    let Some(output) = run(&args) else { return };
    assert_ok(&args, &output);
    let mode = |p: &str| std::fs::metadata(p).unwrap().permissions().mode() & 0o777;
    std::fs::set_permissions(&out, std::fs::Permissions::from_mode(0o600)).unwrap();
    assert_ok(&args, &run(&args).unwrap());
    assert_eq!(mode(&out), 0o600, "the rewrite changed the permissions");

    std::fs::set_permissions(&out, std::fs::Permissions::from_mode(0o444)).unwrap();
    let before = std::fs::read(&out).unwrap();
    let output = run(&args).unwrap();
    assert_refused(&args, &output, "read-only");
    assert_eq!(std::fs::read(&out).unwrap(), before);
    assert_eq!(mode(&out), 0o444);
}

#[test]
fn options_the_mode_would_ignore_are_refused() {
    let scratch = Scratch::new("ignored");
    let out = scratch.path("x.exr");
    let cases: [(&[&str], &str); 10] = [
        (&["--mode", "path-trace", "--estimator", "cube"], "--estimator"),
        (
            &["--mode", "sppm", "--maps", "contact", "--estimator", "ball"],
            "--maps",
        ),
        (&["--mode", "sppm", "--estimator", "ball"], "--estimator"),
        (&["--mode", "sppm", "--spp", "4"], "--samples-per-pixel"),
        (&["--mode", "visualize", "--passes", "3"], "--passes"),
        (&["--mode", "shadow-rays", "--time", "1"], "--time"),
        (&["--mode", "sppm", "--first-pass", "2"], "--first-pass"),
        (&["--mode", "path-trace", "--photons", "300"], "--photons"),
        (&["--mode", "path-trace", "--k", "20"], "--k"),
        (
            &["--scene", "accordion", "--light-units", "viewer"],
            "--light-units",
        ),
    ];
    for (extra, needle) in cases {
        let args = with(&with(&SMALL_PT, extra), &["--out", &out]);
        let Some(output) = run(&args) else { return };
        assert_refused(&args, &output, needle);
    }
    let args = [
        "--merge",
        &out,
        "--scene",
        "accordion",
        "--out",
        &scratch.path("m.exr"),
    ];
    let output = run(&args).unwrap();
    assert_refused(&args, &output, "--scene");

    // A path-traced run's figures record no maps, estimator or k.
    let json = scratch.path("x.json");
    let args = with(
        &SMALL_PT,
        &["--mode", "path-trace", "--out", &out, "--stats-json", &json],
    );
    assert_ok(&args, &run(&args).unwrap());
    let text = std::fs::read_to_string(&json).unwrap();
    for key in ["\"maps\"", "\"estimator\"", "\"k\""] {
        assert!(
            !text.contains(key),
            "{key} recorded for a path-traced run: {text}"
        );
    }
    let args = with(&SMALL, &["--out", &out, "--stats-json", &json]);
    assert_ok(&args, &run(&args).unwrap());
    assert!(
        std::fs::read_to_string(&json)
            .unwrap()
            .contains("\"maps\": \"contact\""),
        "the default partition is recorded"
    );
}

#[test]
fn help_lists_the_scale_scenes_in_one_wording_and_one_pass_is_singular() {
    let Some(output) = run(&["--help"]) else { return };
    let help = String::from_utf8_lossy(&output.stdout);
    for needle in ["split-rooms-N", "cube-field-N", "report's"] {
        assert!(help.contains(needle), "--help does not name {needle}: {help}");
    }
    assert!(!help.contains("paper's"), "{help}");

    let scratch = Scratch::new("plural");
    let out = scratch.path("x.exr");
    let args = with(&SMALL, &["--mode", "progressive", "--passes", "1", "--out", &out]);
    let output = run(&args).unwrap();
    let stdout = String::from_utf8_lossy(&output.stdout);
    assert!(stdout.contains("(1 pass)"), "{stdout}");
    assert!(!stdout.contains("1 passes"), "{stdout}");
}

#[test]
fn the_same_inputs_give_the_same_bytes_at_any_thread_count() {
    let scratch = Scratch::new("bytes");
    let files = |name: &str| -> Vec<Vec<u8>> {
        ["exr", "png"]
            .iter()
            .map(|ext| std::fs::read(scratch.0.join(format!("{name}.{ext}"))).unwrap())
            .collect()
    };
    let mut runs: Vec<(&str, Vec<&str>)> = Vec::new();
    for threads in ["1", "2", "3"] {
        runs.push((
            threads,
            vec!["--mode", "progressive", "--passes", "2", "--threads", threads],
        ));
    }
    for (i, threads) in ["1", "3"].into_iter().enumerate() {
        let name = ["sppm1", "sppm3"][i];
        runs.push((
            name,
            vec!["--mode", "sppm", "--passes", "2", "--threads", threads],
        ));
    }
    for (name, extra) in &runs {
        let out = scratch.path(&format!("{name}.exr"));
        let args = with(&with(&SMALL, extra), &["--out", &out]);
        let Some(output) = run(&args) else { return };
        assert_ok(&args, &output);
    }
    assert!(
        files("1") == files("2") && files("1") == files("3"),
        "progressive files differ"
    );
    assert!(files("sppm1") == files("sppm3"), "SPPM files differ");
    // Merges of the same shards, twice.
    let (a, b) = (scratch.path("a.exr"), scratch.path("b.exr"));
    shard(&a, "0", "1", "1");
    shard(&b, "1", "1", "2");
    for name in ["m1", "m2"] {
        let args = ["--merge", &a, &b, "--out", &scratch.path(&format!("{name}.exr"))];
        assert_ok(&args, &run(&args).unwrap());
    }
    assert!(files("m1") == files("m2"), "merged files differ");
}
