//! The render example's `--shard-index-from` and `--passes-per-shard`: each scheduler's
//! variable numbers the shard as `--first-pass i×N --passes N` would, bit for bit; a bad
//! variable, a conflicting option or a mode without shards is refused in one line.

#[path = "support/scratch.rs"]
mod scratch;
use scratch::Scratch;
#[path = "support/example.rs"]
mod example;
use example::{assert_ok, assert_refused};
use std::process::{Command, Output};

/// The three schedulers' options and variables.
const SOURCES: [(&str, &str); 3] = [
    ("slurm", "SLURM_ARRAY_TASK_ID"),
    ("kubernetes", "JOB_COMPLETION_INDEX"),
    ("aws-batch", "AWS_BATCH_JOB_ARRAY_INDEX"),
];

/// A small progressive render: 16×16, 2,000 photons per pass.
const SMALL: [&str; 8] = [
    "--scene",
    "cornell-box",
    "--mode",
    "progressive",
    "--size",
    "16x16",
    "--photons",
    "2000",
];

/// The render example run in `dir` with `args` and only `env` of the schedulers' variables
/// (the test may itself run inside an array job); `None`: not built, the test skips.
fn run_with(dir: &Scratch, env: &[(&str, &str)], args: &[&str]) -> Option<Output> {
    let mut command = Command::new(example::example("render")?);
    command.current_dir(&dir.0).args(args);
    for (_, variable) in SOURCES {
        command.env_remove(variable);
    }
    command.envs(env.iter().copied());
    Some(command.output().expect("the example starts"))
}

#[test]
fn each_schedulers_index_gives_the_bytes_of_the_same_pass_range() {
    let dir = Scratch::new("shard-index-bytes");
    // Shard 3 of 2 passes is passes 6 and 7.
    let mut reference = SMALL.to_vec();
    reference.extend(["--first-pass", "6", "--passes", "2", "--out", "reference.exr"]);
    let Some(output) = run_with(&dir, &[], &reference) else {
        return;
    };
    assert_ok(&reference, &output);
    let expected = std::fs::read(dir.0.join("reference.exr")).unwrap();
    for (source, variable) in SOURCES {
        let out = format!("{source}/shard-{{index}}.exr");
        let json = format!("{source}/shard-{{index}}.json");
        let mut args = SMALL.to_vec();
        args.extend(["--shard-index-from", source, "--passes-per-shard", "2"]);
        args.extend(["--out", &out, "--stats-json", &json]);
        let Some(output) = run_with(&dir, &[(variable, "3")], &args) else {
            return;
        };
        assert_ok(&args, &output);
        let shard = dir.0.join(source).join("shard-3.exr");
        assert!(
            std::fs::read(&shard).unwrap() == expected,
            "{source}: not the bytes of passes 6..8"
        );
        let stats = std::fs::read_to_string(dir.0.join(source).join("shard-3.json")).unwrap();
        assert!(stats.contains("\"first_pass\": 6, \"end_pass\": 8"), "{stats}");
    }
}

#[test]
fn without_out_each_shard_writes_its_own_default_file() {
    let dir = Scratch::new("shard-index-default-out");
    let mut args = SMALL.to_vec();
    args.extend(["--shard-index-from", "slurm", "--passes-per-shard", "1"]);
    let Some(output) = run_with(&dir, &[("SLURM_ARRAY_TASK_ID", "5")], &args) else {
        return;
    };
    assert_ok(&args, &output);
    assert!(dir.0.join("target/out/cornell-box-shard-5.exr").is_file());
}

#[test]
fn bad_index_variables_are_refused_naming_the_variable_and_its_value() {
    let dir = Scratch::new("shard-index-bad");
    let huge = "18446744073709551616";
    for (source, variable) in SOURCES {
        let mut args = SMALL.to_vec();
        args.extend(["--shard-index-from", source, "--passes-per-shard", "4"]);
        args.extend(["--out", "x.exr"]);
        let Some(output) = run_with(&dir, &[], &args) else {
            return;
        };
        assert_refused(&args, &output, &format!("{variable} is not set"));
        for (value, needle) in [
            ("", format!("{variable} is empty")),
            ("-1", format!("{variable}=\"-1\" is negative")),
            ("two", format!("{variable}=\"two\" is not a whole number")),
            ("1.5", format!("{variable}=\"1.5\" is not a whole number")),
            (" 1", format!("{variable}=\" 1\" is not a whole number")),
            (huge, format!("{variable}={huge} is too large")),
            // Fits u64, but the first pass index × 4 does not.
            (
                "4611686018427387904",
                format!("{variable}=4611686018427387904 × --passes-per-shard 4 overflows"),
            ),
        ] {
            let Some(output) = run_with(&dir, &[(variable, value)], &args) else {
                return;
            };
            assert_refused(&args, &output, &needle);
        }
    }
    assert!(!dir.0.join("x.exr").exists());
}

#[test]
fn conflicting_options_and_modes_without_shards_are_refused() {
    let dir = Scratch::new("shard-index-refused");
    let env = [("SLURM_ARRAY_TASK_ID", "1")];
    let from = ["--shard-index-from", "slurm", "--passes-per-shard", "2"];
    let cases: Vec<(Vec<&str>, &str)> = vec![
        (
            vec!["--mode", "progressive", "--first-pass", "2"],
            "--first-pass does not combine",
        ),
        (
            vec!["--mode", "progressive", "--passes", "2"],
            "--passes does not combine",
        ),
        (
            vec!["--mode", "progressive", "--time", "5"],
            "--time does not combine",
        ),
        (
            vec!["--mode", "sppm"],
            "--shard-index-from does not apply to --mode sppm",
        ),
        (
            vec!["--mode", "final-gather"],
            "does not apply to --mode final-gather",
        ),
        (
            vec!["--mode", "path-trace"],
            "does not apply to --mode path-trace",
        ),
        (vec!["--merge", "a.exr"], "does not apply to --merge"),
    ];
    for (extra, needle) in cases {
        let mut args = vec!["--size", "8x8", "--out", "x.exr"];
        args.extend(from);
        args.extend(extra);
        let Some(output) = run_with(&dir, &env, &args) else {
            return;
        };
        assert_refused(&args, &output, needle);
    }
    let lone: Vec<(Vec<&str>, &str)> = vec![
        (vec!["--shard-index-from", "slurm"], "needs --passes-per-shard"),
        (
            vec!["--passes-per-shard", "2"],
            "--passes-per-shard needs --shard-index-from",
        ),
        (
            vec!["--shard-index-from", "slurm", "--passes-per-shard", "0"],
            "at least 1",
        ),
        (
            vec!["--out", "shard-{index}.exr"],
            "only --shard-index-from fills",
        ),
    ];
    for (extra, needle) in lone {
        let mut args = vec!["--mode", "progressive", "--size", "8x8"];
        args.extend(extra);
        let Some(output) = run_with(&dir, &env, &args) else {
            return;
        };
        assert_refused(&args, &output, needle);
    }
    // The output checks see the paths with {index} filled: shard-1.exr's PNG is shard-1.png.
    let mut args = SMALL.to_vec();
    args.extend(from);
    args.extend(["--out", "shard-{index}.exr", "--stats-json", "shard-1.png"]);
    let Some(output) = run_with(&dir, &env, &args) else {
        return;
    };
    assert_refused(&args, &output, "same file");
}
