//! The library crates have no import loops, and their modules import what they use from where
//! it is defined: a small reader of `use` lines and paths builds each crate's module graph.
//!
//! What it reads (a documented approximation, no parser): comments, strings and character
//! literals are dropped; `mod x;` / `mod x { … }` declare modules (a module declared under
//! `#[cfg(test)]` is test code and left out); every `use` path and every path in code that
//! starts with `crate`, `super`, `self`, a child module or a name a `use` brought in is
//! resolved to the module that *defines* its item, following `use` / `pub use` re-exports (also
//! `*` globs, by looking for a definition of the name in the glob's module). A private `use`
//! and a path in code are edges; a `pub use` is a re-export for users and an edge only when the
//! re-exported name is also used in the file's own code. Modules map to files (an inline module
//! is part of its file), and a loop is a cycle between distinct files: a `mod.rs` that uses its
//! child while the child uses the `mod.rs` (through `super`) is a loop, declaring the child is
//! not.

#[path = "support/module_reader.rs"]
mod module_reader;
#[path = "support/rust_tokens.rs"]
mod rust_tokens;

use module_reader::Crate;
use std::path::{Path, PathBuf};

fn crate_src(name: &str) -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("crates")
        .join(name)
        .join("src")
}

fn loops_of(name: &str) -> Vec<String> {
    Crate::read(name, &crate_src(name)).loops()
}

#[test]
fn pm_geom_has_no_import_loops() {
    let loops = loops_of("pm-geom");
    assert!(loops.is_empty(), "import loops:\n{}", loops.join("\n"));
}

#[test]
fn pm_kdtree_has_no_import_loops() {
    let loops = loops_of("pm-kdtree");
    assert!(loops.is_empty(), "import loops:\n{}", loops.join("\n"));
}

#[test]
fn pm_trace_has_no_import_loops() {
    let loops = loops_of("pm-trace");
    assert!(loops.is_empty(), "import loops:\n{}", loops.join("\n"));
}

#[test]
fn pm_render_has_no_import_loops() {
    let loops = loops_of("pm-render");
    assert!(loops.is_empty(), "import loops:\n{}", loops.join("\n"));
}

#[test]
fn library_modules_import_from_where_names_are_defined() {
    let mut indirect = Vec::new();
    for name in ["pm-geom", "pm-kdtree", "pm-trace", "pm-render"] {
        let (_, found) = Crate::read(name, &crate_src(name)).edges();
        indirect.extend(found.into_iter().map(|s| format!("{name}: {s}")));
    }
    assert!(
        indirect.is_empty(),
        "imports through a re-export:\n{}",
        indirect.join("\n")
    );
}
