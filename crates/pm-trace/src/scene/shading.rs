//! Per-vertex attributes of a mesh (texture coordinates, colours, normals, a base-colour
//! texture, an emission texture, the material's parameter textures and normal map) and their
//! interpolation at a hit, from barycentrics computed after the hit.

use std::sync::Arc;

use glam::{Vec2, Vec3};

use super::material_texture::texels_across;
use super::material_textures::MaterialTextures;
use crate::bsdf::shading_point::TextureFactors;
use crate::emission::EmissionTexture;
use crate::sampler::Sampler;
use crate::texture::Texture;

/// What a mesh's vertices carry besides positions: see [`SceneBuilder::attributed_mesh`].
///
/// [`SceneBuilder::attributed_mesh`]: super::SceneBuilder::attributed_mesh
#[derive(Clone, Debug, Default, PartialEq)]
pub struct VertexAttributes {
    /// Texture coordinates per vertex (glTF convention: v grows down the image).
    pub uvs: Option<Vec<Vec2>>,
    /// Linear RGB colour per vertex, multiplying the base colour (glTF `COLOR_0`).
    pub colors: Option<Vec<Vec3>>,
    /// Shading normal per vertex (glTF `NORMAL`), interpolated at hits for the cosine terms
    /// of shading; need not be unit length (zero-length ones fall back to the geometric
    /// normal).
    pub normals: Option<Vec<Vec3>>,
    /// The base-colour texture and how to sample it, read at `uvs` (shared between meshes:
    /// one copy of the image however many meshes use it).
    pub base_color_texture: Option<(Arc<Texture>, Sampler)>,
    /// A texture multiplying the surface's emission, with its own texture coordinates
    /// ([`crate::Scene::emission`] reads it at hits; a [`crate::TexturedAreaLight`] over the
    /// same triangles, texture and factor makes the matching light).
    pub emission_texture: Option<EmissionTexture>,
    /// Textures of the material's parameters (read into [`crate::ShadingPoint::factors`]) and
    /// its normal map (read into [`crate::Scene::shading_normal_at`]), each with its own
    /// texture coordinates.
    pub material_textures: MaterialTextures,
}

/// A mesh's attributes and the triangles (by source face) to interpolate them over. The
/// corners are kept here because the half-edge mesh welds and reorders vertices.
#[derive(Clone, Debug)]
pub(crate) struct MeshShading {
    positions: Vec<Vec3>,
    triangles: Vec<[u32; 3]>,
    attributes: VertexAttributes,
}

impl MeshShading {
    pub(crate) fn new(positions: &[Vec3], triangles: &[[u32; 3]], attributes: VertexAttributes) -> Self {
        Self {
            positions: positions.to_vec(),
            triangles: triangles.to_vec(),
            attributes,
        }
    }

    /// The same attributes for a mesh re-made of pieces of this one's triangles (faces split
    /// along contact lines): piece `i` lies inside triangle `sources[i]` and is shaded by
    /// interpolating over that whole triangle, so every point keeps the attributes it had.
    /// `None` when some source is not a triangle of this mesh.
    pub(crate) fn for_pieces(&self, sources: &[usize]) -> Option<Self> {
        let triangles = sources
            .iter()
            .map(|&s| self.triangles.get(s).copied())
            .collect::<Option<Vec<_>>>()?;
        Some(Self {
            positions: self.positions.clone(),
            triangles,
            attributes: self.attributes.clone(),
        })
    }

    /// The corners, the triangles over them and the attributes, as given.
    pub(crate) fn parts(&self) -> (&[Vec3], &[[u32; 3]], &VertexAttributes) {
        (&self.positions, &self.triangles, &self.attributes)
    }

