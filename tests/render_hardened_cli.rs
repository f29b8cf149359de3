//! The render example against hostile options: limits refused before rendering with one line
//! naming the problem, outputs that cannot name one file, and a failed write that leaves the
//! previous file (or the link naming it) as it was.
//!
//! The example is built next to the test binaries by `cargo test --workspace`; when it is
//! missing the tests say so and skip.

#[path = "support/scratch.rs"]
mod scratch;
use scratch::Scratch;

#[path = "support/example.rs"]
mod example;

use example::{assert_refused, example, run};
use std::path::Path;
use std::process::{Command, Output};

#[test]
fn limits_are_refused_before_rendering_with_one_line() {
    let scratch = Scratch::new("limits");
    let out = scratch.path("x.exr");
    let cases: [(&[&str], &str); 6] = [
        (&["--threads", "65536"], "threads"),
        (&["--threads", "65535"], "threads"),
        (&["--photons", "4294967295"], "photon"),
        (&["--size", "16384x16384"], "pixels"),
        (&["--spp", "4294967295"], "samples"),
        // The four cells fit, the 2×2 grid does not: refused before the four renders.
        (
            &["--compare", "--size", "4097x4097", "--photons", "100"],
            "--compare",
        ),
    ];
    for (args, needle) in cases {
        let mut args = args.to_vec();
        args.extend(["--out", &out]);
        let Some(output) = run(&args) else { return };
        assert_refused(&args, &output, needle);
    }
}

#[test]
fn a_nan_exposure_and_a_folder_as_out_are_refused() {
    let scratch = Scratch::new("smaller");
    let out = scratch.path("x.exr");
    let args = [
        "--exposure",
        "nan",
        "--size",
        "8x8",
        "--photons",
        "100",
        "--out",
        &out,
    ];
    let Some(output) = run(&args) else { return };
    assert_refused(&args, &output, "exposure");
    assert!(!Path::new(&out).exists());

    let folder = scratch.path("folder");
    std::fs::create_dir(&folder).unwrap();
    let args = ["--size", "8x8", "--photons", "100", "--out", &folder];
    let Some(output) = run(&args) else { return };
    assert_refused(&args, &output, "folder");
    assert!(!scratch.0.join("folder.exr").exists(), "a sibling was written");
}

#[test]
fn stats_json_naming_an_image_output_is_refused_and_the_image_kept() {
    let scratch = Scratch::new("same");
    let out = scratch.path("x.exr");
    std::fs::write(&out, b"previous image").unwrap();
    for stats in [out.clone(), scratch.path("x.png")] {
        let args = [
            "--size",
            "8x8",
            "--photons",
            "100",
            "--out",
            &out,
            "--stats-json",
            &stats,
        ];
        let Some(output) = run(&args) else { return };
        assert_refused(&args, &output, "same file");
        assert_eq!(std::fs::read(&out).unwrap(), b"previous image");
    }
    // Through a link to the image, too.
    #[cfg(unix)]
    {
        let link = scratch.path("stats.json");
        std::os::unix::fs::symlink(&out, &link).unwrap();
        let args = [
            "--size",
            "8x8",
            "--photons",
            "100",
            "--out",
            &out,
            "--stats-json",
            &link,
        ];
        let Some(output) = run(&args) else { return };
        assert_refused(&args, &output, "same file");
        assert_eq!(std::fs::read(&out).unwrap(), b"previous image");
    }
}

/// Runs the example with files limited to 2 KiB (`ulimit -f`; SIGXFSZ ignored so the write
/// fails with EFBIG instead of killing the process).
#[cfg(unix)]
fn run_with_small_file_limit(args: &[&str]) -> Option<Output> {
    let exe = example("render")?;
    let script = "trap '' XFSZ; ulimit -f 2; exec \"$@\"";
    Some(
        Command::new("sh")
            .args(["-c", script, "sh"])
            .arg(exe)
            .args(args)
            .output()
            .expect("sh starts"),
    )
}

#[cfg(unix)]
#[test]
fn a_failed_write_leaves_the_previous_file_and_link_intact() {
    let scratch = Scratch::new("failed-write");
    let previous = b"previous image, not to be lost".as_slice();
    // A regular file, and a link to another one, each named as the output.
    let out = scratch.path("x.exr");
    std::fs::write(&out, previous).unwrap();
    let real = scratch.path("real.exr");
    std::fs::write(&real, previous).unwrap();
    let link = scratch.path("link.exr");
    std::os::unix::fs::symlink("real.exr", &link).unwrap();
    for target in [&out, &link] {
        let args = ["--size", "96x96", "--photons", "2000", "--out", target.as_str()];
        let Some(output) = run_with_small_file_limit(&args) else {
            return;
        };
        let stderr = String::from_utf8_lossy(&output.stderr);
        assert!(
            !output.status.success(),
            "a write past the file size limit succeeded"
        );
        assert!(!stderr.contains("panicked"), "{stderr}");
        assert_eq!(stderr.trim().lines().count(), 1, "{stderr}");
        assert_eq!(
            std::fs::read(target).ok().as_deref(),
            Some(previous),
            "{target} lost by a failed write: {stderr}"
        );
    }
    assert!(std::fs::symlink_metadata(&link).unwrap().file_type().is_symlink());
    let left: Vec<_> = std::fs::read_dir(&scratch.0)
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .filter(|n| n.starts_with('.'))
        .collect();
    assert!(left.is_empty(), "temporary files left: {left:?}");
}
