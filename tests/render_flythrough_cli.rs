//! The render example's `--frames N --orbit DEGREES`: frames at the scene's own camera are the
//! bytes of a normal run (one cache, rendered again per frame, changes nothing); a turned
//! camera gives another image; a loaded cache gives the frames of the built one; and the
//! options are refused where no cache is read and for nonsense values.

#[path = "support/scratch.rs"]
mod scratch;
use scratch::Scratch;
#[path = "support/example.rs"]
mod example;
use example::{assert_ok, assert_refused, run};

const COMMON: [&str; 6] = ["--size", "16x16", "--photons", "5000", "--spp", "1"];

fn render(extra: &[&str]) -> Option<()> {
    let mut args = COMMON.to_vec();
    args.extend(extra);
    let output = run(&args)?;
    assert_ok(&args, &output);
    Some(())
}

#[test]
fn frames_at_the_scene_camera_are_the_normal_image_and_turned_frames_differ() {
    let dir = Scratch::new("render-flythrough-cli");
    let (one, still, turn) = (dir.path("one.exr"), dir.path("still.exr"), dir.path("turn.exr"));
    let (cache, loaded, json) = (dir.path("c.cache"), dir.path("loaded.exr"), dir.path("f.json"));
    let Some(()) = render(&["--out", &one]) else {
        return;
    };
    let read = |name: &str| std::fs::read(dir.path(name)).unwrap();
    render(&[
        "--out",
        &still,
        "--frames",
        "3",
        "--orbit",
        "0",
        "--stats-json",
        &json,
    ]);
    for frame in ["still-0", "still-1", "still-2"] {
        assert_eq!(read(&format!("{frame}.exr")), read("one.exr"), "{frame}.exr");
        assert_eq!(read(&format!("{frame}.png")), read("one.png"), "{frame}.png");
    }
    let figures = std::fs::read_to_string(&json).unwrap();
    assert!(figures.contains("\"setup\": {") && figures.contains("\"frame\": 2"));
    render(&[
        "--out",
        &turn,
        "--frames",
        "2",
        "--orbit",
        "90",
        "--save-cache",
        &cache,
    ]);
    assert_eq!(read("turn-0.exr"), read("one.exr"));
    assert_ne!(read("turn-1.exr"), read("one.exr"));
    render(&[
        "--out",
        &loaded,
        "--frames",
        "2",
        "--orbit",
        "90",
        "--load-cache",
        &cache,
    ]);
    assert_eq!(read("loaded-0.exr"), read("turn-0.exr"));
    assert_eq!(read("loaded-1.exr"), read("turn-1.exr"));
    // The fewest frames: one, numbered 0, the normal image.
    let single = dir.path("single.exr");
    render(&["--out", &single, "--frames", "1", "--orbit", "45"]);
    assert_eq!(read("single-0.exr"), read("one.exr"));
}

#[test]
fn frames_are_refused_where_no_cache_is_read_and_for_nonsense_values() {
    let dir = Scratch::new("render-flythrough-cli-refused");
    let out = dir.path("x.exr");
    let frame = dir.path("x-1.png");
    let fly = ["--frames", "2", "--orbit", "10"];
    let cases: Vec<(Vec<&str>, &str)> = vec![
        ([&["--mode", "path-trace"][..], &fly].concat(), "--frames"),
        ([&["--mode", "progressive"][..], &fly].concat(), "--frames"),
        ([&["--mode", "sppm"][..], &fly].concat(), "--frames"),
        ([&["--compare"][..], &fly].concat(), "--compare"),
        (vec!["--frames", "0", "--orbit", "10"], "--frames 0"),
        (vec!["--frames", "10001", "--orbit", "10"], "--frames 10001"),
        (vec!["--frames", "2", "--orbit", "NaN"], "--orbit"),
        (vec!["--frames", "2", "--orbit", "400"], "--orbit 400"),
        (vec!["--frames", "2"], "needs --orbit"),
        (vec!["--orbit", "10"], "needs --frames"),
        ([&fly[..], &["--stats-json", &frame]].concat(), "same file"),
        (
            [&fly[..], &["--load-cache", &frame]].concat(),
            "an output may not replace an input",
        ),
    ];
    for (args, needle) in cases {
        let mut all = vec!["--size", "8x8", "--out", &out];
        all.extend(args.iter().copied());
        let Some(output) = run(&all) else { return };
        assert_refused(&all, &output, needle);
    }
}
