//! The render example's files: the scene it reads (a built-in name or a glTF path, with a
//! message that names what is wrong) and the outputs it checks before rendering.

use photon_maps::render::image::{check_output_path, output_target, write_atomically};
use photon_maps::trace::gltf::{GltfOptions, LightUnits};
use photon_maps::trace::{Scene, scenes};
use std::fs;
use std::io::Write as _;
use std::path::{Path, PathBuf};

/// A built-in scene by name, or a glTF file by path (its lights read in `units`); also the name
/// used for output files.
pub fn load_scene(arg: &str, units: LightUnits) -> Result<(Scene, String), String> {
    let path = Path::new(arg);
    let extension = path
        .extension()
        .and_then(|e| e.to_str())
        .map(str::to_ascii_lowercase);
    let is_gltf = matches!(extension.as_deref(), Some("gltf" | "glb"));
    if path.is_dir() {
        return Err(format!(
            "scene {arg} is a folder: give a .gltf or .glb file, or a built-in scene ({})",
            scenes::NAMES.join(", ")
        ));
    }
    if let Some(ext) = extension.as_deref().filter(|_| !is_gltf) {
        return Err(format!(
            "scene {arg}: .{ext} files are not read; give a .gltf or .glb file, or a built-in scene ({})",
            scenes::NAMES.join(", ")
        ));
    }
    if !is_gltf && !arg.contains(['/', '\\']) {
        return scenes::build(arg)
            .map(|s| (s, arg.to_owned()))
            .map_err(|e| e.to_string());
    }
    if !path.is_file() {
        return Err(format!("scene file not found: {arg}"));
    }
    let name = scene_name(arg);
    let options = GltfOptions {
        light_units: units,
        ..GltfOptions::default()
    };
    photon_maps::trace::gltf::load_scene_with(path, &options)
        .map(|s| (s, name))
        .map_err(|e| e.to_string())
}

/// The name used for output files: a built-in scene's name, or a file's stem. Known without
/// loading the scene, so outputs are checked before it is read.
pub fn scene_name(arg: &str) -> String {
    let path = Path::new(arg);
    if arg.contains(['/', '\\']) || path.extension().is_some() {
        path.file_stem()
            .and_then(|s| s.to_str())
            .unwrap_or("scene")
            .to_owned()
    } else {
        arg.to_owned()
    }
}

/// Prints a line to stdout; a closed pipe (`render | head -1`) is not an error worth a panic.
pub fn say(line: &str) {
    let _ = writeln!(std::io::stdout().lock(), "{line}");
}

/// A file a run reads or writes, with the option that names it in messages.
pub struct NamedFile<'a> {
    /// How the user named it (`--out`, `--out's PNG sibling`, `--scene`, `shard`).
    pub option: &'static str,
    /// The path as given.
    pub path: &'a Path,
}

