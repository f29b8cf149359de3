//! Copies of one face: exact copies found by sorting hashes of their vertices, and the test of
//! whether a piece lies under another face in the same plane (a later copy's hidden part).

use super::face::Face;
use glam::Vec3;

/// For each polygon, whether an earlier one has the same vertices in the same cyclic order
/// (an exact copy, facing the same way). Polygons are sorted by a hash of their vertices
/// (starting at the smallest), and only those with equal hashes are compared.
pub(super) fn exact_duplicates<P: AsRef<[Vec3]>>(polygons: &[P]) -> Vec<bool> {
    let hash = |p: &[Vec3]| {
        rotated(p).flatten().fold(0xcbf2_9ce4_8422_2325u64, |h, bits| {
            (h ^ bits as u64).wrapping_mul(0x0100_0000_01b3)
        })
    };
    let mut order: Vec<(u64, usize)> = polygons
        .iter()
        .enumerate()
        .map(|(i, p)| (hash(p.as_ref()), i))
        .collect();
    order.sort_unstable();
    let mut duplicate = vec![false; polygons.len()];
    for run in order.chunk_by(|a, b| a.0 == b.0).filter(|run| run.len() > 1) {
        for (k, &(_, i)) in run.iter().enumerate() {
            let p = polygons[i].as_ref();
            duplicate[i] = run.iter().enumerate().any(|(m, &(_, j))| {
                let q = polygons[j].as_ref();
                m != k && j < i && q.len() == p.len() && rotated(q).eq(rotated(p))
            });
        }
    }
    duplicate
}

/// The vertices of `p` as bits, starting at the smallest, in order.
fn rotated(p: &[Vec3]) -> impl Iterator<Item = [u32; 3]> + '_ {
    let start = (0..p.len())
        .min_by_key(|&i| p[i].to_array().map(f32::to_bits))
        .unwrap_or(0);
    (0..p.len()).map(move |k| p[(start + k) % p.len()].to_array().map(f32::to_bits))
}

/// Whether `piece` lies in (or within `gap` of) `cover`'s plane and inside its outline.
pub(super) fn covered_by(piece: &[Vec3], cover: &Face, tolerance: f32, gap: f32) -> bool {
    let centroid = piece.iter().copied().sum::<Vec3>() / piece.len() as f32;
    let distance = cover.normal.dot(centroid) - cover.offset;
    if distance.abs() > gap {
        return false;
    }
    let c = centroid - cover.normal * distance;
    let n = cover.vertices.len();
    (0..n).all(|i| {
        let (a, b) = (cover.vertices[i], cover.vertices[(i + 1) % n]);
        cover.normal.cross(b - a).normalize_or_zero().dot(c - a) >= -tolerance
    })
}
