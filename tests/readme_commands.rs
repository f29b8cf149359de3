//! The README's commands that write files, at their smallest sizes, run in a scratch copy of
//! the repository's tracked files: each writes under `target/` (where the README says) and
//! changes no tracked file (issue 32: `convergence --quick` rewrote docs/convergence.md and
//! its charts, because `--out-dir` defaulted to `docs`).

#[path = "support/example.rs"]
mod example;
#[path = "support/scratch.rs"]
mod scratch;
#[path = "support/tracked.rs"]
mod tracked;

use std::process::Command;

/// Runs example `name` with `args` in a scratch copy of the repository and checks that it
/// succeeds, writes each of `expected` (relative to the copy) and changes no tracked file,
/// in the copy or in the repository.
fn writes_only_under_target(label: &str, name: &str, args: &[&str], expected: &[&str]) {
    let Some(exe) = example::example(name) else { return };
    let dir = scratch::Scratch::new(label);
    let Some(copy) = tracked::Copy::new(&dir.0) else {
        return;
    };
    let before = tracked::snapshot();
    let output = Command::new(&exe)
        .args(args)
        .current_dir(&copy.dir)
        .output()
        .expect("the example starts");
    example::assert_ok(args, &output);
    let differing = copy.differing();
    assert!(
        differing.is_empty(),
        "{name} {args:?} changed tracked files: {differing:?}"
    );
    for file in expected {
        assert!(
            copy.dir.join(file).is_file(),
            "{name} {args:?} did not write {file}"
        );
        assert!(file.starts_with("target/"), "{file} is not under target/");
    }
    if let (Some(before), Some(after)) = (before, tracked::snapshot()) {
        let changed = tracked::changed(&before, &after);
        assert!(
            changed.is_empty(),
            "{name} {args:?} changed the repository: {changed:?}"
        );
    }
}

/// `cargo run --release --example render` (and its `--mode photon-map` view), small.
#[test]
fn the_default_render_writes_under_target() {
    for (label, mode) in [
        ("render-default", None),
        ("render-photon-map", Some("photon-map")),
    ] {
        let mut args = vec!["--size", "24x24", "--photons", "2000"];
        args.extend(mode.iter().flat_map(|m| ["--mode", m]));
        writes_only_under_target(
            label,
            "render",
            &args,
            &["target/out/cornell-box.exr", "target/out/cornell-box.png"],
        );
    }
}

/// `cargo run --release --example render -- --compare --scene lit-unlit-rooms`, small.
#[test]
fn the_compare_grid_writes_under_target() {
    writes_only_under_target(
        "render-compare",
        "render",
        &[
            "--compare",
            "--scene",
            "lit-unlit-rooms",
            "--size",
            "24x24",
            "--photons",
            "2000",
        ],
        &["target/out/lit-unlit-rooms.exr", "target/out/lit-unlit-rooms.png"],
    );
}

/// `cargo run --release --example convergence` without `--out-dir`, quick and on one scene.
#[test]
fn the_convergence_study_writes_under_target() {
    writes_only_under_target(
        "convergence",
        "convergence",
        &[
            "--quick",
            "--scenes",
            "cornell-box",
            "--methods",
            "path-trace,final-gather",
            "--no-per-pass",
        ],
        &[
            "target/convergence/convergence.md",
            "target/convergence/images/convergence-cornell-box.png",
        ],
    );
}

/// `cargo run --release --example results` without `--out-dir`, quick.
#[test]
fn the_results_write_under_target() {
    writes_only_under_target(
        "results",
        "results",
        &["--quick", "--ref-spp-scale", "0.05"],
        &["target/results-quick/results.md"],
    );
}

/// `--extend-references` writes into the references, so it needs their folder named.
#[test]
fn extending_references_needs_their_folder_named() {
    let Some(exe) = example::example("convergence") else {
        return;
    };
    let dir = scratch::Scratch::new("extend");
    let Some(copy) = tracked::Copy::new(&dir.0) else {
        return;
    };
    let output = Command::new(&exe)
        .args(["--extend-references", "1", "--scenes", "cornell-box"])
        .current_dir(&copy.dir)
        .output()
        .expect("the example starts");
    let stderr = String::from_utf8_lossy(&output.stderr);
    assert!(!output.status.success(), "extended unnamed references: {stderr}");
    assert!(stderr.contains("--reference-dir"), "{stderr}");
    assert!(copy.differing().is_empty(), "{:?}", copy.differing());
}