    /// Checks every attribute has one entry per vertex and every corner is a vertex.
    pub(crate) fn validate(&self) -> Result<(), String> {
        let n = self.positions.len();
        let check = |name: &str, len: Option<usize>| match len {
            Some(len) if len != n => Err(format!("{len} {name} for {n} vertices")),
            _ => Ok(()),
        };
        check("texture coordinates", self.attributes.uvs.as_ref().map(Vec::len))?;
        check("colours", self.attributes.colors.as_ref().map(Vec::len))?;
        check("normals", self.attributes.normals.as_ref().map(Vec::len))?;
        check(
            "emission texture coordinates",
            self.attributes.emission_texture.as_ref().map(|e| e.uvs.len()),
        )?;
        for (name, texture) in self.attributes.material_textures.named() {
            check(
                &format!("{name} texture coordinates"),
                texture.map(|t| t.uvs.len()),
            )?;
        }
        check(
            "normal-map tangents",
            self.attributes
                .material_textures
                .normal
                .as_ref()
                .map(|n| n.tangents.len()),
        )?;
        if let Some(bad) = self.triangles.iter().flatten().find(|&&i| i as usize >= n) {
            return Err(format!("corner {bad} out of range for {n} vertices"));
        }
        if self.attributes.base_color_texture.is_some() && self.attributes.uvs.is_none() {
            return Err("a base-colour texture without texture coordinates".into());
        }
        Ok(())
    }

    pub(crate) fn heap_bytes(&self) -> usize {
        size_of::<Self>()
            + self.positions.capacity() * size_of::<Vec3>()
            + self.triangles.capacity() * size_of::<[u32; 3]>()
            + self
                .attributes
                .uvs
                .as_ref()
                .map_or(0, |v| v.capacity() * size_of::<Vec2>())
            + self
                .attributes
                .colors
                .as_ref()
                .map_or(0, |v| v.capacity() * size_of::<Vec3>())
            + self
                .attributes
                .normals
                .as_ref()
                .map_or(0, |v| v.capacity() * size_of::<Vec3>())
            + self
                .attributes
                .emission_texture
                .as_ref()
                .map_or(0, |e| e.uvs.capacity() * size_of::<Vec2>())
            + self.attributes.material_textures.heap_bytes()
    }

    /// The material textures' factors at point `p` of source triangle `face`, averaged over
    /// `footprint` metres (0: a point lookup), or `None` when the mesh has no such texture.
    #[inline]
    pub(crate) fn factors_at(&self, face: usize, p: Vec3, footprint: f32) -> Option<TextureFactors> {
        let textures = &self.attributes.material_textures;
        if !textures.has_factors() {
            return None;
        }
        let &corners = self.triangles.get(face)?;
        let positions = corners.map(|i| self.positions[i as usize]);
        let [a, b, c] = positions;
        Some(textures.factors_at(corners, positions, barycentrics(a, b, c, p), footprint))
    }

    /// True when the mesh has an emission texture.
    #[inline]
    pub(crate) fn has_emission_texture(&self) -> bool {
        self.attributes.emission_texture.is_some()
    }

    /// The emission texture's value at point `p` of source triangle `face`, or `None` when
    /// the mesh has no emission texture.
    #[inline]
    pub(crate) fn emission_texture_at(&self, face: usize, p: Vec3) -> Option<Vec3> {
        let emission = self.attributes.emission_texture.as_ref()?;
        let &corners = self.triangles.get(face)?;
        let [a, b, c] = corners.map(|i| self.positions[i as usize]);
        Some(emission.at(
            corners.map(|i| emission.uvs[i as usize]),
            barycentrics(a, b, c, p),
        ))
    }

    /// True when the mesh has per-vertex normals or a normal map.
    #[inline]
    pub(crate) fn has_normals(&self) -> bool {
        self.attributes.normals.is_some() || self.attributes.material_textures.normal.is_some()
    }

