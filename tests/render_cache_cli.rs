//! The render example's `--save-cache` and `--load-cache`: refused where no photons are read
//! (path-trace, progressive, SPPM, --compare) and where the cache file would replace an output;
//! a save then a load write the same image bytes, the load saying it traced nothing.

#[path = "support/scratch.rs"]
mod scratch;
use scratch::Scratch;
#[path = "support/example.rs"]
mod example;
use example::{assert_ok, assert_refused, run};

#[test]
fn cache_options_are_refused_where_they_do_not_apply() {
    let dir = Scratch::new("render-cache-cli-refused");
    let cache = dir.path("c.cache");
    let out = dir.path("x.exr");
    let png = dir.path("x.png");
    for (args, needle) in [
        (
            vec!["--mode", "path-trace", "--save-cache", &cache],
            "--save-cache",
        ),
        (vec!["--mode", "sppm", "--load-cache", &cache], "--load-cache"),
        (
            vec!["--mode", "progressive", "--save-cache", &cache],
            "--save-cache",
        ),
        (vec!["--compare", "--save-cache", &cache], "--save-cache"),
        (vec!["--save-cache", &png], "same file"),
    ] {
        let mut all = vec!["--size", "8x8", "--out", &out];
        all.extend(args.iter().copied());
        let Some(output) = run(&all) else { return };
        assert_refused(&all, &output, needle);
    }
}

#[test]
fn save_then_load_writes_the_same_image_bytes() {
    let dir = Scratch::new("render-cache-cli-round-trip");
    let cache = dir.path("c.cache");
    let (fresh, loaded) = (dir.path("fresh.exr"), dir.path("loaded.exr"));
    let json = dir.path("loaded.json");
    let common = ["--size", "24x24", "--photons", "20000", "--spp", "2"];
    let mut save = common.to_vec();
    save.extend(["--save-cache", &cache, "--out", &fresh]);
    let Some(output) = run(&save) else { return };
    assert_ok(&save, &output);
    let mut load = common.to_vec();
    load.extend(["--load-cache", &cache, "--out", &loaded, "--stats-json", &json]);
    let Some(output) = run(&load) else { return };
    assert_ok(&load, &output);
    assert!(String::from_utf8_lossy(&output.stdout).contains("no tracing or building"));
    assert!(
        std::fs::read_to_string(&json)
            .unwrap()
            .contains("\"cache\": \"loaded\"")
    );
    assert_eq!(std::fs::read(&fresh).unwrap(), std::fs::read(&loaded).unwrap());
    // Other settings: refused by name.
    let mut other = load.clone();
    other[3] = "20001";
    let Some(output) = run(&other) else { return };
    assert_refused(&other, &output, "photons=20000");
}
