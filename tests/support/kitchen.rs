//! The obvhs crate's kitchen, converted to glTF by `scripts/kitchen-gltf.py` (never committed),
//! for the tests and benches that measure a real exported interior. Include it with
//! `#[path = "support/kitchen.rs"] mod kitchen;` (from `tests/`) or
//! `#[path = "../tests/support/kitchen.rs"] mod kitchen;` (from `benches/`).

use photon_maps::trace::Scene;
use std::path::{Path, PathBuf};

/// Where the converted kitchen is: `PM_KITCHEN_GLTF`, or the conversion script's default,
/// `target/kitchen/kitchen.gltf`.
pub fn kitchen_path() -> PathBuf {
    std::env::var_os("PM_KITCHEN_GLTF").map_or_else(
        || Path::new(env!("CARGO_MANIFEST_DIR")).join("target/kitchen/kitchen.gltf"),
        PathBuf::from,
    )
}

/// The kitchen at `path`, or `None` with a message saying it was skipped when the file is
/// not there (a user's clone, or CI's).
pub fn load_kitchen(path: &Path) -> Option<Scene> {
    if !path.is_file() {
        eprintln!(
            "skipped: {} not found (run scripts/kitchen-gltf.py, which needs the obvhs crate's kitchen in the cargo registry)",
            path.display()
        );
        return None;
    }
    Some(photon_maps::trace::gltf::load_scene(path).expect("the kitchen loads"))
}
