//! The node graph walk: from the chosen scene's roots with an explicit stack, composing world
//! transforms in f64 (a georeferenced root node's kilometres of translation and its children's
//! millimetres stay apart until the scene is re-centred). A node reached twice (a cycle, or a child shared by two parents) or a chain
//! deeper than [`MAX_DEPTH`] is an error, so hostile graphs cost bounded time and memory.

use std::path::Path;

use glam::{DMat4, DQuat, DVec3};
use gltf::json;

use super::error::GltfError;
use super::node_transform::NodeTransform;

/// The deepest node chain accepted (root nodes have depth 1).
pub const MAX_DEPTH: usize = 256;

/// A node reached from the scene, with its world transform (f64, before re-centring).
pub(super) struct PlacedNode {
    pub index: usize,
    pub world: DMat4,
}

/// The root nodes to walk: the default scene, else scene 0, else every node that is no
/// other node's child.
pub(super) fn root_nodes(file: &Path, root: &json::Root) -> Result<Vec<usize>, GltfError> {
    let scene = match root.scene {
        Some(s) => Some(root.scenes.get(s.value()).ok_or_else(|| GltfError::Scene {
            file: file.to_path_buf(),
            reason: format!(
                "default scene {} does not exist (the file has {})",
                s.value(),
                root.scenes.len()
            ),
        })?),
        None => root.scenes.first(),
    };
    if let Some(scene) = scene {
        return Ok(scene.nodes.iter().map(|n| n.value()).collect());
    }
    let mut is_child = vec![false; root.nodes.len()];
    for node in &root.nodes {
        for child in node.children.iter().flatten() {
            if let Some(flag) = is_child.get_mut(child.value()) {
                *flag = true;
            }
        }
    }
    Ok((0..root.nodes.len()).filter(|&i| !is_child[i]).collect())
}

/// Walks the graph below `roots`, depth first in document order, composing each node's
/// `transforms` entry (its fields in f64, one entry per node of `root`).
pub(super) fn walk(
    file: &Path,
    root: &json::Root,
    transforms: &[NodeTransform],
    roots: &[usize],
) -> Result<Vec<PlacedNode>, GltfError> {
    let node_error = |node: usize, reason: String| GltfError::Node {
        file: file.to_path_buf(),
        node,
        reason,
    };
    let mut visited = vec![false; root.nodes.len()];
    let mut placed = Vec::new();
    // (node, parent's world transform, depth); reversed so that pops follow document order.
    let mut stack: Vec<(usize, DMat4, usize)> =
        roots.iter().rev().map(|&n| (n, DMat4::IDENTITY, 1)).collect();
    while let Some((index, parent, depth)) = stack.pop() {
        let (node, transform) = root.nodes.get(index).zip(transforms.get(index)).ok_or_else(|| {
            node_error(
                index,
                format!("does not exist (the file has {})", root.nodes.len()),
            )
        })?;
        if std::mem::replace(&mut visited[index], true) {
            return Err(node_error(
                index,
                "is reached twice: the node graph has a cycle or a shared child".into(),
            ));
        }
        if depth > MAX_DEPTH {
            return Err(node_error(index, format!("lies deeper than {MAX_DEPTH} levels")));
        }
        let local = local_transform(transform).map_err(|reason| node_error(index, reason))?;
        let world = parent * local;
        if !world.is_finite() {
            return Err(node_error(index, "world transform is not finite".into()));
        }
        placed.push(PlacedNode { index, world });
        for child in node.children.iter().flatten().rev() {
            stack.push((child.value(), world, depth + 1));
        }
    }
    Ok(placed)
}

/// The node's local transform in f64: its column-major `matrix`, else translation × rotation ×
/// scale (the quaternion normalised in f64), from the fields as the file writes them.
fn local_transform(node: &NodeTransform) -> Result<DMat4, String> {
    if let Some(m) = node.matrix {
        let m = DMat4::from_cols_array(&m);
        return if m.is_finite() {
            Ok(m)
        } else {
            Err("matrix is not finite".into())
        };
    }
    let t = DVec3::from(node.translation.unwrap_or([0.0; 3]));
    let s = DVec3::from(node.scale.unwrap_or([1.0; 3]));
    let r = DQuat::from_array(node.rotation.unwrap_or([0.0, 0.0, 0.0, 1.0]));
    if !(t.is_finite() && s.is_finite() && r.is_finite()) {
        return Err("translation, rotation or scale is not finite".into());
    }
    let length = r.length();
    if length < 1e-6 {
        return Err("rotation quaternion has zero length".into());
    }
    Ok(DMat4::from_scale_rotation_translation(s, r / length, t))
}
