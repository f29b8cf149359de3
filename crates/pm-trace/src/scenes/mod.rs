//! The report's built-in scenes by name (DESIGN.md section 8).

use crate::{Scene, SceneError};

/// Names of the built-in scenes.
pub const NAMES: [&str; 5] = [
    "cornell-box",
    "lit-unlit-rooms",
    "colored-rooms",
    "accordion",
    "touching-rooms",
];

/// Builds the built-in scene `name`; an unknown name is an error listing the valid ones.
pub fn build(name: &str) -> Result<Scene, SceneError> {
    Err(SceneError::UnknownScene {
        name: name.to_string(),
        valid: NAMES.join(", "),
    })
}
