//! The convergence study as the lead runs it, on a tiny size so that it cannot rot: it writes
//! the Markdown with one table row per budget and one column per method for each scene, the
//! leak table shows the progressive renderer's dark room exactly black at every pass count and
//! SPPM's one map leaking, the charts are 800×500 PNGs, and the peak heap does not grow with
//! the pass count.
//!
//! Like the other example tests, it skips when the example was not built beside it.

#[path = "support/example.rs"]
mod example;

use example::example;
use std::process::Command;

const SCENES: [&str; 4] = ["cornell-box", "lit-unlit-rooms", "colored-rooms", "accordion"];
const FONT: &str = "/usr/share/fonts/truetype/dejavu/DejaVuSans.ttf";

#[test]
fn quick_study_writes_tables_leak_rows_and_charts() {
    let Some(exe) = example("convergence") else {
        return;
    };
    let dir = std::env::temp_dir().join(format!("pm-convergence-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    let budgets = "0.01,0.02,0.03,0.04,0.05";
    let output = Command::new(exe)
        .args([
            "--quick",
            "--size",
            "16",
            "--photons",
            "3000",
            "--budgets",
            budgets,
        ])
        .args([
            "--pass-counts",
            "1,3",
            "--reference-seconds",
            "0.2",
            "--font",
            FONT,
        ])
        .arg("--out-dir")
        .arg(&dir)
        .arg("--reference-dir")
        .arg(dir.join("reference"))
        .output()
        .expect("the example starts");
    assert!(
        output.status.success(),
        "{}",
        String::from_utf8_lossy(&output.stderr)
    );
    let md = std::fs::read_to_string(dir.join("convergence.md")).unwrap();
    for scene in SCENES {
        let section = md
            .split(&format!("## {scene}\n"))
            .nth(1)
            .unwrap_or_else(|| panic!("no section for {scene}"));
        let section = section.split("\n## ").next().unwrap();
        let header = section.lines().find(|l| l.starts_with("| seconds |")).unwrap();
        for method in [
            "path tracing",
            "SPPM",
            "progressive disc",
            "progressive cube",
            "progressive ball",
            "final gather",
            "progressive final gather",
        ] {
            assert!(header.contains(method), "{scene}: no {method} column");
        }
        for budget in budgets.split(',') {
            assert!(
                section.lines().any(|l| l.starts_with(&format!("| {budget} |"))),
                "{scene}: no row for {budget} s"
            );
        }
        if std::path::Path::new(FONT).is_file() {
            let png = dir.join(format!("images/convergence-{scene}.png"));
            let decoder = png::Decoder::new(std::io::BufReader::new(std::fs::File::open(&png).unwrap()));
            let info = decoder.read_info().unwrap().info().clone();
            assert_eq!((info.width, info.height), (800, 500), "{scene}");
            assert!(
                section.contains(&format!("(images/convergence-{scene}.png)")),
                "{scene}: chart not linked"
            );
        } else {
            eprintln!("{scene}: no font at {FONT}, so no chart was drawn; skipping the chart checks");
        }
    }
    // Leak rows: | scene | method | passes | brightest dark pixel | leak ratio |
    let leaks: Vec<Vec<&str>> = md
        .split("## Light leaked")
        .nth(1)
        .unwrap()
        .lines()
        .filter(|l| l.contains("rooms |"))
        .map(|l| l.split('|').map(str::trim).collect())
        .collect();
    assert_eq!(
        leaks.len(),
        2 * 4 * 2,
        "two scenes, four methods, two pass counts"
    );
    let mut sppm_leaks = 0;
    for row in &leaks {
        let brightest: f64 = row[4].parse().unwrap();
        if row[2].starts_with("progressive") {
            assert_eq!(brightest, 0.0, "{row:?}: the dark room must stay exactly black");
        } else if brightest > 0.0 {
            sppm_leaks += 1;
        }
    }
    // SPPM's one map gathers through the wall near it (whether a pixel at this tiny size
    // shows it at every pass count depends on where its few photons fall).
    assert!(sppm_leaks > 0, "SPPM's one map is expected to leak: {leaks:?}");
    let creases = md.split("crease bias, per pass count").nth(1).unwrap();
    let creases = creases.split("\n## ").next().unwrap();
    assert_eq!(
        creases.lines().filter(|l| l.starts_with("| progressive")).count(),
        3 * 2
    );
    // The memory table: the peak heap of the longest run is within 10 % of the shortest's.
    let memory = md
        .split("## Memory per pass count")
        .nth(1)
        .expect("a memory table");
    let peaks: Vec<f64> = memory
        .lines()
        .filter(|l| l.starts_with("| progressive cube"))
        .map(|l| l.split('|').nth(4).unwrap().trim().parse().unwrap())
        .collect();
    assert_eq!(peaks.len(), 3, "{memory}");
    assert!(
        peaks[2] <= peaks[0] * 1.1,
        "peak heap grew with passes: {peaks:?} MiB"
    );
    let _ = std::fs::remove_dir_all(&dir);
}

/// `--references-only` renders a reference and stops; `--extend-references` adds batches to
/// it (more samples, same files), and refuses a reference it did not path trace itself.
#[test]
fn references_render_alone_and_extend() {
    let Some(exe) = example("convergence") else {
        return;
    };
    let dir = std::env::temp_dir().join(format!("pm-convergence-refs-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    let run = |extra: &[&str]| {
        Command::new(&exe)
            .args(["--references-only", "--scenes", "accordion", "--size", "8"])
            .args(["--reference-seconds", "0.05"])
            .args(extra)
            .arg("--out-dir")
            .arg(&dir)
            .arg("--reference-dir")
            .arg(&dir)
            .output()
            .expect("the example starts")
    };
    let spp = || -> u64 {
        let text = std::fs::read_to_string(dir.join("accordion-8x8.txt")).unwrap();
        text.split_whitespace().next().unwrap().parse().unwrap()
    };
    assert!(run(&[]).status.success());
    assert!(!dir.join("convergence.md").exists(), "references only: no study");
    let first = spp();
    let out = run(&["--extend-references", "0.05"]);
    assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
    let second = spp();
    assert!(
        second > first && second % 8 == 0,
        "{first} → {second} samples per pixel"
    );
    // A reference from elsewhere (no note that this example path traced it) is not extended.
    std::fs::write(
        dir.join("accordion-8x8.txt"),
        format!("{second} samples per pixel\n"),
    )
    .unwrap();
    let out = run(&["--extend-references", "0.05"]);
    assert!(!out.status.success());
    assert!(
        String::from_utf8_lossy(&out.stderr).contains("cannot be extended"),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let _ = std::fs::remove_dir_all(&dir);
}
