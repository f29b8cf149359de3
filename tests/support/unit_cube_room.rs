//! A unit cube room seen from inside, as the glTF tests write it: eight corners (corner `i`
//! at `(i & 1, i >> 1 & 1, i >> 2 & 1)`) and six quads wound to face inwards, split into
//! twelve triangles.

/// The eight corners of the unit cube, corner `i` at `(i & 1, i >> 1 & 1, i >> 2 & 1)`.
pub fn corners() -> [[f32; 3]; 8] {
    std::array::from_fn(|i| [(i & 1) as f32, ((i >> 1) & 1) as f32, ((i >> 2) & 1) as f32])
}

/// The six faces as corner quads, wound so that their normals point into the cube.
const INWARD_QUADS: [[u32; 4]; 6] = [
    [0, 4, 5, 1],
    [2, 3, 7, 6],
    [0, 2, 6, 4],
    [1, 5, 7, 3],
    [4, 6, 7, 5],
    [0, 1, 3, 2],
];

/// The 36 triangle indices of the inward faces (each quad `a b c d` as `a b c` and `a c d`).
pub fn triangle_indices() -> Vec<u32> {
    INWARD_QUADS
        .iter()
        .flat_map(|q| [q[0], q[1], q[2], q[0], q[2], q[3]])
        .collect()
}
