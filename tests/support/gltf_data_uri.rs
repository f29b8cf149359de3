//! A small glTF writer for the emission tests: primitives, materials, images and point
//! lights in one `.gltf` whose buffer and images are percent-encoded `data:` URIs.

#![allow(dead_code)]

/// One primitive: positions, optional texture coordinates, triangle indices, material.
pub struct Prim {
    pub positions: Vec<[f32; 3]>,
    pub uvs: Option<Vec<[f32; 2]>>,
    pub indices: Vec<u32>,
    pub material: usize,
}

pub fn percent(bytes: &[u8]) -> String {
    bytes.iter().map(|b| format!("%{b:02X}")).collect()
}

/// A glTF file of `prims` (each its own mesh and node), `materials` and `images` (JSON
/// objects), `textures` (JSON), point lights at positions with intensities in candela.
pub fn gltf(
    prims: &[Prim],
    materials: &[String],
    textures: &str,
    images: &[String],
    lights: &[([f32; 3], f32)],
) -> String {
    let mut bin: Vec<u8> = Vec::new();
    let (mut views, mut accessors, mut meshes, mut nodes) = (vec![], vec![], vec![], vec![]);
    let mut view = |bin: &mut Vec<u8>, data: Vec<u8>| {
        let offset = bin.len();
        let len = data.len();
        bin.extend(data);
        views.push(format!(
            r#"{{"buffer":0,"byteOffset":{offset},"byteLength":{len}}}"#
        ));
        views.len() - 1
    };
    for (i, p) in prims.iter().enumerate() {
        let floats: Vec<u8> = p
            .positions
            .iter()
            .flatten()
            .flat_map(|f| f.to_le_bytes())
            .collect();
        let v = view(&mut bin, floats);
        let (mut lo, mut hi) = ([f32::MAX; 3], [f32::MIN; 3]);
        for q in &p.positions {
            for k in 0..3 {
                lo[k] = lo[k].min(q[k]);
                hi[k] = hi[k].max(q[k]);
            }
        }
        accessors.push(format!(
            r#"{{"bufferView":{v},"componentType":5126,"count":{},"type":"VEC3","min":{lo:?},"max":{hi:?}}}"#,
            p.positions.len()
        ));
        let position = accessors.len() - 1;
        let mut attributes = format!(r#""POSITION":{position}"#);
        if let Some(uvs) = &p.uvs {
            let v = view(
                &mut bin,
                uvs.iter().flatten().flat_map(|f| f.to_le_bytes()).collect(),
            );
            accessors.push(format!(
                r#"{{"bufferView":{v},"componentType":5126,"count":{},"type":"VEC2"}}"#,
                uvs.len()
            ));
            attributes += &format!(r#","TEXCOORD_0":{}"#, accessors.len() - 1);
        }
        let v = view(&mut bin, p.indices.iter().flat_map(|i| i.to_le_bytes()).collect());
        accessors.push(format!(
            r#"{{"bufferView":{v},"componentType":5125,"count":{},"type":"SCALAR"}}"#,
            p.indices.len()
        ));
        meshes.push(format!(
            r#"{{"primitives":[{{"attributes":{{{attributes}}},"indices":{},"material":{}}}]}}"#,
            accessors.len() - 1,
            p.material
        ));
        nodes.push(format!(r#"{{"mesh":{i}}}"#));
    }
    let mut light_defs = vec![];
    for (i, (at, candela)) in lights.iter().enumerate() {
        light_defs.push(format!(r#"{{"type":"point","intensity":{candela}}}"#));
        nodes.push(format!(
            r#"{{"translation":{at:?},"extensions":{{"KHR_lights_punctual":{{"light":{i}}}}}}}"#
        ));
    }
    let all: Vec<String> = (0..nodes.len()).map(|i| i.to_string()).collect();
    format!(
        r#"{{"asset":{{"version":"2.0"}},
        "extensionsUsed":["KHR_lights_punctual","KHR_materials_emissive_strength"],
        "extensions":{{"KHR_lights_punctual":{{"lights":[{}]}}}},
        "buffers":[{{"byteLength":{},"uri":"data:application/octet-stream,{}"}}],
        "bufferViews":[{}],"accessors":[{}],"meshes":[{}],"nodes":[{}],
        "materials":[{}],"textures":{textures},"images":[{}],
        "scenes":[{{"nodes":[{}]}}],"scene":0}}"#,
        light_defs.join(","),
        bin.len(),
        percent(&bin),
        views.join(","),
        accessors.join(","),
        meshes.join(","),
        nodes.join(","),
        materials.join(","),
        images.join(","),
        all.join(","),
    )
}

/// The cube `[0,1]³ + offset` as 12 inward-facing triangles.
pub fn room(offset: [f32; 3], material: usize) -> Prim {
    let positions = super::unit_cube_room::corners()
        .into_iter()
        .map(|c| [c[0] + offset[0], c[1] + offset[1], c[2] + offset[2]])
        .collect();
    let indices = super::unit_cube_room::triangle_indices();
    Prim {
        positions,
        uvs: None,
        indices,
        material,
    }
}

/// A `side × side` quad centred at `centre` in the xz plane, facing +y, u along x and v
/// along z over `[0, 1]²`.
pub fn emitter_quad(centre: [f32; 3], side: f32, material: usize) -> Prim {
    let h = side / 2.0;
    let [x, y, z] = centre;
    Prim {
        positions: vec![
            [x - h, y, z - h],
            [x - h, y, z + h],
            [x + h, y, z + h],
            [x + h, y, z - h],
        ],
        uvs: Some(vec![[0.0, 0.0], [0.0, 1.0], [1.0, 1.0], [1.0, 0.0]]),
        indices: vec![0, 1, 2, 0, 2, 3],
        material,
    }
}

pub fn png(width: u32, height: u32, rgb: &[u8]) -> Vec<u8> {
    let mut out = Vec::new();
    let mut e = png::Encoder::new(&mut out, width, height);
    e.set_color(png::ColorType::Rgb);
    e.set_depth(png::BitDepth::Eight);
    let mut w = e.write_header().unwrap();
    w.write_image_data(rgb).unwrap();
    w.finish().unwrap();
    out
}

pub fn png_image(bytes: &[u8]) -> String {
    format!(r#"{{"uri":"data:image/png,{}"}}"#, percent(bytes))
}
