//! The names that changed keep working: `Mode::Visualize` and the mode name `visualize` are
//! the photon-map mode (the name is the command line's to parse), and the render example's `--mode visualize --spp N` writes the very
//! image `--mode photon-map --samples-per-pixel N` writes.

#[path = "support/example.rs"]
mod example;

use photon_maps::render::Mode;

#[test]
#[allow(deprecated)]
fn the_old_mode_name_is_the_photon_map_mode() {
    assert_eq!(Mode::Visualize, Mode::PhotonMap);
    assert_eq!(Mode::PhotonMap.name(), "photon-map");
}

#[test]
fn the_old_cli_names_render_the_same_image() {
    let dir = std::env::temp_dir().join(format!("pm-old-names-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let render = |name: &str, args: &[&str]| {
        let out = dir.join(format!("{name}.exr"));
        let common = [
            "--size",
            "24x16",
            "--photons",
            "3000",
            "--out",
            out.to_str().unwrap(),
        ];
        let all: Vec<&str> = args.iter().chain(common.iter()).copied().collect();
        let output = example::run(&all)?;
        assert!(
            output.status.success(),
            "{}",
            String::from_utf8_lossy(&output.stderr)
        );
        Some(std::fs::read(&out).unwrap())
    };
    let Some(old) = render("old", &["--mode", "visualize", "--spp", "2"]) else {
        return;
    };
    let new = render("new", &["--mode", "photon-map", "--samples-per-pixel", "2"]).unwrap();
    let one_sample = render("one", &["--mode", "photon-map"]).unwrap();
    assert_eq!(old, new, "the old names give the same image");
    assert_ne!(new, one_sample, "the sample count reaches the renderer");
    std::fs::remove_dir_all(&dir).ok();
}
