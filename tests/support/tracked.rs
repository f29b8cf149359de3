//! The repository's tracked files, for the tests that check an example writes none of them:
//! a snapshot of their sizes and modification times, and scratch copies of them to run
//! examples in. Without git (a source tarball) there is no list, and the tests say so and skip.
#![allow(dead_code)]

use std::collections::BTreeMap;
use std::path::{Path, PathBuf};
use std::process::Command;
use std::time::SystemTime;

/// The repository root (this package's manifest folder).
pub fn root() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
}

/// The tracked files, relative to the root, from `git ls-files` (`None`, with a notice,
/// where git or the repository is missing).
pub fn tracked_files() -> Option<Vec<PathBuf>> {
    let output = Command::new("git")
        .arg("-C")
        .arg(root())
        .args(["ls-files", "-z"])
        .output()
        .ok()
        .filter(|o| o.status.success());
    let Some(output) = output else {
        eprintln!(
            "no git repository at {}: tracked files not checked",
            root().display()
        );
        return None;
    };
    let files: Vec<PathBuf> = output
        .stdout
        .split(|&b| b == 0)
        .filter(|name| !name.is_empty())
        .map(|name| PathBuf::from(String::from_utf8_lossy(name).into_owned()))
        // A tracked file deleted in the working tree is not there to copy or compare.
        .filter(|name| root().join(name).is_file())
        .collect();
    Some(files)
}

/// Size and modification time of every tracked file in the working tree.
pub type Snapshot = BTreeMap<PathBuf, (u64, Option<SystemTime>)>;

/// The tracked files' sizes and modification times now (`None` without git).
pub fn snapshot() -> Option<Snapshot> {
    let files = tracked_files()?;
    Some(
        files
            .into_iter()
            .map(|name| {
                let meta = std::fs::metadata(root().join(&name)).ok();
                let stamp = meta.map_or((0, None), |m| (m.len(), m.modified().ok()));
                (name, stamp)
            })
            .collect(),
    )
}

/// The tracked files whose size or modification time differs between two snapshots.
pub fn changed(before: &Snapshot, after: &Snapshot) -> Vec<PathBuf> {
    before
        .iter()
        .filter(|(name, stamp)| after.get(*name) != Some(stamp))
        .map(|(name, _)| name.clone())
        .collect()
}

/// A copy of the tracked files in `dir` (which must exist), to run examples in as if in the
/// repository; `differing` lists what a run changed there.
pub struct Copy {
    pub dir: PathBuf,
    files: Vec<PathBuf>,
}

impl Copy {
    /// Copies every tracked file into `dir` (`None` without git).
    pub fn new(dir: &Path) -> Option<Copy> {
        let files = tracked_files()?;
        for name in &files {
            let to = dir.join(name);
            std::fs::create_dir_all(to.parent().unwrap()).unwrap();
            std::fs::copy(root().join(name), &to).unwrap();
        }
        Some(Copy {
            dir: dir.to_owned(),
            files,
        })
    }

    /// The copied files whose bytes now differ from the repository's (or that are gone).
    pub fn differing(&self) -> Vec<PathBuf> {
        self.files
            .iter()
            .filter(|name| std::fs::read(self.dir.join(name)).ok() != std::fs::read(root().join(name)).ok())
            .cloned()
            .collect()
    }
}
