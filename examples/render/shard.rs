//! `--shard-index-from` and `--passes-per-shard`: a progressive shard's pass range taken from a
//! batch scheduler's array index, so that one job script serves every task of an array.

use super::Args;
use clap::ArgMatches;
use clap::ValueEnum;
use clap::parser::ValueSource;
use std::ffi::OsString;
use std::fmt;
use std::path::PathBuf;

/// What `{index}` in `--out` and `--stats-json` stands for with `--shard-index-from`.
pub const INDEX_PLACEHOLDER: &str = "{index}";

/// `--shard-index-from`: the scheduler whose array index numbers this task.
#[derive(Clone, Copy, Debug, PartialEq, Eq, ValueEnum)]
pub enum IndexSource {
    /// Slurm array jobs (`sbatch --array`): `SLURM_ARRAY_TASK_ID`.
    Slurm,
    /// Kubernetes Indexed Jobs (`completionMode: Indexed`): `JOB_COMPLETION_INDEX`.
    Kubernetes,
    /// AWS Batch array jobs: `AWS_BATCH_JOB_ARRAY_INDEX`.
    AwsBatch,
}

impl IndexSource {
    /// The environment variable the scheduler sets in each task.
    pub fn variable(self) -> &'static str {
        match self {
            IndexSource::Slurm => "SLURM_ARRAY_TASK_ID",
            IndexSource::Kubernetes => "JOB_COMPLETION_INDEX",
            IndexSource::AwsBatch => "AWS_BATCH_JOB_ARRAY_INDEX",
        }
    }
}

impl fmt::Display for IndexSource {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let value = self.to_possible_value().ok_or(fmt::Error)?;
        f.write_str(value.get_name())
    }
}

/// The array index in `variable`'s `value` (as read from the environment): decimal digits
/// only, no sign, space or `+`, within `u64`; any other value is refused naming both.
pub fn parse_index(variable: &str, value: Option<OsString>) -> Result<u64, String> {
    let Some(value) = value else {
        return Err(format!(
            "--shard-index-from: {variable} is not set; run inside the scheduler's array job or set it"
        ));
    };
    let Some(text) = value.to_str() else {
        return Err(format!(
            "--shard-index-from: {variable}={:?} is not a number",
            value.to_string_lossy()
        ));
    };
    if text.is_empty() {
        return Err(format!(
            "--shard-index-from: {variable} is empty; expected an array index (0, 1, 2, …)"
        ));
    }
    if !text.bytes().all(|b| b.is_ascii_digit()) {
        let what = if text.starts_with('-') {
            "is negative"
        } else {
            "is not a whole number"
        };
        return Err(format!(
            "--shard-index-from: {variable}={text:?} {what}; expected an array index (0, 1, 2, …)"
        ));
    }
    text.parse::<u64>().map_err(|_| {
        format!(
            "--shard-index-from: {variable}={text} is too large (the largest index is {})",
            u64::MAX
        )
    })
}

/// The shard's first pass, `index × passes_per_shard`, refused when it does not fit.
pub fn first_pass(variable: &str, index: u64, passes_per_shard: u64) -> Result<u64, String> {
    index
        .checked_mul(passes_per_shard)
        .and_then(|first| first.checked_add(passes_per_shard).map(|_| first))
        .ok_or_else(|| {
            format!(
                "--shard-index-from: {variable}={index} × --passes-per-shard {passes_per_shard} overflows the pass numbers (at most {})",
                u64::MAX
            )
        })
}

/// Sets `--first-pass` and `--passes` from the scheduler's index and `{index}` in the output
/// paths; refuses the two options apart, with `--first-pass`, `--passes` or `--time`, and
/// `{index}` in an output path without `--shard-index-from`. Runs after the mode checks.
pub fn resolve(args: &mut Args, matches: &ArgMatches) -> Result<(), String> {
    let given = |id: &str| matches.value_source(id) == Some(ValueSource::CommandLine);
    let Some(source) = args.shard_index_from else {
        if args.passes_per_shard.is_some() {
            return Err(
                "--passes-per-shard needs --shard-index-from slurm|kubernetes|aws-batch to number the shard"
                    .into(),
            );
        }
        for (name, path) in [("--out", &args.out), ("--stats-json", &args.stats_json)] {
            if path.as_ref().is_some_and(|p| names_index(p)) {
                return Err(format!(
                    "{name} contains {INDEX_PLACEHOLDER}, which only --shard-index-from fills; give it or rename the file"
                ));
            }
        }
        return Ok(());
    };
    for (id, name) in [
        ("first_pass", "--first-pass"),
        ("passes", "--passes"),
        ("time", "--time"),
    ] {
        if given(id) {
            return Err(format!(
                "{name} does not combine with --shard-index-from: the index and --passes-per-shard set the shard's passes; drop {name}"
            ));
        }
    }
    let passes = match args.passes_per_shard {
        Some(0) => return Err("--passes-per-shard must be at least 1".into()),
        Some(n) => n,
        None => {
            return Err(format!(
                "--shard-index-from {source} needs --passes-per-shard N (shard i renders passes i×N … i×N+N−1)"
            ));
        }
    };
    let variable = source.variable();
    let index = parse_index(variable, std::env::var_os(variable))?;
    args.first_pass = first_pass(variable, index, passes)?;
    args.passes = Some(passes);
    // Without --out, each shard gets its own default file, not one they all overwrite.
    let scene = super::files::scene_name(&args.scene);
    let out = args
        .out
        .take()
        .unwrap_or_else(|| super::default_out(&format!("{scene}-shard-{INDEX_PLACEHOLDER}")));
    let fill = |path: PathBuf| match names_index(&path) {
        true => PathBuf::from(
            path.to_string_lossy()
                .replace(INDEX_PLACEHOLDER, &index.to_string()),
        ),
        false => path,
    };
    args.out = Some(fill(out));
    args.stats_json = args.stats_json.take().map(fill);
    Ok(())
}

/// Whether a path holds the `{index}` placeholder.
fn names_index(path: &std::path::Path) -> bool {
    path.to_string_lossy().contains(INDEX_PLACEHOLDER)
}
