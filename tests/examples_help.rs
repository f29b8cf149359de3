//! Every example answers `--help` at once and writes nothing: not in the folder it runs in,
//! and not in the repository's tracked files (issue 32: `scale --help` ran its minute-long
//! benchmark, and a README command rewrote docs/).

#[path = "support/example.rs"]
mod example;
#[path = "support/scratch.rs"]
mod scratch;
#[path = "support/tracked.rs"]
mod tracked;

use std::process::Command;
use std::time::{Duration, Instant};

const EXAMPLES: [&str; 6] = [
    "render",
    "results",
    "scale",
    "convergence",
    "floor_band",
    "cache_query",
];

#[test]
fn every_example_answers_help_at_once_and_writes_nothing() {
    let before = tracked::snapshot();
    for name in EXAMPLES {
        let Some(exe) = example::example(name) else { return };
        let dir = scratch::Scratch::new(name);
        let start = Instant::now();
        let output = Command::new(&exe)
            .arg("--help")
            .current_dir(&dir.0)
            .output()
            .expect("the example starts");
        let took = start.elapsed();
        let stdout = String::from_utf8_lossy(&output.stdout);
        assert!(
            output.status.success(),
            "{name} --help failed: {}",
            String::from_utf8_lossy(&output.stderr)
        );
        assert!(
            stdout.contains("Usage:"),
            "{name} --help printed no usage: {stdout}"
        );
        assert!(
            took < Duration::from_secs(5),
            "{name} --help took {took:?}: it ran instead of answering"
        );
        let written: Vec<_> = std::fs::read_dir(&dir.0)
            .unwrap()
            .flatten()
            .map(|e| e.path())
            .collect();
        assert!(written.is_empty(), "{name} --help wrote {written:?}");
    }
    if let (Some(before), Some(after)) = (before, tracked::snapshot()) {
        let changed = tracked::changed(&before, &after);
        assert!(changed.is_empty(), "--help changed tracked files: {changed:?}");
    }
}

/// What the guide promises of a misspelt value: the list of possible values, and clap's
/// "a similar value exists" tip when one is close.
#[test]
fn a_close_misspelling_gets_the_list_and_a_suggestion() {
    let Some(output) = example::run(&["--maps", "creese"]) else {
        return;
    };
    let stderr = String::from_utf8_lossy(&output.stderr);
    assert!(!output.status.success(), "--maps creese was accepted");
    assert!(
        stderr.contains("[possible values: single, crease, contact]"),
        "{stderr}"
    );
    assert!(stderr.contains("a similar value exists: 'crease'"), "{stderr}");
}
