//! Helpers shared by the pm-trace integration tests: test meshes and photon sums.

#![allow(dead_code)]

use pm_trace::glam::{DVec3, Vec3};
use pm_trace::{PhotonKind, TracedPhotons};

/// An icosphere of radius `r` at `c`: an icosahedron subdivided `levels` times, projected
/// onto the sphere, outward-facing triangles.
pub fn icosphere(c: Vec3, r: f32, levels: u32) -> (Vec<Vec3>, Vec<[u32; 3]>) {
    let t = (1.0 + 5f32.sqrt()) / 2.0;
    let mut v: Vec<Vec3> = [
        [-1.0, t, 0.0],
        [1.0, t, 0.0],
        [-1.0, -t, 0.0],
        [1.0, -t, 0.0],
        [0.0, -1.0, t],
        [0.0, 1.0, t],
        [0.0, -1.0, -t],
        [0.0, 1.0, -t],
        [t, 0.0, -1.0],
        [t, 0.0, 1.0],
        [-t, 0.0, -1.0],
        [-t, 0.0, 1.0],
    ]
    .iter()
    .map(|a| Vec3::from(*a).normalize())
    .collect();
    let mut f: Vec<[u32; 3]> = vec![
        [0, 11, 5],
        [0, 5, 1],
        [0, 1, 7],
        [0, 7, 10],
        [0, 10, 11],
        [1, 5, 9],
        [5, 11, 4],
        [11, 10, 2],
        [10, 7, 6],
        [7, 1, 8],
        [3, 9, 4],
        [3, 4, 2],
        [3, 2, 6],
        [3, 6, 8],
        [3, 8, 9],
        [4, 9, 5],
        [2, 4, 11],
        [6, 2, 10],
        [8, 6, 7],
        [9, 8, 1],
    ];
    for _ in 0..levels {
        let mut mid = std::collections::HashMap::new();
        let mut next = Vec::new();
        let mut midpoint = |a: u32, b: u32, v: &mut Vec<Vec3>| -> u32 {
            *mid.entry((a.min(b), a.max(b))).or_insert_with(|| {
                v.push(((v[a as usize] + v[b as usize]) * 0.5).normalize());
                v.len() as u32 - 1
            })
        };
        for [a, b, c] in f {
            let ab = midpoint(a, b, &mut v);
            let bc = midpoint(b, c, &mut v);
            let ca = midpoint(c, a, &mut v);
            next.extend([[a, ab, ca], [b, bc, ab], [c, ca, bc], [ab, bc, ca]]);
        }
        f = next;
    }
    (v.into_iter().map(|p| c + p * r).collect(), f)
}

/// Sum (in double precision) of the power of the photons of `kind` (all kinds for `None`)
/// over all maps.
pub fn stored_power(traced: &TracedPhotons, kind: Option<PhotonKind>) -> DVec3 {
    traced
        .photons_per_map()
        .iter()
        .flatten()
        .filter(|p| kind.is_none_or(|k| p.kind == k))
        .map(|p| p.power.as_dvec3())
        .sum()
}

/// The unit cube `[0, 1]³` as six quads with inward normals (a closed room).
pub fn unit_box() -> (Vec<Vec3>, Vec<[u32; 4]>) {
    let c: Vec<Vec3> = (0..8)
        .map(|i| Vec3::new((i & 1) as f32, ((i >> 1) & 1) as f32, ((i >> 2) & 1) as f32))
        .collect();
    (
        c,
        vec![
            [0, 4, 5, 1],
            [2, 3, 7, 6],
            [0, 2, 6, 4],
            [1, 5, 7, 3],
            [4, 6, 7, 5],
            [0, 1, 3, 2],
        ],
    )
}
