//! Reading the scene file: a bounded read, a check of a GLB container's length fields against
//! the bytes actually present, and the gltf crate's parser behind a panic guard.

use std::fs::File;
use std::io::Read;
use std::panic::{AssertUnwindSafe, catch_unwind};
use std::path::Path;

use gltf::json;
use json::validation::Checked;

use super::error::GltfError;

/// Reads at most `limit` bytes of `path`; a longer file is an error, never a truncated read.
pub(super) fn read_bounded(path: &Path, limit: u64) -> Result<Vec<u8>, GltfError> {
    let io = |source| GltfError::Io {
        file: path.to_path_buf(),
        source,
    };
    let not_regular = || {
        io(std::io::Error::new(
            std::io::ErrorKind::InvalidInput,
            "not a regular file (a FIFO, device or folder is never opened)",
        ))
    };
    // Check the type before opening: opening a FIFO blocks until a writer appears.
    if !std::fs::metadata(path).map_err(io)?.is_file() {
        return Err(not_regular());
    }
    let file = File::open(path).map_err(io)?;
    let meta = file.metadata().map_err(io)?;
    if !meta.is_file() {
        return Err(not_regular());
    }
    let mut bytes = Vec::with_capacity(meta.len().min(limit) as usize);
    file.take(limit.saturating_add(1))
        .read_to_end(&mut bytes)
        .map_err(io)?;
    if bytes.len() as u64 > limit {
        return Err(GltfError::FileTooLarge {
            file: path.to_path_buf(),
            limit,
        });
    }
    Ok(bytes)
}

const GLB_MAGIC: &[u8; 4] = b"glTF";
const CHUNK_JSON: u32 = 0x4E4F_534A;
const CHUNK_BIN: u32 = 0x004E_4942;

fn u32_at(bytes: &[u8], at: usize) -> Option<u32> {
    let b = bytes.get(at..at.checked_add(4)?)?;
    Some(u32::from_le_bytes([b[0], b[1], b[2], b[3]]))
}

/// Checks a GLB container's header and chunk lengths against the bytes present, so that the
/// gltf crate never sees a length that lies. Bytes that are not a GLB pass unchanged.
pub(super) fn check_glb(bytes: &[u8]) -> Result<(), String> {
    if !bytes.starts_with(GLB_MAGIC) {
        return Ok(());
    }
    let (Some(version), Some(length)) = (u32_at(bytes, 4), u32_at(bytes, 8)) else {
        return Err(format!("header cut short: {} bytes", bytes.len()));
    };
    if version != 2 {
        return Err(format!("version {version}, only 2 is supported"));
    }
    if length as usize != bytes.len() {
        return Err(format!(
            "header says {length} bytes, the file has {}",
            bytes.len()
        ));
    }
    let mut at = 12usize;
    let mut index = 0;
    while at < bytes.len() {
        let (Some(chunk_len), Some(kind)) = (u32_at(bytes, at), u32_at(bytes, at + 4)) else {
            return Err(format!("chunk {index} header cut short at byte {at}"));
        };
        let end = (at + 8)
            .checked_add(chunk_len as usize)
            .filter(|&end| end <= bytes.len())
            .ok_or_else(|| format!("chunk {index} declares {chunk_len} bytes, past the end of the file"))?;
        match (index, kind) {
            (0, CHUNK_JSON) | (1, CHUNK_BIN) => {}
            (0, _) => return Err("the first chunk is not JSON".into()),
            (1, CHUNK_JSON) => return Err("a second JSON chunk".into()),
            _ => {} // unknown chunks are skipped by the spec
        }
        at = end;
        index += 1;
    }
    if index == 0 {
        return Err("no JSON chunk".into());
    }
    Ok(())
}

/// The document's JSON text: a GLB container's first chunk (whose lengths [`check_glb`] has
/// checked; empty if they do not hold), else all of `bytes`, as the gltf crate tells them apart.
pub(super) fn json_text(bytes: &[u8]) -> &[u8] {
    if !bytes.starts_with(GLB_MAGIC) {
        return bytes;
    }
    let chunk = u32_at(bytes, 12).and_then(|len| bytes.get(20..20usize.checked_add(len as usize)?));
    chunk.unwrap_or_default()
}

/// Runs `f`, turning a panic into [`GltfError::Panic`]. The gltf crate panics on some
/// malformed files; this is the last line of defence after our own checks. It installs no
/// panic hook, so the process's hook may still print the panic message.
pub(super) fn guard<T>(file: &Path, f: impl FnOnce() -> Result<T, GltfError>) -> Result<T, GltfError> {
    match catch_unwind(AssertUnwindSafe(f)) {
        Ok(result) => result,
        Err(payload) => {
            let message = payload
                .downcast_ref::<&str>()
                .map(|s| (*s).to_owned())
                .or_else(|| payload.downcast_ref::<String>().cloned())
                .unwrap_or_else(|| "non-string panic payload".to_owned());
            Err(GltfError::Panic {
                file: file.to_path_buf(),
                message,
            })
        }
    }
}

