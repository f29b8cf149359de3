//! The study's scenes: a built-in scene by name, or a glTF file by path, named by its file
//! stem in the record, the references' files and the charts (the record keeps the path, so
//! that a re-score loads the same file).

use photon_maps::trace::gltf::{GltfOptions, load_scene_with};
use photon_maps::trace::{Scene, scenes};
use std::path::Path;

/// The scene `arg` names and the name the study files it under: a built-in scene's own name,
/// or a `.gltf`/`.glb` file's stem (its lights in the glTF specification's units).
pub fn load(arg: &str) -> Result<(Scene, String), String> {
    let path = Path::new(arg);
    let is_gltf = path
        .extension()
        .and_then(|e| e.to_str())
        .is_some_and(|e| e.eq_ignore_ascii_case("gltf") || e.eq_ignore_ascii_case("glb"));
    if !is_gltf {
        return scenes::build(arg)
            .map(|scene| (scene, arg.to_owned()))
            .map_err(|e| e.to_string());
    }
    let name = path
        .file_stem()
        .and_then(|s| s.to_str())
        .filter(|s| !s.is_empty())
        .ok_or_else(|| format!("scene {arg}: no file name to file the study under"))?;
    let scene = load_scene_with(path, &GltfOptions::default()).map_err(|e| format!("{arg}: {e}"))?;
    Ok((scene, name.to_owned()))
}