/// The one check of a run's outputs, made before anything is rendered, the same in every
/// mode: each output can be written (its folder is created; a folder, device, FIFO or
/// read-only file is refused), no two outputs are one file, and no output is an input (the
/// scene file, a shard). Files are compared by what a write would replace: links followed
/// (a dangling link to the file it would create), folders canonicalised, so `x.exr`,
/// `./x.exr` and a link to it are one file whether or not it exists yet.
pub fn check_outputs(outputs: &[NamedFile<'_>], inputs: &[NamedFile<'_>]) -> Result<(), String> {
    let mut seen: Vec<(PathBuf, &NamedFile<'_>)> = Vec::new();
    for output in outputs {
        check_writable(output.path)?;
        let identity = file_identity(output.path)?;
        if let Some((_, other)) = seen.iter().find(|(id, _)| *id == identity) {
            return Err(format!(
                "{} {} and {} {} are the same file; give each output its own path",
                other.option,
                other.path.display(),
                output.option,
                output.path.display()
            ));
        }
        for input in inputs {
            if file_identity(input.path).is_ok_and(|id| id == identity) {
                return Err(format!(
                    "{} {} is the same file as the {} {} it reads; an output may not replace an input",
                    output.option,
                    output.path.display(),
                    input.option,
                    input.path.display()
                ));
            }
        }
        seen.push((identity, output));
    }
    Ok(())
}

/// What a write to `path` replaces, as a canonical path: the link target followed, its
/// folder canonicalised and its name kept.
fn file_identity(path: &Path) -> Result<PathBuf, String> {
    let fail = |e: std::io::Error| format!("{}: {e}", path.display());
    let target = output_target(path).map_err(fail)?;
    let folder = target.parent().filter(|p| !p.as_os_str().is_empty());
    let folder = folder.map_or_else(|| fs::canonicalize("."), fs::canonicalize);
    match (folder, target.file_name()) {
        (Ok(folder), Some(name)) => Ok(folder.join(name)),
        (Err(e), _) => Err(fail(e)),
        (_, None) => Err(format!("{}: not a file name", path.display())),
    }
}

/// Creates the parent folder, refuses a target that is not a regular file (a folder, a
/// device, a FIFO) or is read-only, and checks a file can be made beside it, so a bad path
/// fails before the render; the target itself is not opened or touched.
fn check_writable(path: &Path) -> Result<(), String> {
    let fail = |e: std::io::Error| format!("cannot write {}: {e}", path.display());
    if let Some(parent) = path.parent().filter(|p| !p.as_os_str().is_empty()) {
        fs::create_dir_all(parent).map_err(fail)?;
    }
    check_output_path(path).map_err(fail)?;
    // An empty atomic write to a file that is then removed: the target is never named.
    let probe = path.with_file_name(format!(
        ".{}.probe-{}",
        path.file_name().and_then(|n| n.to_str()).unwrap_or("out"),
        std::process::id()
    ));
    write_atomically(&probe, |_| Ok(())).map_err(fail)?;
    fs::remove_file(&probe).ok();
    Ok(())
}

/// The outputs of a run in any mode: the .exr and .png siblings of `base` and the figures'
/// JSON, checked by [`check_outputs`] against each other and `inputs`; returns the image
/// paths.
pub fn check_run_outputs(
    base: &Path,
    stats_json: Option<&Path>,
    inputs: &[NamedFile<'_>],
) -> Result<(PathBuf, PathBuf), String> {
    if base.is_dir() {
        return Err(format!(
            "--out {} is a folder; name a file (its .exr and .png siblings are written)",
            base.display()
        ));
    }
    let (exr, png) = (base.with_extension("exr"), base.with_extension("png"));
    check_outputs(&run_outputs(&exr, &png, stats_json), inputs)?;
    Ok((exr, png))
}

/// A run's image files and its figures' JSON, named by the options that give them.
fn run_outputs<'a>(exr: &'a Path, png: &'a Path, stats_json: Option<&'a Path>) -> Vec<NamedFile<'a>> {
    let images = [("--out's EXR", exr), ("--out's PNG", png)];
    images
        .into_iter()
        .chain(stats_json.map(|path| ("--stats-json", path)))
        .map(|(option, path)| NamedFile { option, path })
        .collect()
}

/// The scene file as an input, when `--scene` names a file rather than a built-in scene.
pub fn scene_input(scene: &str) -> Option<NamedFile<'_>> {
    let path = Path::new(scene);
    path.is_file().then_some(NamedFile {
        option: "--scene",
        path,
    })
}

/// The files a glTF scene reads besides itself (its buffer and image files, as the loader
/// resolves them), which no output may replace either; none for a built-in scene, a `.glb`
/// whose URIs name none, or a file that does not parse (its load reports that).
pub fn scene_dependencies(scene: &str) -> Vec<PathBuf> {
    match scene_input(scene) {
        Some(input) => {
            photon_maps::trace::gltf::external_files(input.path, &Default::default()).unwrap_or_default()
        }
        None => Vec::new(),
    }
}

/// Every file the scene reads, as inputs for [`check_outputs`]; `dependencies` from
/// [`scene_dependencies`].
pub fn scene_inputs<'a>(scene: &'a str, dependencies: &'a [PathBuf]) -> Vec<NamedFile<'a>> {
    let files = dependencies.iter().map(|path| NamedFile {
        option: "scene's buffer or image",
        path,
    });
    scene_input(scene).into_iter().chain(files).collect()
}

/// `--save-cache`'s file, checked with the run's other outputs: writable, not one of them and
/// not an input ([`check_outputs`]).
pub fn check_cache_output(
    cache: &Path,
    base: &Path,
    stats_json: Option<&Path>,
    inputs: &[NamedFile<'_>],
) -> Result<(), String> {
    let (exr, png) = (base.with_extension("exr"), base.with_extension("png"));
    let mut outputs = run_outputs(&exr, &png, stats_json);
    outputs.push(NamedFile {
        option: "--save-cache",
        path: cache,
    });
    check_outputs(&outputs, inputs)
}
