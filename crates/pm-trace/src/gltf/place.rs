//! A decoded primitive placed by a node: its vertices taken through the node's f64 world
//! transform, moved by the scene's re-centring offset, and only then rounded to f32; its
//! normals by the transform's inverse transpose, tangents by the transform; its winding kept
//! front-facing under mirrors.

use std::path::Path;

use glam::{DMat3, DMat4, DVec3, Vec3};

use super::decoded::LocalPrimitive;
use super::error::GltfError;
use super::mesh::GltfMesh;
use super::origin::{WorldBounds, unit_f32};
use crate::scene::material_textures::MaterialTextures;

impl LocalPrimitive {
    /// Adds the world position (f64, before re-centring) of every vertex under `world` to
    /// `bounds`.
    pub(super) fn add_world_bounds(&self, world: DMat4, bounds: &mut WorldBounds) {
        for p in &self.positions {
            bounds.add(world.transform_point3(p.as_dvec3()));
        }
    }

    /// The primitive placed by node `node` with world transform `world`, re-centred on
    /// `origin`: each position is `world · p − origin` in f64, then rounded once to f32 (and
    /// checked finite there); normals by the inverse transpose of `world`'s linear part; the
    /// winding flipped back under a mirroring transform.
    pub(super) fn place(
        &self,
        file: &Path,
        node: usize,
        at: (usize, usize),
        world: DMat4,
        origin: DVec3,
    ) -> Result<GltfMesh, GltfError> {
        let mut positions = Vec::with_capacity(self.positions.len());
        for (i, p) in self.positions.iter().enumerate() {
            let w = world.transform_point3(p.as_dvec3()) - origin;
            let w32 = w.as_vec3();
            // Beyond the photon maps' coordinate range the scene is refused anyway; saying so
            // here names the position (a face that large would otherwise be dropped as
            // degenerate, its area past f32, and the scene refused as having no geometry).
            if !(w32.is_finite() && w32.abs().max_element() < pm_kdtree::MAX_COORDINATE) {
                return Err(GltfError::Primitive {
                    file: file.to_path_buf(),
                    mesh: at.0,
                    primitive: at.1,
                    reason: format!(
                        "position {i} is not finite or beyond ±{:e} m in the world: {w} (local {p}, re-centred on {origin})",
                        pm_kdtree::MAX_COORDINATE
                    ),
                });
            }
            positions.push(w32);
        }
        let mut triangles = self.triangles.clone();
        // A mirroring transform flips the winding; flip it back so front faces stay front.
        if world.determinant() < 0.0 {
            for t in &mut triangles {
                t.swap(1, 2);
            }
        }
        let to_world = DMat3::from_mat4(world).inverse().transpose();
        let normals = self.normals.as_ref().map(|normals| {
            normals
                .iter()
                .map(|v| unit_f32(to_world * v.as_dvec3()).unwrap_or(Vec3::ZERO))
                .collect()
        });
        Ok(GltfMesh {
            node,
            mesh: at.0,
            primitive: at.1,
            material_index: self.material_index,
            positions,
            triangles,
            material: self.material,
            uvs: self.uvs.clone(),
            colors: self.colors.clone(),
            normals,
            base_color_texture: self.base_color_texture.clone(),
            emission_texture: self.emission_texture.clone(),
            material_textures: self.placed_material_textures(world),
        })
    }

    /// The material textures with the normal map's tangents taken to the world by `world`'s
    /// linear part (tangents are directions on the surface, not normals), and their bitangent
    /// signs flipped under a mirroring transform (which flips `N × T` against the mapped
    /// bitangent).
    fn placed_material_textures(&self, world: DMat4) -> MaterialTextures {
        let mut textures = self.material_textures.clone();
        if let Some(normal) = &mut textures.normal {
            let linear = DMat3::from_mat4(world);
            let sign = if linear.determinant() < 0.0 { -1.0 } else { 1.0 };
            for t in &mut normal.tangents {
                let xyz = unit_f32(linear * t.truncate().as_dvec3()).unwrap_or(Vec3::ZERO);
                *t = xyz.extend(t.w * sign);
            }
        }
        textures
    }
}
