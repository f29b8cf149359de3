//! The render example as a user runs it: bad input exits non-zero with one line naming the
//! problem (never a panic), and one or two threads write byte-identical EXR files.
//!
//! `cargo test` builds the examples next to the test binaries; when this test is built alone
//! (`cargo test --test render_example_cli`) the example may be missing, and the test says so
//! and skips.

use std::path::PathBuf;
use std::process::{Command, Output};

/// The built example, `target/<profile>/examples/render`, if it is there.
fn example() -> Option<PathBuf> {
    let exe = std::env::current_exe().ok()?;
    let profile_dir = exe.parent()?.parent()?;
    let path = profile_dir
        .join("examples")
        .join(format!("render{}", std::env::consts::EXE_SUFFIX));
    path.is_file().then_some(path)
}

fn run(args: &[&str]) -> Option<Output> {
    let Some(exe) = example() else {
        eprintln!("render example not built next to this test; skipping (run `cargo test --workspace`)");
        return None;
    };
    Some(Command::new(exe).args(args).output().expect("the example starts"))
}

fn scratch_dir(name: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("pm-cli-{name}-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

#[test]
fn bad_input_exits_non_zero_with_one_line_naming_the_problem() {
    let dir = scratch_dir("bad");
    let out = dir.join("x.exr");
    let out = out.to_str().unwrap();
    let blocker = dir.join("a-file");
    std::fs::write(&blocker, b"not a folder").unwrap();
    let under_file = blocker.join("x.exr");
    let cases: [(&[&str], &str); 7] = [
        (&["--scene", "no-such-scene", "--out", out], "no-such-scene"),
        (&["--scene", "/no/such/file.gltf", "--out", out], "file.gltf"),
        (&["--k", "0", "--out", out], "k"),
        (&["--photons", "0", "--out", out], "photon"),
        (&["--size", "0x10", "--out", out], "0x10"),
        (&["--maps", "diagonal", "--out", out], "diagonal"),
        (&["--out", under_file.to_str().unwrap()], "a-file"),
    ];
    for (args, needle) in cases {
        let Some(output) = run(args) else { return };
        let stderr = String::from_utf8_lossy(&output.stderr);
        assert!(!output.status.success(), "{args:?} succeeded");
        assert!(!stderr.contains("panicked"), "{args:?} panicked: {stderr}");
        assert_eq!(
            stderr.trim().lines().count(),
            1,
            "{args:?}: not one line: {stderr}"
        );
        assert!(
            stderr.to_lowercase().contains(needle),
            "{args:?}: {stderr:?} does not name {needle:?}"
        );
    }
    std::fs::remove_dir_all(&dir).ok();
}

#[test]
fn one_and_two_threads_write_byte_identical_exr_files() {
    let dir = scratch_dir("threads");
    let mut files = Vec::new();
    for threads in ["1", "2"] {
        let path = dir.join(format!("t{threads}.exr"));
        let args = [
            "--scene",
            "cornell-box",
            "--size",
            "48x32",
            "--photons",
            "5000",
            "--threads",
            threads,
            "--out",
            path.to_str().unwrap(),
        ];
        let Some(output) = run(&args) else { return };
        assert!(
            output.status.success(),
            "{}",
            String::from_utf8_lossy(&output.stderr)
        );
        files.push(std::fs::read(&path).unwrap());
    }
    assert!(files[0].len() > 1000, "an EXR was written");
    assert!(files[0] == files[1], "threads 1 and 2 wrote different EXR files");
    std::fs::remove_dir_all(&dir).ok();
}
