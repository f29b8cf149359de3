//! Files a run reads: refused unless they are regular files (following links) within a size
//! bound, checked before they are opened. A FIFO would block the reader for ever and a
//! device (`/dev/zero`) never ends; both are refused by name, never read.

use crate::error::RenderError;
use std::io::Read as _;
use std::path::Path;

/// Checks that `path` names a regular file (links followed) of at most `max_bytes` bytes,
/// without opening it; returns its size.
pub fn check_input_file(path: &Path, max_bytes: u64) -> Result<u64, RenderError> {
    let meta = std::fs::metadata(path).map_err(|e| RenderError::ImageIo {
        path: path.to_path_buf(),
        message: e.to_string(),
    })?;
    if !meta.is_file() {
        return Err(RenderError::NotARegularFile {
            path: path.to_path_buf(),
        });
    }
    if meta.len() > max_bytes {
        return Err(RenderError::InputTooLarge {
            path: path.to_path_buf(),
            bytes: meta.len(),
            max_bytes,
        });
    }
    Ok(meta.len())
}

/// Reads a UTF-8 text file of at most `max_bytes` bytes after [`check_input_file`]; a file
/// that grows past the bound while it is read is refused too (the read stops there).
pub fn read_text_file(path: &Path, max_bytes: u64) -> Result<String, RenderError> {
    let size = check_input_file(path, max_bytes)?;
    let io = |e: std::io::Error| RenderError::ImageIo {
        path: path.to_path_buf(),
        message: e.to_string(),
    };
    let file = std::fs::File::open(path).map_err(io)?;
    let mut bytes = Vec::with_capacity(size as usize);
    file.take(max_bytes.saturating_add(1))
        .read_to_end(&mut bytes)
        .map_err(io)?;
    if bytes.len() as u64 > max_bytes {
        return Err(RenderError::InputTooLarge {
            path: path.to_path_buf(),
            bytes: bytes.len() as u64,
            max_bytes,
        });
    }
    String::from_utf8(bytes).map_err(|e| RenderError::ImageIo {
        path: path.to_path_buf(),
        message: format!("not UTF-8 text: {e}"),
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn devices_folders_and_large_files_are_refused_before_they_are_read() {
        let dir = std::env::temp_dir().join(format!("pm-input-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let text = dir.join("a.txt");
        std::fs::write(&text, "twelve bytes").unwrap();
        assert_eq!(read_text_file(&text, 12).unwrap(), "twelve bytes");
        assert!(matches!(
            read_text_file(&text, 11),
            Err(RenderError::InputTooLarge {
                bytes: 12,
                max_bytes: 11,
                ..
            })
        ));
        assert!(matches!(
            check_input_file(&dir, u64::MAX),
            Err(RenderError::NotARegularFile { .. })
        ));
        #[cfg(unix)]
        assert!(matches!(
            read_text_file(Path::new("/dev/zero"), 1 << 20),
            Err(RenderError::NotARegularFile { .. })
        ));
        assert!(matches!(
            check_input_file(&dir.join("missing"), 1),
            Err(RenderError::ImageIo { .. })
        ));
        std::fs::remove_dir_all(&dir).unwrap();
    }
}
