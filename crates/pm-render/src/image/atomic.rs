//! Atomic file writes: the bytes go to a temporary file beside the target, which is renamed over
//! the target only once everything is written, so a failed write never loses the old file.

use std::fs::{self, File, OpenOptions};
use std::io::{self, BufWriter};
use std::path::{Path, PathBuf};
use std::sync::atomic::{AtomicU64, Ordering};

/// Writes a file atomically: `write` fills a buffered temporary file in the target's folder,
/// which then replaces the target by a rename. On any error the temporary file is removed and
/// the target (and any symbolic link naming it) is left exactly as it was.
///
/// - A symbolic link is kept: the file it points to is replaced (in that file's folder).
/// - A target that exists but is not a regular file (a folder, a device, a FIFO, a socket) is
///   refused with [`io::ErrorKind::InvalidInput`] before anything is created.
/// - A file replaced keeps its permissions; a new file gets the default permissions of a
///   newly created file.
/// - A target whose permissions allow no writing is refused with
///   [`io::ErrorKind::PermissionDenied`] (even for a user, such as root, whom the system
///   would let write it): replacing it would undo the protection.
///
/// ```
/// # let dir = std::env::temp_dir().join(format!("pm-atomic-doc-{}", std::process::id()));
/// # std::fs::create_dir_all(&dir)?;
/// use std::io::Write;
/// let path = dir.join("figures.json");
/// pm_render::image::write_atomically(&path, |w| w.write_all(b"{}\n"))?;
/// assert_eq!(std::fs::read(&path)?, b"{}\n");
/// # std::fs::remove_dir_all(&dir)?;
/// # Ok::<(), std::io::Error>(())
/// ```
pub fn write_atomically(
    path: impl AsRef<Path>,
    write: impl FnOnce(&mut BufWriter<File>) -> io::Result<()>,
) -> io::Result<()> {
    let target = resolve_target(path.as_ref())?;
    let kept = match fs::metadata(&target) {
        Ok(meta) => Some(meta.permissions()),
        Err(e) if e.kind() == io::ErrorKind::NotFound => None,
        Err(e) => return Err(e),
    };
    let (temp_path, file) = create_temp_beside(&target)?;
    let result = (|| {
        let mut writer = BufWriter::new(file);
        write(&mut writer)?;
        let file = writer.into_inner().map_err(|e| e.into_error())?;
        if let Some(permissions) = kept {
            file.set_permissions(permissions)?;
        }
        file.sync_all()?;
        drop(file);
        fs::rename(&temp_path, &target)
    })();
    if result.is_err() {
        let _ = fs::remove_file(&temp_path);
    }
    result
}

/// Checks that `path` names a writable regular file or nothing, following symbolic links to
/// the file to replace, as [`write_atomically`] will. Errors name the path.
pub fn check_output_path(path: impl AsRef<Path>) -> io::Result<()> {
    resolve_target(path.as_ref()).map(|_| ())
}

/// The file a write to `path` replaces or creates: `path` itself, or the final target of the
/// symbolic link it names (also when that target does not exist yet).
pub fn output_target(path: impl AsRef<Path>) -> io::Result<PathBuf> {
    resolve_target(path.as_ref())
}

/// The file to replace: `path` itself, or the final target of the symbolic link it names.
fn resolve_target(path: &Path) -> io::Result<PathBuf> {
    let refuse = |what: &str| {
        io::Error::new(
            io::ErrorKind::InvalidInput,
            format!(
                "{} is {what}, not a regular file; refusing to replace it",
                path.display()
            ),
        )
    };
    if path.as_os_str().is_empty() || path.file_name().is_none() {
        return Err(refuse("not a file name"));
    }
    let mut target = path.to_path_buf();
    // Follow links by hand (bounded, like the kernel's 40) so a dangling link's target is
    // created in its folder rather than the link being replaced.
    for _ in 0..40 {
        match fs::symlink_metadata(&target) {
            Err(e) if e.kind() == io::ErrorKind::NotFound => return Ok(target),
            Err(e) => return Err(e),
            Ok(meta) if meta.file_type().is_symlink() => {
                let link = fs::read_link(&target)?;
                target = match target.parent() {
                    Some(parent) => parent.join(link),
                    None => link,
                };
            }
            Ok(meta) if meta.is_file() => {
                // A rename would replace a file the user may not write (the folder's
                // permission suffices): refuse one without write permission bits, or that
                // the user cannot open for writing (opened, not truncated: nothing changes).
                let writable =
                    !meta.permissions().readonly() && OpenOptions::new().write(true).open(&target).is_ok();
                if !writable {
                    return Err(io::Error::new(
                        io::ErrorKind::PermissionDenied,
                        format!(
                            "{} is read-only (or not writable by this user); refusing to replace it",
                            path.display()
                        ),
                    ));
                }
                return Ok(target);
            }
            Ok(meta) if meta.is_dir() => return Err(refuse("a folder")),
            Ok(_) => return Err(refuse("a device, FIFO or socket")),
        }
    }
    Err(refuse("a chain of too many symbolic links"))
}

