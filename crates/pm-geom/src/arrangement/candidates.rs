//! The broad phase of an arrangement: which pairs of faces may meet, through a hierarchy over
//! each face's reach.

use super::face::Face;
use crate::aabb::Aabb;
use crate::bounds_bvh::BoundsBvh;
use glam::Vec3;

/// The pairs of faces that may meet: each face reaches `gap` along its own normal (where a
/// near-contact or a facing overlap finds the other face) and twice the tolerance every way
/// (where faces cross or touch), and a pair is a candidate when either face's reach overlaps
/// the other's own bounds. Each pair once, `i < j`, in index order, whatever the tree.
///
/// Why along the normal only: every meeting the pair test reports has a point of one face
/// within `gap` of the other face's plane whose projection lies on that face (near-contacts,
/// in-plane overlaps), or a point within the tolerance of both (crossings). A tessellated
/// floor's triangles padded by the gap every way were partners of all their neighbours within
/// the gap (13.1 M candidates on a 57k-triangle kitchen, 96 % of them missing); padded along
/// the floor's normal they meet only what lies on or above them.
pub(super) struct CandidatePairs {
    /// The faces that take part (indices into the input).
    pub(super) live: Vec<usize>,
    /// Each live face's bounds padded by its reach (gap along the normal, twice the tolerance
    /// every way), which the tree holds, and padded by twice the tolerance only.
    reach: Vec<Aabb>,
    tight: Vec<Aabb>,
    bvh: BoundsBvh,
}

impl CandidatePairs {
    pub(super) fn new(faces: &[Option<Face>], tolerance: f32, gap: f32) -> Self {
        let live: Vec<usize> = (0..faces.len()).filter(|&i| faces[i].is_some()).collect();
        let margin = Vec3::splat(2.0 * tolerance);
        let (mut reach, mut tight) = (Vec::with_capacity(live.len()), Vec::with_capacity(live.len()));
        for &i in &live {
            let face = faces[i].as_ref().expect("live faces are faces");
            let own = Aabb::from_points(face.vertices);
            // The normal's components rounded up a little, so that rounding never shortens a
            // reach: the pair test's projections err by far less than the tolerance margin.
            let along = face.normal.abs() * (gap * (1.0 + 1e-3));
            reach.push(Aabb::new(own.min - margin - along, own.max + margin + along));
            tight.push(Aabb::new(own.min - margin, own.max + margin));
        }
        // Every face queries the tree once: leaves of 12 halve the levels each query walks
        // (82 against 97 ms on split-rooms-100's 120,000 quads with leaves of 4).
        let bvh = BoundsBvh::build_sah(&reach, 12);
        CandidatePairs {
            live,
            reach,
            tight,
            bvh,
        }
    }

    /// The later live faces (tree indices `m > n`) that may meet live face `n`, in index order,
    /// into `partners`; stops adding past `cap` of them.
    pub(super) fn partners(&self, n: usize, cap: usize, partners: &mut Vec<u32>) {
        let (reach, tight) = (&self.reach[n], &self.tight[n]);
        partners.clear();
        self.bvh.for_each_candidate(reach, |m| {
            let k = m as usize;
            if k > n
                && (reach.overlaps(&self.tight[k]) || tight.overlaps(&self.reach[k]))
                && partners.len() <= cap
            {
                partners.push(m);
            }
        });
        // In index order, not the tree's: which pairs are candidates is then all that the
        // cuts depend on, and a better broad phase cannot change the pieces.
        partners.sort_unstable();
    }
}

#[cfg(test)]
mod tests {
    use super::super::continuation::NO_FACE;
    use super::super::face_of;
    use super::super::pair::{Meeting, PairOutcome, PairScratch, meet};
    use super::super::test_stream::stream;
    use super::*;

    /// Every pair the pair test finds meeting is a candidate, checked by brute force over all
    /// pairs of 1,200 small triangles in a unit box: a third in axis planes, a third in
    /// planes tilted a few degrees off them, a third at random, placed densely enough that
    /// there are about 1,900 near-contacts and 4,000 other meetings. With the reach
    /// cut to the tolerance margin (no gap along the normal) the near-contacts go missing.
    #[test]
    fn every_pair_that_meets_is_a_candidate() {
        every_pair_that_meets_is_a_candidate_at(1.0, Vec3::ZERO);
    }

    /// The same at the ends of the operating range: the box a micrometre wide at the origin,
    /// and ten kilometres wide ten thousand kilometres from it, where a float step is a metre
    /// and the tolerance is raised to eight of them, as the arrangement raises it.
    #[test]
    fn every_pair_that_meets_is_a_candidate_at_micrometres_and_far_from_the_origin() {
        every_pair_that_meets_is_a_candidate_at(1e-6, Vec3::ZERO);
        every_pair_that_meets_is_a_candidate_at(1e4, Vec3::new(1e7, -6e6, 3e6));
    }

    fn every_pair_that_meets_is_a_candidate_at(scale: f32, origin: Vec3) {
        let mut next = stream();
        let largest = (origin.abs() + Vec3::splat(scale)).max_element();
        let tolerance = (1e-4 * scale).max(largest * 8.0 * f32::EPSILON);
        let gap = 0.03 * scale;
        let mut polygons: Vec<Vec<Vec3>> = Vec::new();
        for i in 0..1200 {
            let centre = Vec3::new(next(), next(), next()) * 0.6;
            let axis = match i % 3 {
                0 => [Vec3::X, Vec3::Y, Vec3::Z][(next() * 3.0) as usize % 3],
                1 => (Vec3::Z + 0.08 * Vec3::new(next() - 0.5, next() - 0.5, 0.0)).normalize(),
                _ => Vec3::new(next() - 0.5, next() - 0.5, next() - 0.5).normalize_or(Vec3::Z),
            };
            let u = axis.any_orthonormal_vector();
            let v = axis.cross(u);
            let (start, sizes) = (
                next() * std::f32::consts::TAU,
                [0.5 + next(), 0.5 + next(), 0.5 + next()],
            );
            let corner = |k: usize| {
                let a = start + 2.1 * k as f32;
                origin + scale * (centre + 0.08 * sizes[k] * (u * a.cos() + v * a.sin()))
            };
            polygons.push(vec![corner(0), corner(1), corner(2)]);
        }
        let across = [NO_FACE; 3];
        let faces: Vec<_> = polygons.iter().map(|p| face_of(p, &across, gap)).collect();
        let candidates = CandidatePairs::new(&faces, tolerance, gap);
        let (mut scratch, mut outcome) = (PairScratch::default(), PairOutcome::default());
        let (mut met, mut partners) = ([0usize; 2], Vec::new());
        for n in 0..candidates.live.len() {
            candidates.partners(n, usize::MAX, &mut partners);
            let a = faces[candidates.live[n]].as_ref().unwrap();
            for m in n + 1..candidates.live.len() {
                let b = faces[candidates.live[m]].as_ref().unwrap();
                meet(&faces, a, b, tolerance, gap, &mut scratch, &mut outcome);
                let found = outcome.meeting.is_some()
                    || outcome.second_hidden
                    || !outcome.on_first.is_empty()
                    || !outcome.on_second.is_empty();
                if found {
                    met[usize::from(matches!(outcome.meeting, Some(Meeting::NearContact)))] += 1;
                    assert!(
                        partners.binary_search(&(m as u32)).is_ok(),
                        "scale {scale}, origin {origin}: faces {n} and {m} meet but are not candidates"
                    );
                }
            }
        }
        assert!(
            met[0] > 100 && met[1] > 100,
            "scale {scale}, origin {origin}: too few meetings to test: {met:?}"
        );
    }
}
