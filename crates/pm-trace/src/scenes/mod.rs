//! The report's built-in scenes by name, each with its camera, and the scale scenes.

mod accordion;
pub mod box_mesh;
mod cornell;
pub mod doorways;
pub mod glossy_cornell;
mod rooms;
pub mod scale;
mod solids;

pub use accordion::ACCORDION_LIGHT_DIRECTION;
pub use solids::{SOLID_NAMES, solid_rooms_gap};

use crate::error::SceneError;
use crate::scene::Scene;

/// Names of the built-in scenes: those of Ball & Stejko's report, in its order, then the
/// glossy Cornell box ([`glossy_cornell`]).
pub const NAMES: [&str; 6] = [
    "cornell-box",
    "lit-unlit-rooms",
    "colored-rooms",
    "accordion",
    "touching-rooms",
    "glossy-cornell-box",
];

/// Builds the built-in scene `name`: one of the report's [`NAMES`], one of the [`SOLID_NAMES`]
/// (the lit and unlit rooms built from solid boxes, as modellers build them), or a scale scene
/// named as [`SCALE_NAMES`] says; an unknown name is an error listing the valid ones.
///
/// ```
/// let scene = pm_trace::scenes::build("cornell-box")?;
/// assert_eq!(scene.lights().len(), 1);
/// assert!(pm_trace::scenes::build("cornell").is_err());
/// # Ok::<(), pm_trace::SceneError>(())
/// ```
pub fn build(name: &str) -> Result<Scene, SceneError> {
    match name {
        "cornell-box" => cornell::cornell_box(),
        "lit-unlit-rooms" => rooms::lit_unlit_rooms(),
        "colored-rooms" => rooms::colored_rooms(),
        "accordion" => accordion::accordion(),
        "touching-rooms" => rooms::touching_rooms(),
        "glossy-cornell-box" => glossy_cornell::glossy_cornell_box(),
        _ => solids::solid_rooms(name)
            .or_else(|| build_scale(name))
            .unwrap_or_else(|| {
                Err(SceneError::UnknownScene {
                    name: name.to_string(),
                    valid: format!(
                        "{}, the solid rooms {}, and the scale scenes {SCALE_NAMES}",
                        NAMES.join(", "),
                        SOLID_NAMES.join(", ")
                    ),
                })
            }),
    }
}

/// How the scale scenes of [`scale`] are named for [`build`].
pub const SCALE_NAMES: &str = "split-rooms-N (lit-unlit-rooms, faces split N x N), cube-field-N (N cubes) and doorway-rooms-N (N lit rooms in a row, seen from the first)";

/// A scale scene by name (`split-rooms-N`, `cube-field-N`, `doorway-rooms-N`), or `None` for
/// other names.
fn build_scale(name: &str) -> Option<Result<Scene, SceneError>> {
    let number = |prefix: &str| name.strip_prefix(prefix).and_then(|n| n.parse::<u32>().ok());
    if let Some(n) = number("split-rooms-") {
        return Some(scale::split_rooms(n));
    }
    if let Some(n) = number("doorway-rooms-") {
        return Some(doorways::doorway_rooms(n));
    }
    number("cube-field-").map(scale::cube_field)
}