    /// The normals at point `p` of source triangle `face`, whose face normal (on the front,
    /// counter-clockwise side) is `face_normal`: the interpolated vertex normal (the face
    /// normal without them; not normalised, not oriented) and, where the mesh has a normal
    /// map, that normal bent by it (unit, on the side the first points to). `None` when the
    /// mesh has neither normals nor a normal map.
    #[inline]
    pub(crate) fn normals_at(&self, face: usize, p: Vec3, face_normal: Vec3) -> Option<(Vec3, Option<Vec3>)> {
        let &corners = self.triangles.get(face)?;
        let positions = corners.map(|i| self.positions[i as usize]);
        let [a, b, c] = positions;
        let w = barycentrics(a, b, c, p);
        let interpolated = self.attributes.normals.as_ref().map(|normals| {
            let [na, nb, nc] = corners.map(|i| normals[i as usize]);
            na * w.x + nb * w.y + nc * w.z
        });
        let Some(map) = &self.attributes.material_textures.normal else {
            return interpolated.map(|n| (n, None));
        };
        let normal = interpolated
            .filter(|n| n.length_squared() > 0.0)
            .unwrap_or(face_normal);
        Some((normal, map.bend(corners, positions, w, normal)))
    }

    /// The colour factor at point `p` of source triangle `face`: texture × vertex colour, the
    /// texture averaged over a footprint `footprint` metres across (0: a point lookup).
    #[inline]
    pub(crate) fn colour_at(&self, face: usize, p: Vec3, footprint: f32) -> Vec3 {
        let Some(&corners) = self.triangles.get(face) else {
            return Vec3::ONE;
        };
        let [a, b, c] = corners.map(|i| self.positions[i as usize]);
        let w = barycentrics(a, b, c, p);
        let mut colour = Vec3::ONE;
        if let Some(colors) = &self.attributes.colors {
            let [ca, cb, cc] = corners.map(|i| colors[i as usize]);
            colour *= ca * w.x + cb * w.y + cc * w.z;
        }
        if let (Some(uvs), Some((texture, sampler))) =
            (&self.attributes.uvs, &self.attributes.base_color_texture)
        {
            let [ta, tb, tc] = corners.map(|i| uvs[i as usize]);
            let uv = ta * w.x + tb * w.y + tc * w.z;
            colour *= if footprint > 0.0 {
                let texels = texels_across(texture, [a, b, c], [ta, tb, tc], footprint);
                sampler.sample_footprint(texture, uv, texels)
            } else {
                sampler.sample(texture, uv)
            };
        }
        colour
    }
}

/// Barycentric weights of `p` (projected onto the triangle's plane) in triangle `a b c`,
/// clamped to the triangle; the centroid for a degenerate triangle.
#[inline]
pub(crate) fn barycentrics(a: Vec3, b: Vec3, c: Vec3, p: Vec3) -> Vec3 {
    let (e1, e2, d) = (b - a, c - a, p - a);
    let (d11, d12, d22) = (e1.dot(e1), e1.dot(e2), e2.dot(e2));
    let (d1p, d2p) = (e1.dot(d), e2.dot(d));
    let det = d11 * d22 - d12 * d12;
    if det.is_nan() || det <= 0.0 || !det.is_finite() {
        return Vec3::splat(1.0 / 3.0);
    }
    let v = ((d22 * d1p - d12 * d2p) / det).clamp(0.0, 1.0);
    let w = ((d11 * d2p - d12 * d1p) / det).clamp(0.0, 1.0 - v);
    Vec3::new(1.0 - v - w, v, w)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn barycentrics_recover_the_weights_of_a_combination() {
        let (a, b, c) = (
            Vec3::new(0.0, 0.0, 1.0),
            Vec3::new(2.0, 0.0, 0.0),
            Vec3::new(0.0, 3.0, 0.5),
        );
        let w = Vec3::new(0.2, 0.3, 0.5);
        let p = a * w.x + b * w.y + c * w.z;
        assert!((barycentrics(a, b, c, p) - w).abs().max_element() < 1e-5);
        assert_eq!(barycentrics(a, a, a, a), Vec3::splat(1.0 / 3.0));
    }
}
