//! The bytes of what a scene's meshes carry besides their geometry (vertex colours, shading
//! normals, texture coordinates and textures), fed in a fixed order to a caller's digest: what
//! a fingerprint of a scene needs beyond its polygons, surfaces and lights.

use super::Scene;
use super::material_texture::MaterialTexture;
use super::shading::VertexAttributes;
use crate::sampler::Sampler;
use crate::texture::Texture;
use glam::{Vec2, Vec3};

impl Scene {
    /// Feeds `sink` the bytes of every mesh's vertex attributes, mesh by mesh in the scene's
    /// order: each mesh's index and whether it has attributes, then its corners and
    /// triangles as given, its texture coordinates, vertex colours and shading normals (each
    /// number's bits, little-endian), its base-colour and emission textures and its material's
    /// parameter textures and normal map (size, encoding, every texel, sampler; the map's
    /// scale and tangents). Equal scenes feed equal bytes; a
    /// change to any texel or attribute changes them. For fingerprints (a photon cache made
    /// for this scene); the geometry, surfaces and lights are not fed.
    pub fn feed_appearance(&self, sink: &mut dyn FnMut(&[u8])) {
        for (index, mesh) in self.meshes.iter().enumerate() {
            sink(&(index as u64).to_le_bytes());
            let Some(shading) = mesh.shading.as_deref() else {
                sink(&[0]);
                continue;
            };
            sink(&[1]);
            let (positions, triangles, attributes) = shading.parts();
            feed_vec3s(sink, positions);
            sink(&(triangles.len() as u64).to_le_bytes());
            let corners: Vec<u8> = triangles.iter().flatten().flat_map(|c| c.to_le_bytes()).collect();
            sink(&corners);
            feed_attributes(sink, attributes);
        }
    }
}

/// The attributes of one mesh, each marked present or absent.
fn feed_attributes(sink: &mut dyn FnMut(&[u8]), attributes: &VertexAttributes) {
    let VertexAttributes {
        uvs,
        colors,
        normals,
        base_color_texture,
        emission_texture,
        material_textures,
    } = attributes;
    feed_optional(sink, uvs.as_deref(), feed_vec2s);
    feed_optional(sink, colors.as_deref(), feed_vec3s);
    feed_optional(sink, normals.as_deref(), feed_vec3s);
    feed_optional(sink, base_color_texture.as_ref(), |sink, (texture, sampler)| {
        feed_texture(sink, texture, sampler)
    });
    feed_optional(sink, emission_texture.as_ref(), |sink, e| {
        feed_vec2s(sink, &e.uvs);
        feed_texture(sink, &e.texture, &e.sampler);
    });
    let [metallic_roughness, later @ ..] = material_textures.named();
    feed_optional(sink, metallic_roughness.1, feed_material_texture);
    // The textures read since: fed only where a mesh has one, so that the bytes of every
    // mesh without (and the fingerprints of caches made before) stay as they were.
    if later.iter().all(|(_, t)| t.is_none()) {
        return;
    }
    sink(b"specular, specular colour, normal map");
    for (_, texture) in later {
        feed_optional(sink, texture, feed_material_texture);
    }
    feed_optional(sink, material_textures.normal.as_ref(), |sink, n| {
        sink(&n.scale.to_bits().to_le_bytes());
        feed_floats(
            sink,
            n.tangents.len(),
            n.tangents.iter().flat_map(|t| t.to_array()),
        );
    });
}

/// A material texture's coordinates, texels and sampler.
fn feed_material_texture(sink: &mut dyn FnMut(&[u8]), texture: &MaterialTexture) {
    feed_vec2s(sink, &texture.uvs);
    feed_texture(sink, &texture.texture, &texture.sampler);
}

/// A marker (0 absent, 1 present) and, when present, `value`'s bytes.
fn feed_optional<T: ?Sized>(
    sink: &mut dyn FnMut(&[u8]),
    value: Option<&T>,
    feed: impl FnOnce(&mut dyn FnMut(&[u8]), &T),
) {
    match value {
        Some(value) => {
            sink(&[1]);
            feed(sink, value);
        }
        None => sink(&[0]),
    }
}

/// A texture's size, encoding and texels, and how it is sampled.
fn feed_texture(sink: &mut dyn FnMut(&[u8]), texture: &Texture, sampler: &Sampler) {
    sink(&texture.width().to_le_bytes());
    sink(&texture.height().to_le_bytes());
    sink(format!("{:?} {sampler:?}", texture.encoding()).as_bytes());
    sink(texture.texels().as_flattened());
}

/// The count and every coordinate's bits.
fn feed_vec3s(sink: &mut dyn FnMut(&[u8]), values: &[Vec3]) {
    feed_floats(sink, values.len(), values.iter().flat_map(|v| v.to_array()));
}

/// The count and every coordinate's bits.
fn feed_vec2s(sink: &mut dyn FnMut(&[u8]), values: &[Vec2]) {
    feed_floats(sink, values.len(), values.iter().flat_map(|v| v.to_array()));
}

/// `count` (of vectors) and the bits of every coordinate, little-endian.
fn feed_floats(sink: &mut dyn FnMut(&[u8]), count: usize, coordinates: impl Iterator<Item = f32>) {
    sink(&(count as u64).to_le_bytes());
    let bytes: Vec<u8> = coordinates.flat_map(|c| c.to_bits().to_le_bytes()).collect();
    sink(&bytes);
}
