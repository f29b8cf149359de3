//! Cameras: the first perspective camera met in the node walk, or a default camera that
//! frames the scene's bounds from the +z side.

use std::path::Path;

use glam::{DMat4, DVec3, Vec3};
use gltf::json;

use super::error::GltfError;
use super::origin::unit_f32;

/// A pinhole camera read from the file or made to frame the scene.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct GltfCamera {
    /// Eye position in metres, relative to [`GltfContent::origin_offset`](super::GltfContent::origin_offset).
    pub position: Vec3,
    /// A point the camera looks at (on its −Z axis).
    pub look_at: Vec3,
    /// The camera's up direction (its +Y axis).
    pub up: Vec3,
    /// Vertical field of view in radians.
    pub vfov: f32,
    /// The aspect ratio the file asks for, if any (renderers use the image's own).
    pub aspect_ratio: Option<f32>,
}

/// Vertical field of view of the default camera: 40°.
pub const DEFAULT_VFOV: f32 = 40.0 * std::f32::consts::PI / 180.0;

/// Reads camera `camera` at a node with world transform `world` (f64), its eye re-centred on
/// `origin`; `None` for an orthographic camera (not supported: the renderer's camera is a
/// pinhole).
pub(super) fn place_camera(
    file: &Path,
    root: &json::Root,
    node: usize,
    camera: usize,
    world: DMat4,
    origin: DVec3,
) -> Result<Option<GltfCamera>, GltfError> {
    let error = |reason: String| GltfError::Node {
        file: file.to_path_buf(),
        node,
        reason,
    };
    let c = root.cameras.get(camera).ok_or_else(|| {
        error(format!(
            "camera {camera} does not exist (the file has {})",
            root.cameras.len()
        ))
    })?;
    let Some(p) = &c.perspective else {
        return Ok(None);
    };
    if !(p.yfov.is_finite() && p.yfov > 0.0 && p.yfov < std::f32::consts::PI) {
        return Err(error(format!(
            "camera {camera}: yfov {} is not in (0, π)",
            p.yfov
        )));
    }
    let position = (world.transform_point3(DVec3::ZERO) - origin).as_vec3();
    if !position.is_finite() {
        return Err(error(format!(
            "camera {camera}: the eye is not finite in f32 once re-centred on {origin}"
        )));
    }
    let forward = unit_f32(world.transform_vector3(DVec3::NEG_Z));
    let up = unit_f32(world.transform_vector3(DVec3::Y));
    let (Some(forward), Some(up)) = (forward, up) else {
        return Err(error(format!("camera {camera}: the node's axes are degenerate")));
    };
    if forward.cross(up).length_squared() < 1e-6 {
        return Err(error(format!(
            "camera {camera}: up is parallel to the view direction"
        )));
    }
    Ok(Some(GltfCamera {
        position,
        look_at: position + forward,
        up,
        vfov: p.yfov,
        aspect_ratio: p.aspect_ratio.filter(|a| a.is_finite() && *a > 0.0),
    }))
}

/// A camera on the +z side of the bounds `(min, max)`, looking along −z (glTF's viewing
/// direction) at their centre, far enough back that the face towards it fits the vertical
/// field of view [`DEFAULT_VFOV`], with a 10 % margin.
pub fn frame_bounds(min: Vec3, max: Vec3) -> GltfCamera {
    let center = (min + max) * 0.5;
    let size = (max - min).max(Vec3::splat(1e-3));
    let position = center + Vec3::Z * crate::camera::Camera::framing_distance(size, DEFAULT_VFOV);
    GltfCamera {
        position,
        look_at: center,
        up: Vec3::Y,
        vfov: DEFAULT_VFOV,
        aspect_ratio: None,
    }
}
