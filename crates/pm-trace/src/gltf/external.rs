//! The files a glTF scene reads besides itself: its buffers' and images' relative URIs, as
//! the loader resolves them (inside the scene's folder), so that a caller can keep its
//! outputs from replacing them.

use std::path::{Path, PathBuf};

use super::buffers::{confined_target, has_prefix_ignore_case};
use super::error::GltfError;
use super::options::GltfOptions;
use super::source::{parse, read_bounded};

/// The canonical paths of the files scene `path` names as buffers or images (not `data:`
/// URIs or the GLB chunk), resolved as the loader resolves them; a URI the loader would
/// refuse (outside the folder, missing, a scheme) is left out, to fail when the scene is
/// loaded. Errors only when the scene file itself cannot be read or parsed.
pub fn external_files(path: &Path, options: &GltfOptions) -> Result<Vec<PathBuf>, GltfError> {
    let bytes = read_bounded(path, options.max_file_bytes)?;
    let (root, _, _) = parse(path, &bytes)?;
    let folder = path
        .parent()
        .filter(|p| !p.as_os_str().is_empty())
        .unwrap_or(Path::new("."));
    let uris = root
        .buffers
        .iter()
        .filter_map(|b| b.uri.as_deref())
        .chain(root.images.iter().filter_map(|i| i.uri.as_deref()));
    let mut files: Vec<PathBuf> = uris
        .filter(|uri| !has_prefix_ignore_case(uri, "data:"))
        .filter_map(|uri| confined_target(folder, uri).ok())
        .collect();
    files.sort();
    files.dedup();
    Ok(files)
}
