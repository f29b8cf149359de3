//! A merge refused for shards rendered with other settings names the settings that differ,
//! instead of printing both settings strings whole (issue 32).

#[path = "support/example.rs"]
mod example;
#[path = "support/scratch.rs"]
mod scratch;

use example::{assert_ok, assert_refused, run};

#[test]
fn a_settings_mismatch_names_the_differing_settings() {
    let dir = scratch::Scratch::new("mismatch");
    let (a, b, merged) = (dir.path("a.exr"), dir.path("b.exr"), dir.path("m.exr"));
    let shard = |out: &str, first: &str, extra: &[&'static str]| {
        let mut args = vec![
            "--mode",
            "progressive",
            "--size",
            "8x8",
            "--photons",
            "500",
            "--passes",
            "1",
        ];
        args.extend_from_slice(extra);
        let mut args: Vec<String> = args.into_iter().map(str::to_owned).collect();
        args.extend(["--first-pass".into(), first.into(), "--out".into(), out.into()]);
        args
    };
    for args in [shard(&a, "0", &[]), shard(&b, "1", &["--spp", "2", "--k", "50"])] {
        let args: Vec<&str> = args.iter().map(String::as_str).collect();
        let Some(output) = run(&args) else { return };
        assert_ok(&args, &output);
    }
    let args = ["--merge", &a, &b, "--out", &merged];
    let Some(output) = run(&args) else { return };
    assert_refused(&args, &output, "spp 1 against 2");
    let stderr = String::from_utf8_lossy(&output.stderr);
    assert!(stderr.contains("k 100 against 50"), "{stderr}");
    assert!(
        !stderr.contains("photons"),
        "names a setting that does not differ: {stderr}"
    );
}
