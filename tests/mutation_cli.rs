//! A seeded mutation test of the render example, run as a user runs it: valid glTF scenes
//! (external buffer, PNG or JPEG texture, `NORMAL`, `TEXCOORD_0`, `COLOR_0`) and valid
//! progressive shards are mutated (accessor types, counts and values, image sizes, bit
//! depths, colour types, truncation, a JPEG marked progressive, shard headers, pass ranges
//! and pixel values, random bytes) and each mutant is rendered or merged. Every run must end
//! within 20 s (under a 4 GB address-space cap on Unix) with status 0 or 1 and no panic; a successful run's EXR must hold only finite
//! pixels; and no file but the outputs named may change.
//!
//! CI runs a short run (`PM_MUTATION_CASES` unset: 24 glTF and 12 shard mutants); set
//! `PM_MUTATION_CASES=N` for N of each and `PM_MUTATION_SEED` for another seed. A failing
//! case prints its seed, index and mutations; its files are kept under the temp folder.

#[path = "support/example.rs"]
mod example;
#[path = "support/mutation_gltf.rs"]
mod mutation_gltf;
#[path = "support/mutation_shard.rs"]
mod mutation_shard;
#[path = "support/unit_cube_room.rs"]
mod unit_cube_room;

use mutation_gltf::gltf_mutant;
use mutation_shard::{header_of, write_shard};
use std::collections::BTreeMap;
use std::path::{Path, PathBuf};
use std::process::{Command, Stdio};
use std::time::{Duration, Instant};

/// SplitMix64: small, seeded, the same sequence everywhere.
struct Rng(u64);

impl Rng {
    fn next(&mut self) -> u64 {
        self.0 = self.0.wrapping_add(0x9e37_79b9_7f4a_7c15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xbf58_476d_1ce4_e5b9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94d0_49bb_1331_11eb);
        z ^ (z >> 31)
    }
    /// A number in `0..n` (0 when `n` is 0: a file already cut to nothing is cut at 0).
    fn below(&mut self, n: usize) -> usize {
        (self.next() % n.max(1) as u64) as usize
    }
    fn pick<'a, T>(&mut self, items: &'a [T]) -> &'a T {
        &items[self.below(items.len())]
    }
}

fn cases() -> usize {
    std::env::var("PM_MUTATION_CASES")
        .ok()
        .and_then(|v| v.parse().ok())
        .unwrap_or(0)
}

fn seed() -> u64 {
    std::env::var("PM_MUTATION_SEED")
        .ok()
        .and_then(|v| v.parse().ok())
        .unwrap_or(21)
}

/// Every file under `dir` with its bytes, outputs left out.
fn snapshot(dir: &Path, outputs: &[&str]) -> BTreeMap<PathBuf, Vec<u8>> {
    let mut out = BTreeMap::new();
    let mut stack = vec![dir.to_path_buf()];
    while let Some(d) = stack.pop() {
        for e in std::fs::read_dir(&d).unwrap() {
            let p = e.unwrap().path();
            if p.is_dir() {
                stack.push(p);
            } else if !outputs.iter().any(|o| p.ends_with(o)) {
                out.insert(p.clone(), std::fs::read(&p).unwrap());
            }
        }
    }
    out
}

/// Runs the example in `dir` with `args`; checks the run ended within 20 s with status 0
/// or 1 and no panic, that a success's EXR `out` has only finite pixels, and that nothing
/// but `outputs` changed. `label` names the case in failures. Returns whether it succeeded
/// (`None`: the example is not built).
fn check_run(dir: &Path, args: &[&str], out: &str, outputs: &[&str], label: &str) -> Option<bool> {
    let exe = example::example("render")?;
    let before = snapshot(dir, outputs);
    // Under a 4 GB address-space cap where the shell can set one, so an allocation the
    // bounds missed aborts here rather than swapping.
    let mut command = if cfg!(unix) {
        let mut c = Command::new("sh");
        c.arg("-c")
            .arg("ulimit -v 4194304 2>/dev/null; exec \"$0\" \"$@\"")
            .arg(exe);
        c
    } else {
        Command::new(exe)
    };
    let mut child = command
        .args(args)
        .current_dir(dir)
        .stdout(Stdio::null())
        .stderr(Stdio::piped())
        .spawn()
        .unwrap();
    let start = Instant::now();
    let status = loop {
        if let Some(status) = child.try_wait().unwrap() {
            break status;
        }
        if start.elapsed() > Duration::from_secs(20) {
            let _ = child.kill();
            let _ = child.wait();
            panic!("{label}: ran past 20 s (kept in {})", dir.display());
        }
        std::thread::sleep(Duration::from_millis(10));
    };
    let mut stderr = String::new();
    use std::io::Read as _;
    child.stderr.take().unwrap().read_to_string(&mut stderr).unwrap();
    assert!(
        !stderr.contains("panicked"),
        "{label}: panicked: {stderr} (kept in {})",
        dir.display()
    );
    assert!(
        matches!(status.code(), Some(0 | 1)),
        "{label}: status {status:?} (an abort or a signal): {stderr} (kept in {})",
        dir.display()
    );
    if status.success() {
        let image = photon_maps::render::Image::read_exr(dir.join(out)).unwrap();
        assert!(
            image.pixels().iter().all(|p| p.is_finite()),
            "{label}: non-finite pixels (kept in {})",
            dir.display()
        );
    }
    let after = snapshot(dir, outputs);
    assert!(
        before == after,
        "{label}: a file that is no output changed (kept in {})",
        dir.display()
    );
    Some(status.success())
}