/// The parsed root, the GLB binary chunk if any, and warnings.
type Parsed = (json::Root, Option<Vec<u8>>, Vec<String>);

/// Parses `.gltf` JSON or a `.glb` container (checked first), then validates it with the
/// gltf crate after our own checks of what its validator would index blindly.
/// Also returns warnings about what was patched (textures naming missing images that no
/// material uses).
pub(super) fn parse(file: &Path, bytes: &[u8]) -> Result<Parsed, GltfError> {
    check_glb(bytes).map_err(|reason| GltfError::Glb {
        file: file.to_path_buf(),
        reason,
    })?;
    // The crate's own messages may start with the words our Display adds.
    let invalid = |e: gltf::Error| GltfError::Parse {
        file: file.to_path_buf(),
        message: strip_prefix_ignore_case(&e.to_string(), "invalid glTF: ").to_owned(),
    };
    guard(file, || {
        let gltf::Gltf { document, blob } =
            gltf::Gltf::from_slice_without_validation(bytes).map_err(invalid)?;
        let mut root = document.into_json();
        check_position_accessors(file, &root)?;
        let warnings = patch_unused_broken_textures(&mut root);
        let document = gltf::Document::from_json(root).map_err(invalid)?;
        Ok((document.into_json(), blob, warnings))
    })
}

fn strip_prefix_ignore_case<'a>(text: &'a str, prefix: &str) -> &'a str {
    match text.get(..prefix.len()) {
        Some(head) if head.eq_ignore_ascii_case(prefix) => &text[prefix.len()..],
        _ => text,
    }
}

/// A texture naming an image that does not exist fails the gltf crate's validation, even
/// when no material uses it (the nvpro Cornell box). Such unused textures are pointed at a
/// placeholder image that is never decoded, with a warning; a used one is left to fail.
fn patch_unused_broken_textures(root: &mut json::Root) -> Vec<String> {
    let used: std::collections::HashSet<usize> = root
        .materials
        .iter()
        .flat_map(|m| {
            let pbr = &m.pbr_metallic_roughness;
            let specular = m.extensions.as_ref().and_then(|e| e.specular.as_ref());
            [
                pbr.base_color_texture.as_ref().map(|t| t.index.value()),
                pbr.metallic_roughness_texture.as_ref().map(|t| t.index.value()),
                specular
                    .and_then(|s| s.specular_texture.as_ref())
                    .map(|t| t.index.value()),
                specular
                    .and_then(|s| s.specular_color_texture.as_ref())
                    .map(|t| t.index.value()),
                m.normal_texture.as_ref().map(|t| t.index.value()),
                m.occlusion_texture.as_ref().map(|t| t.index.value()),
                m.emissive_texture.as_ref().map(|t| t.index.value()),
            ]
        })
        .flatten()
        .collect();
    let images = root.images.len();
    let mut warnings = Vec::new();
    let mut placeholder = None;
    for (i, t) in root.textures.iter_mut().enumerate() {
        let source = t.source.value();
        if source < images || used.contains(&i) {
            continue;
        }
        warnings.push(format!(
            "texture {i} names image {source}, which does not exist (the file has {images}); no material uses it, so it is ignored"
        ));
        let index = *placeholder.get_or_insert(images);
        t.source = json::Index::new(index as u32);
    }
    if placeholder.is_some() {
        root.images.push(json::Image {
            buffer_view: None,
            mime_type: None,
            name: None,
            uri: Some("data:,".into()),
            extensions: None,
            extras: Default::default(),
        });
    }
    warnings
}

/// The gltf crate's validator indexes `accessors` with each `POSITION` attribute unchecked
/// (it panics on a missing one); check them first.
fn check_position_accessors(file: &Path, root: &json::Root) -> Result<(), GltfError> {
    for (mesh, m) in root.meshes.iter().enumerate() {
        for (primitive, p) in m.primitives.iter().enumerate() {
            let position = p.attributes.get(&Checked::Valid(json::mesh::Semantic::Positions));
            if let Some(accessor) = position
                && accessor.value() >= root.accessors.len()
            {
                return Err(GltfError::Primitive {
                    file: file.to_path_buf(),
                    mesh,
                    primitive,
                    reason: format!(
                        "POSITION accessor {} does not exist (the file has {})",
                        accessor.value(),
                        root.accessors.len()
                    ),
                });
            }
        }
    }
    Ok(())
}
