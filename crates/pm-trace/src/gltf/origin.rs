//! Re-centring: a flattened scene's world bounds, kept in f64, decide the world point its f32
//! coordinates are made relative to, so a model placed kilometres from the file's origin (a
//! georeferenced root node) keeps the detail it has near its own centre.

use glam::{DVec3, Vec3};

/// The bounds of world-space points in f64, empty until a point is added.
#[derive(Clone, Copy, Debug, Default)]
pub(super) struct WorldBounds {
    corners: Option<(DVec3, DVec3)>,
}

impl WorldBounds {
    /// The bounds grown to hold `p`.
    pub(super) fn add(&mut self, p: DVec3) {
        self.corners = Some(match self.corners {
            Some((lo, hi)) => (lo.min(p), hi.max(p)),
            None => (p, p),
        });
    }

    /// The world point the scene is re-centred on, subtracted from every position before it
    /// becomes f32: the bounds' centre when it lies farther from the origin than the bounds'
    /// largest side, else zero (also without points, or with bounds that are not finite, whose
    /// positions then fail their own f32 check).
    ///
    /// Near the origin nothing moves: every coordinate is then within 1.5 times the largest
    /// side, against half of it re-centred, so re-centring would gain at most two bits of f32
    /// precision, while staying put keeps the file's own coordinates and every image of a model
    /// modelled around its origin bit for bit. Far out, the f32 spacing at the geometry falls
    /// from that of the offset's magnitude to that of the model's own size.
    pub(super) fn origin_offset(&self) -> DVec3 {
        let Some((lo, hi)) = self.corners else {
            return DVec3::ZERO;
        };
        let centre = (lo + hi) * 0.5;
        let extent = (hi - lo).max_element();
        let far = centre.abs().max_element() > extent;
        if centre.is_finite() && extent.is_finite() && far {
            centre
        } else {
            DVec3::ZERO
        }
    }
}

/// `v` (an f64 direction) as an f32 unit vector: rounded to f32 and normalised there (so a
/// direction that composes exactly, as under identity or axis-aligned transforms, gives the
/// same bits as an f32 pipeline), else divided by its largest component in f64 first when its
/// length leaves f32's range; `None` when it has no direction.
pub(super) fn unit_f32(v: DVec3) -> Option<Vec3> {
    v.as_vec3().try_normalize().or_else(|| {
        let largest = v.abs().max_element();
        let scalable = largest.is_finite() && largest > 0.0;
        scalable
            .then(|| (v / largest).as_vec3().try_normalize())
            .flatten()
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    fn bounds(points: &[[f64; 3]]) -> WorldBounds {
        let mut b = WorldBounds::default();
        for &p in points {
            b.add(DVec3::from(p));
        }
        b
    }

    #[test]
    fn a_model_around_its_origin_stays_put() {
        assert_eq!(WorldBounds::default().origin_offset(), DVec3::ZERO);
        // Centre (1, 0.5, 0.5), largest side 2: not farther out than the model is large.
        assert_eq!(
            bounds(&[[0.0, 0.0, 0.0], [2.0, 1.0, 1.0]]).origin_offset(),
            DVec3::ZERO
        );
    }

    #[test]
    fn a_model_far_out_is_centred() {
        let b = bounds(&[[6.4e6, 0.0, -3.0], [6.4e6 + 2.0, 1.0, -1.0]]);
        assert_eq!(b.origin_offset(), DVec3::new(6.4e6 + 1.0, 0.5, -2.0));
        // One point: no extent, any distance from the origin is far.
        assert_eq!(
            bounds(&[[0.0, 5.0, 0.0]]).origin_offset(),
            DVec3::new(0.0, 5.0, 0.0)
        );
    }

    #[test]
    fn bounds_that_are_not_finite_give_no_offset() {
        let b = bounds(&[[0.0; 3], [f64::INFINITY, 0.0, 0.0]]);
        assert_eq!(b.origin_offset(), DVec3::ZERO);
    }

    #[test]
    fn directions_keep_their_f32_bits_and_survive_f32_overflow() {
        let v = Vec3::new(0.3, -0.4, 0.5);
        assert_eq!(unit_f32(v.as_dvec3()), v.try_normalize());
        let huge = unit_f32(DVec3::new(1e300, 0.0, 0.0));
        assert_eq!(huge, Some(Vec3::X));
        let tiny = unit_f32(DVec3::new(0.0, -1e-300, 0.0));
        assert_eq!(tiny, Some(Vec3::NEG_Y));
        assert_eq!(unit_f32(DVec3::ZERO), None);
        assert_eq!(unit_f32(DVec3::NAN), None);
    }
}
