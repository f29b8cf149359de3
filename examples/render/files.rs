//! The render example's files: the scene it reads (a built-in name or a glTF path, with a
//! message that names what is wrong) and the outputs it checks before rendering.

use photon_maps::render::image::{check_output_path, write_atomically};
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
    let name = path
        .file_stem()
        .and_then(|s| s.to_str())
        .unwrap_or("scene")
        .to_owned();
    let options = GltfOptions {
        light_units: units,
        ..GltfOptions::default()
    };
    photon_maps::trace::gltf::load_scene_with(path, &options)
        .map(|s| (s, name))
        .map_err(|e| e.to_string())
}

/// Prints a line to stdout; a closed pipe (`render | head -1`) is not an error worth a panic.
pub fn say(line: &str) {
    let _ = writeln!(std::io::stdout().lock(), "{line}");
}

/// Creates the parent folder, refuses a target that is not a regular file (a folder, a
/// device, a FIFO) and checks a file can be made beside it, so a bad path fails before the
/// render; the target itself is not opened or touched.
pub fn check_writable(path: &Path) -> Result<(), String> {
    let fail = |e: std::io::Error| format!("cannot write {}: {e}", path.display());
    if let Some(parent) = path.parent().filter(|p| !p.as_os_str().is_empty()) {
        fs::create_dir_all(parent).map_err(fail)?;
    }
    check_output_path(path).map_err(|e| e.to_string())?;
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

/// Refuses two outputs that are one file (`--stats-json` naming the image, or a link to it).
pub fn refuse_shared_outputs(outputs: &[&Path]) -> Result<(), String> {
    let identity = |path: &Path| -> PathBuf {
        // Existing files (and links to them) by their canonical path; new ones by their
        // canonical folder and name.
        if let Ok(p) = fs::canonicalize(path) {
            return p;
        }
        let folder = path.parent().filter(|p| !p.as_os_str().is_empty());
        let folder = folder.map_or_else(|| fs::canonicalize("."), fs::canonicalize);
        match (folder, path.file_name()) {
            (Ok(folder), Some(name)) => folder.join(name),
            _ => path.to_path_buf(),
        }
    };
    for (i, a) in outputs.iter().enumerate() {
        for b in &outputs[i + 1..] {
            if identity(a) == identity(b) {
                return Err(format!(
                    "outputs {} and {} are the same file; give each output its own path",
                    a.display(),
                    b.display()
                ));
            }
        }
    }
    Ok(())
}