/// A new, empty file beside `target` that no other writer uses.
fn create_temp_beside(target: &Path) -> io::Result<(PathBuf, File)> {
    static COUNTER: AtomicU64 = AtomicU64::new(0);
    let folder = match target.parent() {
        Some(p) if !p.as_os_str().is_empty() => p.to_path_buf(),
        _ => PathBuf::from("."),
    };
    let name = target
        .file_name()
        .map(|n| n.to_string_lossy().into_owned())
        .unwrap_or_default();
    loop {
        let n = COUNTER.fetch_add(1, Ordering::Relaxed);
        let temp = folder.join(format!(".{name}.{}-{n}.tmp", std::process::id()));
        match OpenOptions::new().write(true).create_new(true).open(&temp) {
            Ok(file) => return Ok((temp, file)),
            Err(e) if e.kind() == io::ErrorKind::AlreadyExists => continue,
            Err(e) => return Err(e),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::io::Write;

    fn scratch(name: &str) -> PathBuf {
        let dir = std::env::temp_dir().join(format!("pm-atomic-{name}-{}", std::process::id()));
        let _ = fs::remove_dir_all(&dir);
        fs::create_dir_all(&dir).unwrap();
        dir
    }

    fn leftovers(dir: &Path) -> Vec<String> {
        fs::read_dir(dir)
            .unwrap()
            .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
            .filter(|n| n.ends_with(".tmp"))
            .collect()
    }

    #[test]
    fn a_failed_write_leaves_the_previous_file_and_no_temporary() {
        let dir = scratch("fail");
        let path = dir.join("out.json");
        fs::write(&path, b"previous").unwrap();
        let err = write_atomically(&path, |w| {
            w.write_all(b"half of the new")?;
            Err(io::Error::other("disk full"))
        })
        .unwrap_err();
        assert_eq!(err.to_string(), "disk full");
        assert_eq!(fs::read(&path).unwrap(), b"previous");
        assert!(leftovers(&dir).is_empty(), "{:?}", leftovers(&dir));
        write_atomically(&path, |w| w.write_all(b"new")).unwrap();
        assert_eq!(fs::read(&path).unwrap(), b"new");
        fs::remove_dir_all(&dir).ok();
    }

    #[cfg(unix)]
    #[test]
    fn a_symbolic_link_survives_failed_and_successful_writes() {
        let dir = scratch("link");
        let file = dir.join("real.png");
        let link = dir.join("link.png");
        fs::write(&file, b"previous").unwrap();
        std::os::unix::fs::symlink("real.png", &link).unwrap();
        assert!(write_atomically(&link, |_| Err(io::Error::other("no"))).is_err());
        assert!(fs::symlink_metadata(&link).unwrap().file_type().is_symlink());
        assert_eq!(fs::read(&file).unwrap(), b"previous");
        write_atomically(&link, |w| w.write_all(b"new")).unwrap();
        assert!(fs::symlink_metadata(&link).unwrap().file_type().is_symlink());
        assert_eq!(fs::read(&file).unwrap(), b"new");
        assert!(leftovers(&dir).is_empty());
        fs::remove_dir_all(&dir).ok();
    }

    #[cfg(unix)]
    #[test]
    fn a_rewrite_keeps_the_permissions_and_a_read_only_file_is_refused() {
        use std::os::unix::fs::PermissionsExt;
        let dir = scratch("permissions");
        let path = dir.join("private.exr");
        fs::write(&path, b"previous").unwrap();
        fs::set_permissions(&path, fs::Permissions::from_mode(0o600)).unwrap();
        write_atomically(&path, |w| w.write_all(b"new")).unwrap();
        assert_eq!(fs::read(&path).unwrap(), b"new");
        let mode = fs::metadata(&path).unwrap().permissions().mode() & 0o777;
        assert_eq!(mode, 0o600, "{mode:o}");
        // Read-only: refused before anything is written, the file as it was.
        fs::set_permissions(&path, fs::Permissions::from_mode(0o444)).unwrap();
        let err = write_atomically(&path, |w| w.write_all(b"newer")).unwrap_err();
        assert_eq!(err.kind(), io::ErrorKind::PermissionDenied, "{err}");
        assert!(check_output_path(&path).is_err());
        assert_eq!(fs::read(&path).unwrap(), b"new");
        assert!(leftovers(&dir).is_empty());
        fs::remove_dir_all(&dir).ok();
    }

    #[cfg(unix)]
    #[test]
    fn the_target_of_a_dangling_link_is_the_file_it_would_create() {
        let dir = scratch("dangling");
        let link = dir.join("s.json");
        std::os::unix::fs::symlink("x.exr", &link).unwrap();
        assert_eq!(output_target(&link).unwrap(), dir.join("x.exr"));
        assert_eq!(output_target(dir.join("y.png")).unwrap(), dir.join("y.png"));
        fs::remove_dir_all(&dir).ok();
    }

    #[cfg(unix)]
    #[test]
    fn folders_and_devices_are_refused_untouched() {
        let dir = scratch("special");
        for target in [dir.clone(), PathBuf::from("/dev/null")] {
            let err = write_atomically(&target, |w| w.write_all(b"x")).unwrap_err();
            assert_eq!(err.kind(), io::ErrorKind::InvalidInput, "{err}");
            assert!(err.to_string().contains(&target.display().to_string()), "{err}");
        }
        // A link to a device: refused, the link kept.
        let link = dir.join("full.exr");
        std::os::unix::fs::symlink("/dev/full", &link).unwrap();
        assert!(write_atomically(&link, |w| w.write_all(b"x")).is_err());
        assert!(fs::symlink_metadata(&link).unwrap().file_type().is_symlink());
        use std::os::unix::fs::FileTypeExt;
        assert!(fs::metadata("/dev/null").unwrap().file_type().is_char_device());
        fs::remove_dir_all(&dir).ok();
    }
}
