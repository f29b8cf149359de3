//! glTF's normal map on a mesh: a tangent-space normal per texel, bent into the world by the
//! interpolated normal and tangent of the hit (glTF 2.0's `normalTexture`), and tangents made
//! by MikkTSpace where the file gives none.

use bevy_mikktspace::{Geometry, TangentSpace, generate_tangents};
use glam::{Vec2, Vec3, Vec4};

use super::material_texture::MaterialTexture;

/// A normal map: texels `(r, g, b)` are the tangent-space normal `(2r − 1, 2g − 1, 2b − 1)`
/// (linear values: [`crate::TexelEncoding::Linear`]), its x and y scaled by `scale`, in the
/// frame of the interpolated tangent `T`, bitangent `B = (N × T) · w` and normal `N`.
#[derive(Clone, Debug, PartialEq)]
pub struct NormalTexture {
    /// The image and its texture coordinates.
    pub map: MaterialTexture,
    /// glTF's `normalTexture.scale`: multiplies the x and y of each texel's normal.
    pub scale: f32,
    /// Per vertex of the mesh: the tangent (xyz, along increasing u) and the bitangent's sign
    /// (w, ±1), as glTF's `TANGENT`; [`mikktspace_tangents`] makes them where a file has none.
    pub tangents: Vec<Vec4>,
}

impl NormalTexture {
    /// The mapped unit normal at barycentric weights `w` of a triangle with corners `corners`
    /// and positions `positions`, where the interpolated vertex normal (or the face normal) is
    /// `normal`, on the side `normal` points to; `None` where the frame or the result is
    /// degenerate (a zero tangent, a tangent along the normal).
    #[inline]
    pub(crate) fn bend(
        &self,
        corners: [u32; 3],
        positions: [Vec3; 3],
        w: Vec3,
        normal: Vec3,
    ) -> Option<Vec3> {
        let n = normal.try_normalize()?;
        let [ta, tb, tc] = corners.map(|i| self.tangents[i as usize]);
        let t = ta * w.x + tb * w.y + tc * w.z;
        let tangent = (t.truncate() - n * n.dot(t.truncate())).try_normalize()?;
        let sign = if t.w < 0.0 { -1.0 } else { 1.0 };
        let bitangent = n.cross(tangent) * sign;
        let texel = self.map.texel_at(corners, positions, w, 0.0) * 2.0 - Vec3::ONE;
        (tangent * (texel.x * self.scale) + bitangent * (texel.y * self.scale) + n * texel.z).try_normalize()
    }

    /// Heap bytes of the tangents.
    pub(crate) fn tangent_heap_bytes(&self) -> usize {
        self.tangents.capacity() * size_of::<Vec4>()
    }
}

/// The least cosine between a mapped shading normal and the geometric normal on the same side
/// ([`crate::Scene::shading_normal_at`]): a normal map that leans the shading normal to the
/// horizon or past it (strong maps, coarse meshes, a large `scale`) is tilted back to this
/// (about 87°), so a lobe about it keeps some directions above the geometric surface. The
/// render modes still count a direction only when it lies above both surfaces (no ray is sent
/// below the geometric surface), so past the horizon light is lost, not leaked.
pub const MIN_MAPPED_COSINE: f32 = 0.05;

/// `mapped` (unit) if its cosine with the unit geometric normal `geometric` is at least
/// [`MIN_MAPPED_COSINE`], else turned towards `geometric` in the plane of the two until it is.
#[inline]
pub(crate) fn above_geometric(mapped: Vec3, geometric: Vec3) -> Vec3 {
    let cos = mapped.dot(geometric);
    if cos >= MIN_MAPPED_COSINE {
        return mapped;
    }
    let Some(along) = (mapped - geometric * cos).try_normalize() else {
        return geometric;
    };
    let sin = (1.0 - MIN_MAPPED_COSINE * MIN_MAPPED_COSINE).sqrt();
    geometric * MIN_MAPPED_COSINE + along * sin
}

/// Tangents per vertex for a normal map, by MikkTSpace (Mikkelsen 2008, the algorithm glTF 2.0
/// names for files without `TANGENT`) over `triangles` (indices into `positions`, `normals`
/// and `uvs`, each one entry per vertex; without normals each triangle's own, as glTF asks for
/// flat shading then).
///
/// glTF's texture coordinates grow *down* the image while its normal maps' green is *up* the
/// image, so the sign MikkTSpace gives (its bitangent follows increasing v) is negated, as
/// three.js's `computeMikkTSpaceTangents` does for glTF: `B = (N × T) · w` then points up the
/// image, which is what the Khronos sample viewer's derivative tangents give. MikkTSpace gives
/// a tangent per triangle corner; a vertex whose corners get different ones (a vertex shared
/// across a mirrored texture seam) keeps its last corner's, as Bevy's loader does. A vertex no
/// triangle gives one (degenerate texture coordinates with no neighbour to borrow from) gets
/// `(1, 0, 0, 1)`, which the shading orthogonalises against the normal ([`NormalTexture`]).
pub fn mikktspace_tangents(
    positions: &[Vec3],
    triangles: &[[u32; 3]],
    normals: Option<&[Vec3]>,
    uvs: &[Vec2],
) -> Vec<Vec4> {
    let mut mesh = Corners {
        positions,
        triangles,
        normals,
        uvs,
        tangents: vec![Vec4::new(1.0, 0.0, 0.0, 1.0); positions.len()],
    };
    // Only fails on a mesh of no faces, whose tangents are all default.
    let _ = generate_tangents(&mut mesh);
    mesh.tangents
}

/// A mesh as MikkTSpace reads it, and the tangents it writes.
struct Corners<'a> {
    positions: &'a [Vec3],
    triangles: &'a [[u32; 3]],
    normals: Option<&'a [Vec3]>,
    uvs: &'a [Vec2],
    tangents: Vec<Vec4>,
}

impl Corners<'_> {
    fn vertex(&self, face: usize, corner: usize) -> usize {
        self.triangles[face][corner] as usize
    }
}

impl Geometry for Corners<'_> {
    fn num_faces(&self) -> usize {
        self.triangles.len()
    }

    fn num_vertices_of_face(&self, _face: usize) -> usize {
        3
    }

    fn position(&self, face: usize, vert: usize) -> [f32; 3] {
        self.positions[self.vertex(face, vert)].to_array()
    }

    fn normal(&self, face: usize, vert: usize) -> [f32; 3] {
        match self.normals {
            Some(normals) => normals[self.vertex(face, vert)].to_array(),
            None => {
                let [a, b, c] = self.triangles[face].map(|i| self.positions[i as usize]);
                (b - a).cross(c - a).normalize_or_zero().to_array()
            }
        }
    }

    fn tex_coord(&self, face: usize, vert: usize) -> [f32; 2] {
        self.uvs[self.vertex(face, vert)].to_array()
    }

    fn set_tangent(&mut self, tangent_space: Option<TangentSpace>, face: usize, vert: usize) {
        if let Some(space) = tangent_space {
            let v = self.vertex(face, vert);
            let [x, y, z, w] = space.tangent_encoded();
            self.tangents[v] = Vec4::new(x, y, z, -w);
        }
    }
}
