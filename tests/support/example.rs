//! Running the built examples from tests: `cargo test` builds the examples next to the test
//! binaries; a test built alone (`cargo test --test NAME`) may not find them, and then says so
//! and skips.

#![allow(dead_code)]

use std::path::PathBuf;
use std::process::{Command, Output};

/// The built example `name`, `target/<profile>/examples/<name>`, if it is there; otherwise
/// prints that the test skips.
pub fn example(name: &str) -> Option<PathBuf> {
    let exe = std::env::current_exe().ok()?;
    let path = exe
        .parent()?
        .parent()?
        .join("examples")
        .join(format!("{name}{}", std::env::consts::EXE_SUFFIX));
    if path.is_file() {
        Some(path)
    } else {
        eprintln!("{name} example not built next to this test; skipping (run `cargo test --workspace`)");
        None
    }
}

/// The render example run with `args` (`None`: not built, the test skips).
pub fn run(args: &[&str]) -> Option<Output> {
    let exe = example("render")?;
    Some(Command::new(exe).args(args).output().expect("the example starts"))
}

/// Asserts a refusal: non-zero exit, no panic, one line on stderr naming `needle` (in any
/// case), nothing rendered (no summary line on stdout).
pub fn assert_refused(args: &[&str], output: &Output, needle: &str) {
    let stderr = String::from_utf8_lossy(&output.stderr);
    let stdout = String::from_utf8_lossy(&output.stdout);
    assert!(!output.status.success(), "{args:?} succeeded");
    assert!(!stderr.contains("panicked"), "{args:?} panicked: {stderr}");
    assert_eq!(
        stderr.trim().lines().count(),
        1,
        "{args:?}: not one line: {stderr}"
    );
    assert!(
        stderr.to_lowercase().contains(&needle.to_lowercase()),
        "{args:?}: {stderr:?} does not name {needle:?}"
    );
    assert!(
        stdout.trim().is_empty(),
        "{args:?} rendered before refusing: {stdout}"
    );
}

/// Asserts a run succeeded, showing its stderr otherwise.
pub fn assert_ok(args: &[&str], output: &Output) {
    assert!(
        output.status.success(),
        "{args:?}: {}",
        String::from_utf8_lossy(&output.stderr)
    );
}
