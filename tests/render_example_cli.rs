//! The render example as a user runs it: bad input exits non-zero with one line naming the
//! problem (never a panic), and one or two threads write byte-identical EXR files.
//!
//! `cargo test` builds the examples next to the test binaries; when this test is built alone
//! (`cargo test --test render_example_cli`) the example may be missing, and the test says so
//! and skips.

#[path = "support/example.rs"]
mod example;

#[path = "support/gltf_data_uri.rs"]
mod gltf_data_uri;
#[path = "support/unit_cube_room.rs"]
mod unit_cube_room;

use example::{assert_refused, run};
use gltf_data_uri::{Prim, gltf};
use std::path::PathBuf;
use std::process::Output;

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
    let cases: [(&[&str], &str); 10] = [
        (&["--scene", "no-such-scene", "--out", out], "no-such-scene"),
        (&["--scene", "/no/such/file.gltf", "--out", out], "file.gltf"),
        (&["--k", "0", "--out", out], "k"),
        (&["--photons", "0", "--out", out], "photon"),
        (&["--size", "0x10", "--out", out], "0x10"),
        (&["--out", under_file.to_str().unwrap()], "a-file"),
        (&["--scene", dir.to_str().unwrap(), "--out", out], "folder"),
        (&["--scene", "room.obj", "--out", out], ".obj files are not read"),
        (&["--compare", "--maps", "contact", "--out", out], "drop --maps"),
        (
            &["--compare", "--mode", "path-trace", "--out", out],
            "photon-map mode",
        ),
    ];
    for (args, needle) in cases {
        let Some(output) = run(args) else { return };
        assert_refused(args, &output, needle);
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

#[test]
fn help_lists_the_values_of_maps_estimator_and_mode_and_typos_get_suggestions() {
    let Some(help) = run(&["--help"]) else { return };
    let help = String::from_utf8_lossy(&help.stdout);
    for value in [
        "single",
        "crease",
        "contact",
        "disc",
        "cube",
        "ball",
        "photon-map",
        "shadow-rays",
        "path-trace",
        "progressive",
        "sppm",
    ] {
        assert!(help.contains(value), "--help does not list {value}: {help}");
    }
    let Some(typo) = run(&["--maps", "creese"]) else {
        return;
    };
    assert!(!typo.status.success());
    let stderr = String::from_utf8_lossy(&typo.stderr);
    assert!(stderr.contains("crease"), "no suggestion for a typo: {stderr}");
}

/// Reads an 8-bit RGB(A) PNG: (width, height, RGB triples).
fn read_png(path: &std::path::Path) -> (u32, u32, Vec<[u8; 3]>) {
    let decoder = png::Decoder::new(std::io::BufReader::new(std::fs::File::open(path).unwrap()));
    let mut reader = decoder.read_info().unwrap();
    let mut buf = vec![0; reader.output_buffer_size().unwrap()];
    let info = reader.next_frame(&mut buf).unwrap();
    assert_eq!(info.bit_depth, png::BitDepth::Eight);
    let channels = info.color_type.samples();
    let pixels = buf[..info.buffer_size()]
        .chunks_exact(channels)
        .map(|p| [p[0], p[1], p[2]])
        .collect();
    (info.width, info.height, pixels)
}

#[test]
fn compare_picks_an_exposure_that_clips_under_5_percent_and_labels_its_panels() {
    let dir = scratch_dir("compare");
    let out = dir.join("grid.exr");
    let args = [
        "--compare",
        "--scene",
        "lit-unlit-rooms",
        "--size",
        "96x96",
        "--photons",
        "20000",
        "--out",
        out.to_str().unwrap(),
    ];
    let Some(output) = run(&args) else { return };
    assert!(
        output.status.success(),
        "{}",
        String::from_utf8_lossy(&output.stderr)
    );
    assert!(String::from_utf8_lossy(&output.stdout).contains("preview exposure"));
    let (width, height, pixels) = read_png(&out.with_extension("png"));
    assert_eq!((width, height), (192, 192));
    let clipped = pixels.iter().filter(|p| p.contains(&255)).count();
    let share = clipped as f64 / pixels.len() as f64;
    assert!(share < 0.05, "{:.1} % of the pixels clip", 100.0 * share);
    // Each panel's top left corner holds a label: white glyph pixels on a black box.
    for (x0, y0) in [(0, 0), (96, 0), (0, 96), (96, 96)] {
        let (mut white, mut black) = (0, 0);
        for y in y0..y0 + 9 {
            for x in x0..x0 + 25 {
                match pixels[(y * width + x) as usize] {
                    [255, 255, 255] => white += 1,
                    [0, 0, 0] => black += 1,
                    _ => {}
                }
            }
        }
        assert!(
            white >= 15 && black >= 50,
            "panel at ({x0}, {y0}): {white} white, {black} black"
        );
    }
    std::fs::remove_dir_all(&dir).ok();
}

/// The mean RGB the example prints in its summary line.
fn printed_mean(out: &Output) -> [f64; 3] {
    let text = String::from_utf8_lossy(&out.stdout);
    let line = text
        .lines()
        .find(|l| l.contains("mean rgb"))
        .expect("a summary line");
    let inside = &line[line.find("mean rgb (").unwrap() + 10..];
    let values: Vec<f64> = inside[..inside.find(')').unwrap()]
        .split(',')
        .map(|v| v.trim().parse().unwrap())
        .collect();
    [values[0], values[1], values[2]]
}

/// `--light-units` reaches the glTF loader: a grey quad lit only by a point lamp of intensity
/// I renders `viewer` (lamps 1:1, 4πI W) exactly 683 times brighter than `mixed` and
/// `photometric` (lamps ÷ 683 lm/W), the same photons scaled; built-in scenes ignore it.
#[test]
fn light_units_scale_a_gltf_lamp_by_683() {
    let dir = scratch_dir("units");
    let quad = Prim {
        positions: vec![
            [-1.0, -1.0, 0.0],
            [1.0, -1.0, 0.0],
            [1.0, 1.0, 0.0],
            [-1.0, 1.0, 0.0],
        ],
        uvs: None,
        indices: vec![0, 1, 2, 0, 2, 3],
        material: 0,
    };
    let grey = r#"{"pbrMetallicRoughness":{"baseColorFactor":[0.5,0.5,0.5,1],"metallicFactor":0}}"#;
    let json = gltf(
        &[quad],
        &[grey.to_owned()],
        "[]",
        &[],
        &[([0.0, 0.0, 1.0], 10_000.0)],
    );
    let file = dir.join("lamp.gltf");
    std::fs::write(&file, json).unwrap();
    let mean = |units: &str| {
        let out = dir.join(format!("{units}.exr"));
        let args = [
            "--scene",
            file.to_str().unwrap(),
            "--size",
            "24x24",
            "--photons",
            "20000",
            "--light-units",
            units,
            "--out",
            out.to_str().unwrap(),
        ];
        let output = run(&args)?;
        assert!(
            output.status.success(),
            "{}",
            String::from_utf8_lossy(&output.stderr)
        );
        Some(printed_mean(&output))
    };
    let Some(mixed) = mean("mixed") else { return };
    println!("mean rgb, mixed units: {mixed:?}");
    let (viewer, photometric) = (mean("viewer").unwrap(), mean("photometric").unwrap());
    for c in 0..3 {
        assert!(mixed[c] > 0.01, "{mixed:?}");
        assert!(
            (viewer[c] / mixed[c] / 683.0 - 1.0).abs() < 1e-3,
            "{viewer:?} vs {mixed:?}"
        );
        assert!(
            (photometric[c] / mixed[c] - 1.0).abs() < 1e-3,
            "{photometric:?} vs {mixed:?}"
        );
    }
    // Built-in scenes are in watts already: the option would do nothing there, so it is
    // refused rather than ignored.
    let out = dir.join("builtin.exr");
    let output = run(&[
        "--size",
        "16x16",
        "--light-units",
        "viewer",
        "--out",
        out.to_str().unwrap(),
    ])
    .unwrap();
    let stderr = String::from_utf8_lossy(&output.stderr);
    assert!(
        !output.status.success() && stderr.contains("--light-units"),
        "{stderr}"
    );
    std::fs::remove_dir_all(&dir).ok();
}
