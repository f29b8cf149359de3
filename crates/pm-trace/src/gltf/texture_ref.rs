//! A material's reference to a texture as this loader reads it (`textureInfo`: the texture,
//! its `TEXCOORD` set and `KHR_texture_transform`), and the texture coordinates it reads.

use glam::Vec2;
use gltf::json;
use json::accessor::Type;
use json::mesh::Semantic;
use json::validation::Checked;

use super::accessor::AccessorReader;
use super::error::GltfError;
use crate::texture_transform::TextureTransform;

/// Which texture a material reads, at which coordinates.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct TextureRef {
    /// Index of the texture in the file's `textures`.
    pub index: usize,
    /// The `TEXCOORD_n` set read (`KHR_texture_transform`'s `texCoord` overrides the
    /// reference's own).
    pub tex_coord: u32,
    /// `KHR_texture_transform`'s offset, rotation and scale (identity without the extension;
    /// non-finite components read as their identity values).
    pub transform: TextureTransform,
}

impl TextureRef {
    /// Reads a glTF `textureInfo`.
    pub(super) fn from_info(info: &json::texture::Info) -> Self {
        let extension = info
            .extensions
            .as_ref()
            .and_then(|e| e.texture_transform.as_ref());
        Self::with_transform(info.index.value(), info.tex_coord, extension)
    }

    /// Reads a material's `normalTexture` and its `scale`, under `extension`, its
    /// `KHR_texture_transform` (which the gltf crate does not type there: see
    /// `normal_transform.rs`).
    pub(super) fn from_normal(
        normal: &json::material::NormalTexture,
        extension: Option<&json::extensions::texture::TextureTransform>,
    ) -> (Self, f32) {
        let reference = Self::with_transform(normal.index.value(), normal.tex_coord, extension);
        (reference, normal.scale)
    }

    /// Texture `index` at `TEXCOORD_tex_coord` under `KHR_texture_transform` `extension`.
    fn with_transform(
        index: usize,
        tex_coord: u32,
        extension: Option<&json::extensions::texture::TextureTransform>,
    ) -> Self {
        let transform = extension.map_or(TextureTransform::IDENTITY, |t| {
            TextureTransform {
                offset: Vec2::from(t.offset.0),
                rotation: t.rotation.0,
                scale: Vec2::from(t.scale.0),
            }
            .finite_or_identity()
        });
        Self {
            index,
            tex_coord: extension.and_then(|t| t.tex_coord).unwrap_or(tex_coord),
            transform,
        }
    }

    /// The texture coordinates of primitive `prim`'s vertices for this reference, transformed;
    /// `None` when the primitive has no such `TEXCOORD` set.
    pub(super) fn read_uvs(
        &self,
        reader: &AccessorReader<'_>,
        prim: &json::mesh::Primitive,
    ) -> Result<Option<Vec<Vec2>>, GltfError> {
        let Some(accessor) = prim
            .attributes
            .get(&Checked::Valid(Semantic::TexCoords(self.tex_coord)))
        else {
            return Ok(None);
        };
        let read = reader.read_vec(accessor.value(), &[Type::Vec2])?;
        let uv = |v: &glam::Vec4| v.truncate().truncate();
        Ok(Some(if self.transform.is_identity() {
            read.iter().map(uv).collect()
        } else {
            read.iter().map(|v| self.transform.apply(uv(v))).collect()
        }))
    }
}
