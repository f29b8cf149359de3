//! Mesh primitives to world-space triangles: triangle lists, strips and fans (points and
//! lines are skipped and counted), every index checked against the vertex count and every
//! position checked to be finite.

use std::path::Path;

use glam::{Mat4, Vec3};
use gltf::json;
use json::mesh::{Mode, Semantic};
use json::validation::Checked;

use super::accessor::AccessorReader;
use super::error::GltfError;

/// What one primitive turned into.
pub(super) enum PrimitiveGeometry {
    /// World-space vertices and triangles indexing them.
    Triangles {
        positions: Vec<Vec3>,
        triangles: Vec<[u32; 3]>,
    },
    /// Points or lines: nothing to render.
    NotTriangles,
    /// No `POSITION` attribute: the spec says to skip it.
    NoPositions,
}

/// Reads primitive `primitive` of mesh `mesh` placed by `world`.
pub(super) fn read_primitive(
    file: &Path,
    reader: &AccessorReader<'_>,
    (mesh, primitive): (usize, usize),
    prim: &json::mesh::Primitive,
    world: Mat4,
) -> Result<PrimitiveGeometry, GltfError> {
    let error = |reason: String| GltfError::Primitive {
        file: file.to_path_buf(),
        mesh,
        primitive,
        reason,
    };
    let mode = match prim.mode {
        Checked::Valid(mode) => mode,
        Checked::Invalid => return Err(error("invalid primitive mode".into())),
    };
    if !matches!(mode, Mode::Triangles | Mode::TriangleStrip | Mode::TriangleFan) {
        return Ok(PrimitiveGeometry::NotTriangles);
    }
    let Some(position_accessor) = prim
        .attributes
        .get(&Checked::Valid(Semantic::Positions))
        .map(|a| a.value())
    else {
        return Ok(PrimitiveGeometry::NoPositions);
    };
    let local = reader.read_vec3(position_accessor)?;
    let mut positions = Vec::with_capacity(local.len());
    for (i, p) in local.iter().enumerate() {
        let w = world.transform_point3(*p);
        if !w.is_finite() {
            return Err(error(format!(
                "position {i} is not finite in the world: {w} (local {p})"
            )));
        }
        positions.push(w);
    }
    let indices = match prim.indices {
        Some(accessor) => reader.read_indices(accessor.value())?,
        None => (0..positions.len() as u32).collect(),
    };
    let vertices = positions.len();
    if let Some(bad) = indices.iter().find(|&&i| i as usize >= vertices) {
        return Err(error(format!("index {bad} out of range for {vertices} vertices")));
    }
    let mut triangles = assemble(mode, &indices).map_err(error)?;
    // A mirroring transform flips the winding; flip it back so front faces stay front faces.
    if world.determinant() < 0.0 {
        for t in &mut triangles {
            t.swap(1, 2);
        }
    }
    Ok(PrimitiveGeometry::Triangles { positions, triangles })
}

/// Index list to triangles for the three triangle modes.
fn assemble(mode: Mode, indices: &[u32]) -> Result<Vec<[u32; 3]>, String> {
    let n = indices.len();
    match mode {
        Mode::Triangles => {
            if !n.is_multiple_of(3) {
                return Err(format!("{n} indices is not a multiple of 3"));
            }
            Ok(indices.chunks_exact(3).map(|t| [t[0], t[1], t[2]]).collect())
        }
        Mode::TriangleStrip => Ok((0..n.saturating_sub(2))
            .map(|i| {
                if i % 2 == 0 {
                    [indices[i], indices[i + 1], indices[i + 2]]
                } else {
                    [indices[i + 1], indices[i], indices[i + 2]]
                }
            })
            .collect()),
        Mode::TriangleFan => Ok((1..n.saturating_sub(1))
            .map(|i| [indices[0], indices[i], indices[i + 1]])
            .collect()),
        _ => Ok(Vec::new()),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn strip_alternates_winding_like_opengl() {
        // OpenGL spec: triangle i of a strip is (i, i+1, i+2) for even i, (i+1, i, i+2) odd.
        let t = assemble(Mode::TriangleStrip, &[0, 1, 2, 3, 4]).unwrap();
        assert_eq!(t, vec![[0, 1, 2], [2, 1, 3], [2, 3, 4]]);
    }

    #[test]
    fn fan_shares_the_first_vertex() {
        let t = assemble(Mode::TriangleFan, &[0, 1, 2, 3]).unwrap();
        assert_eq!(t, vec![[0, 1, 2], [0, 2, 3]]);
        assert!(assemble(Mode::TriangleFan, &[0, 1]).unwrap().is_empty());
    }

    #[test]
    fn triangle_list_must_be_whole() {
        assert!(assemble(Mode::Triangles, &[0, 1, 2, 3]).is_err());
    }
}