/// Counts of rendered and refused mutants; both must occur, or the mutants test nothing.
#[derive(Default)]
struct Tally {
    rendered: usize,
    refused: usize,
}

impl Tally {
    fn add(&mut self, outcome: bool) {
        if outcome {
            self.rendered += 1;
        } else {
            self.refused += 1;
        }
    }

    fn check(&self, what: &str) {
        eprintln!("{what}: {} rendered, {} refused", self.rendered, self.refused);
        assert!(
            self.rendered > 0 && self.refused > 0,
            "{what}: the mutants are all alike"
        );
    }
}

const MODES: [&[&str]; 4] = [
    &["--mode", "photon-map", "--photons", "300"],
    &["--mode", "path-trace"],
    &["--mode", "sppm", "--photons", "300", "--passes", "1"],
    &["--mode", "progressive", "--photons", "300", "--passes", "1"],
];

#[test]
fn mutated_gltf_scenes_render_or_are_refused_cleanly() {
    let n = match cases() {
        0 => 24,
        n => n,
    };
    let seed = seed();
    let mut rng = Rng(seed);
    let mut tally = Tally::default();
    for case in 0..n {
        let mutant = gltf_mutant(&mut rng);
        let mode = *rng.pick(&MODES);
        let dir = std::env::temp_dir().join(format!("pm-mutation-gltf-{}-{case}", std::process::id()));
        let _ = std::fs::remove_dir_all(&dir);
        std::fs::create_dir_all(&dir).unwrap();
        for (name, bytes) in &mutant.files {
            std::fs::write(dir.join(name), bytes).unwrap();
        }
        let mut args = vec!["--scene", "scene.gltf", "--size", "8x6", "--out", "out/x.exr"];
        args.extend_from_slice(mode);
        let label = format!("seed {seed} glTF case {case} {mode:?}: {:?}", mutant.done);
        let Some(outcome) = check_run(&dir, &args, "out/x.exr", &["out/x.exr", "out/x.png"], &label) else {
            return;
        };
        tally.add(outcome);
        std::fs::remove_dir_all(&dir).ok();
    }
    tally.check("glTF mutants");
}

#[test]
fn mutated_shards_merge_or_are_refused_cleanly() {
    let n = match cases() {
        0 => 12,
        n => n / 2,
    };
    let seed = seed();
    let mut rng = Rng(seed ^ 0x5eed);
    let base = std::env::temp_dir().join(format!("pm-mutation-shards-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&base);
    std::fs::create_dir_all(&base).unwrap();
    let render = |name: &str, first: &str| {
        let args = [
            "--mode",
            "progressive",
            "--size",
            "8x6",
            "--photons",
            "300",
            "--passes",
            "1",
            "--first-pass",
            first,
            "--out",
            name,
        ];
        let exe = example::example("render")?;
        let status = Command::new(exe).args(args).current_dir(&base).output().unwrap();
        assert!(
            status.status.success(),
            "{}",
            String::from_utf8_lossy(&status.stderr)
        );
        Some(std::fs::read(base.join(name)).unwrap())
    };
    let Some(a) = render("a.exr", "0") else { return };
    let b = render("b.exr", "1").unwrap();
    let (scene, settings) = header_of(&base.join("a.exr"));
    let mut tally = Tally::default();
    let passes = [
        "0",
        "1",
        "2",
        "18446744073709551613",
        "18446744073709551614",
        "18446744073709551615",
    ];
    for case in 0..n {
        let dir = base.join(format!("case{case}"));
        std::fs::create_dir_all(&dir).unwrap();
        let (pa, pb) = (dir.join("a.exr"), dir.join("b.exr"));
        std::fs::write(&pa, &a).unwrap();
        std::fs::write(&pb, &b).unwrap();
        let target = if rng.below(2) == 0 { &pa } else { &pb };
        let done = match rng.below(4) {
            0 => {
                let mut bytes = std::fs::read(target).unwrap();
                let at = rng.below(bytes.len().min(600));
                bytes[at] ^= 1 << rng.below(8);
                std::fs::write(target, bytes).unwrap();
                format!("bit flip at {at}")
            }
            1 => {
                let mut bytes = std::fs::read(target).unwrap();
                let keep = rng.below(bytes.len());
                bytes.truncate(keep);
                std::fs::write(target, bytes).unwrap();
                format!("cut at {keep}")
            }
            2 => {
                let (first, count) = (*rng.pick(&passes), *rng.pick(&passes));
                let lines = [
                    "photon-maps shard v2".to_owned(),
                    first.into(),
                    count.into(),
                    scene.clone(),
                    settings.clone(),
                ];
                write_shard(target, &lines, 1.0, 0.0);
                format!("header passes {first} + {count}")
            }
            _ => {
                let values = [f64::NAN, f64::INFINITY, -1.0, 1e300, 1e-320, 0.0];
                let (hi, lo) = (*rng.pick(&values), *rng.pick(&values));
                let first = if target == &pa { "0" } else { "1" };
                let lines = [
                    "photon-maps shard v2".to_owned(),
                    first.into(),
                    "1".into(),
                    scene.clone(),
                    settings.clone(),
                ];
                write_shard(target, &lines, hi, lo);
                format!("pixel sums {hi} + {lo}")
            }
        };
        let args = ["--merge", "a.exr", "b.exr", "--out", "m.exr"];
        let label = format!("seed {seed} shard case {case} ({}): {done}", target.display());
        tally.add(check_run(&dir, &args, "m.exr", &["m.exr", "m.png"], &label).unwrap_or(false));
    }
    tally.check("shard mutants");
    std::fs::remove_dir_all(&base).ok();
}
