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
use photon_maps::render::Image;
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

/// `--save-run` keeps the study, `--rescore` measures it again without rendering: against
/// the same references it writes the same Markdown (one sentence more), and against an
/// extended reference each budget's error is the kept image's, as computed here from the
/// files (relative RMSE over every pixel, less the reference's own noise in quadrature).
#[test]
fn a_kept_run_rescores_the_same_and_against_an_extended_reference() {
    let Some(exe) = example("convergence") else {
        return;
    };
    let dir = std::env::temp_dir().join(format!("pm-convergence-rescore-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    let (kept, references) = (dir.join("run"), dir.join("references"));
    let run = |args: &[&str], out: &str| {
        let output = Command::new(&exe)
            .args(args)
            .args(["--font", FONT, "--reference-dir"])
            .arg(&references)
            .arg("--out-dir")
            .arg(dir.join(out))
            .output()
            .expect("the example starts");
        assert!(
            output.status.success(),
            "{args:?}: {}",
            String::from_utf8_lossy(&output.stderr)
        );
        std::fs::read_to_string(dir.join(out).join("convergence.md")).unwrap_or_default()
    };
    let study = [
        "--quick",
        "--size",
        "16",
        "--budgets",
        "0.000001,0.02,0.05",
        "--scenes",
        "accordion",
        "--methods",
        "path-trace,final-gather",
        "--no-per-pass",
        "--all-pixels",
        "--reference-seconds",
        "0.2",
        "--save-run",
    ];
    let first = run(&[&study[..], &[kept.to_str().unwrap()]].concat(), "first");
    let rescore = ["--rescore", kept.to_str().unwrap()];
    let same = run(&rescore, "same");
    let without_note: Vec<&str> = same.lines().filter(|l| !l.starts_with("Re-scored by")).collect();
    let first_lines: Vec<&str> = first.lines().collect();
    assert_eq!(
        without_note.len(),
        first_lines.len() + 1,
        "one paragraph more (a sentence and its blank line)"
    );
    let mut rest = without_note.iter().filter(|l| !l.is_empty());
    for line in first_lines.iter().filter(|l| !l.is_empty()) {
        assert_eq!(
            Some(line),
            rest.next(),
            "rescoring against the same references changed the study"
        );
    }

    let out = Command::new(&exe)
        .args(["--references-only", "--scenes", "accordion", "--size", "16"])
        .args(["--extend-references", "0.2", "--reference-dir"])
        .arg(&references)
        .arg("--out-dir")
        .arg(dir.join("first"))
        .output()
        .unwrap();
    assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
    let extended = run(&rescore, "extended");
    let reference = Image::read_exr(references.join("accordion-16x16.exr")).unwrap();
    let half = Image::read_exr(references.join("accordion-16x16.half.exr")).unwrap();
    let spp = std::fs::read_to_string(references.join("accordion-16x16.txt")).unwrap();
    let spp = spp.split_whitespace().next().unwrap();
    assert!(
        extended.contains(&format!("Reference: {spp} samples per pixel")),
        "the study names the extended reference ({spp} spp)"
    );
    let noise = relative_rmse(&half, &reference);
    let mut checked = 0;
    for row in extended.lines().filter(|l| l.starts_with("| 0.0")) {
        // | seconds | path tracing | final gather | …: "error (passes)" per method.
        for (cell, method) in row.split('|').skip(2).zip(["path-trace", "final-gather"]) {
            let Some((error, passes)) = cell.trim().split_once(" (") else {
                continue;
            };
            let image = Image::read_exr(
                kept.join("accordion")
                    .join(format!("{method}-{}.exr", passes.trim_end_matches(')'))),
            )
            .unwrap();
            let measured = relative_rmse(&image, &reference);
            let expected = (measured * measured - noise * noise).max(0.0).sqrt();
            let error: f64 = error.trim_end_matches("⁽*⁾").parse().unwrap();
            assert!(
                (error - expected).abs() <= 0.000_051,
                "{method} at {row}: {error} against {expected:.6} from its kept image"
            );
            checked += 1;
        }
    }
    assert!(checked >= 3, "{checked} cells checked:\n{extended}");
    // The smallest budget ends before any pass: nothing kept, nothing to measure, both times.
    for md in [&first, &extended] {
        let row = md.lines().find(|l| l.starts_with("| 0.000001 |")).unwrap();
        assert!(row.starts_with("| 0.000001 | — | — |"), "{row}");
    }

    let refused = Command::new(&exe)
        .args(["--rescore", kept.to_str().unwrap(), "--size", "8"])
        .output()
        .unwrap();
    assert!(!refused.status.success(), "--size does not apply to --rescore");
    let refused = Command::new(&exe)
        .args(["--references-only", "--save-run", kept.to_str().unwrap()])
        .output()
        .unwrap();
    assert!(!refused.status.success(), "--references-only keeps no run");
    // A record that claims another size, or is cut short, is refused, naming what is wrong.
    let record = std::fs::read_to_string(kept.join("study.json")).unwrap();
    let refused_record = |text: &str, needle: &str| {
        std::fs::write(kept.join("study.json"), text).unwrap();
        let out = Command::new(&exe)
            .arg("--rescore")
            .arg(&kept)
            .arg("--reference-dir")
            .arg(&references)
            .arg("--out-dir")
            .arg(dir.join("hostile"))
            .output()
            .unwrap();
        let stderr = String::from_utf8_lossy(&out.stderr);
        assert!(
            !out.status.success() && stderr.contains(needle) && !stderr.contains("panicked"),
            "{needle}: {stderr}"
        );
    };
    refused_record(
        &record.replace("\"size\":16,", "\"size\":1000000,"),
        "accordion-1000000x1000000.exr",
    );
    refused_record(&record[..record.len() / 2], "study.json");
    // A scene name that is not a built-in one (here an absolute path, which would reach outside
    // the reference folder) is refused before any file is opened.
    let absolute = record.replacen("\"name\":\"accordion\"", "\"name\":\"/etc/accordion\"", 1);
    assert_ne!(absolute, record, "the record names its scenes");
    refused_record(&absolute, "neither a built-in scene");
    // A glTF source must name the scene by its plain stem.
    let sourced = record.replacen(
        "\"name\":\"accordion\",\"source\":null",
        "\"name\":\"accordion\",\"source\":\"/etc/evil.gltf\"",
        1,
    );
    assert_ne!(sourced, record, "the record names its scenes' sources");
    refused_record(&sourced, "neither a built-in scene");
    // A kept image gone, or a reference cut short: refused, naming the file.
    let gone = std::fs::read_dir(kept.join("accordion"))
        .unwrap()
        .map(|e| e.unwrap().path())
        .find(|p| p.to_string_lossy().contains("final-gather-"))
        .unwrap();
    std::fs::remove_file(&gone).unwrap();
    // A FIFO in its place, and a folder as the record: refused as not regular files before
    // they are opened (a FIFO would block the reader for ever).
    #[cfg(unix)]
    {
        let made = Command::new("mkfifo").arg(&gone).status().unwrap();
        assert!(made.success());
        refused_record(&record, "not a regular file");
        std::fs::remove_file(&gone).unwrap();
    }
    refused_record(&record, &gone.file_name().unwrap().to_string_lossy());
    let half = references.join("accordion-16x16.half.exr");
    let bytes = std::fs::read(&half).unwrap();
    std::fs::write(&half, &bytes[..bytes.len() / 2]).unwrap();
    refused_record(&record, "accordion-16x16.half.exr");
    assert!(!dir.join("hostile/convergence.md").exists());
    std::fs::remove_file(kept.join("study.json")).unwrap();
    std::fs::create_dir(kept.join("study.json")).unwrap();
    let folder = Command::new(&exe).arg("--rescore").arg(&kept).output().unwrap();
    let stderr = String::from_utf8_lossy(&folder.stderr);
    assert!(
        !folder.status.success() && stderr.contains("not a regular file"),
        "{stderr}"
    );
    let missing = Command::new(&exe)
        .args(["--rescore"])
        .arg(dir.join("nothing"))
        .output()
        .unwrap();
    let stderr = String::from_utf8_lossy(&missing.stderr);
    assert!(
        !missing.status.success() && stderr.contains("study.json") && !stderr.contains("panicked"),
        "{stderr}"
    );
    let _ = std::fs::remove_dir_all(&dir);
}

/// Relative RMSE over every pixel and channel: RMSE over the reference's mean.
fn relative_rmse(image: &Image, reference: &Image) -> f64 {
    let (mut squares, mut sum) = (0.0f64, 0.0f64);
    for (p, r) in image.pixels().iter().zip(reference.pixels()) {
        for c in 0..3 {
            squares += (f64::from(p[c]) - f64::from(r[c])).powi(2);
            sum += f64::from(r[c]);
        }
    }
    let n = 3.0 * image.pixels().len() as f64;
    (squares / n).sqrt() / (sum / n)
}
