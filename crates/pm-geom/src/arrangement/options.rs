//! What a caller sets for an arrangement: the tolerance under which points coincide, the gap
//! under which faces touch, and the bounds on its work.

/// Tolerances and bounds of [`split_polygons_at_intersections`](super::split_polygons_at_intersections).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ArrangementOptions {
    /// Distance (metres) under which points coincide and a point lies on a plane or a line; a
    /// good choice is `1e-5` × the scene's diagonal, and a mesh welded from the output should
    /// use the same weld tolerance.
    pub tolerance: f32,
    /// Distance (metres, at least `tolerance`) under which two faces that do not meet count as
    /// touching: a wall that stops this close to a floor cuts the floor as if it stood on it.
    pub gap: f32,
    /// Most candidate face pairs (faces whose padded bounds overlap) examined.
    pub max_pairs: usize,
    /// Most output pieces, and most cut segments.
    pub max_pieces: usize,
    /// Most output pieces per input polygon, over the whole arrangement (a floor of
    /// [`Self::MIN_PIECE_LIMIT`] pieces is always allowed): see [`Self::piece_limit`].
    pub max_pieces_per_polygon: usize,
    /// Most vertices over all output pieces.
    pub max_vertices: usize,
    /// Most distinct cut lines on one input polygon. Cuts along one line merge, and finding the
    /// line a new cut joins looks through the polygon's lines, so this bounds that work too (a
    /// floor under a dense field of small objects within the gap of it gets a line per object
    /// edge).
    pub max_cut_lines_per_polygon: usize,
}

impl ArrangementOptions {
    /// Default [`Self::max_pairs`]: 16 million pairs, a few seconds of work.
    pub const DEFAULT_MAX_PAIRS: usize = 16_000_000;
    /// Default [`Self::max_pieces`]: 2 million pieces.
    pub const DEFAULT_MAX_PIECES: usize = 2_000_000;
    /// Default [`Self::max_vertices`]: 16 million vertices (192 MB of positions).
    pub const DEFAULT_MAX_VERTICES: usize = 16_000_000;
    /// Default [`Self::max_pieces_per_polygon`]: 8. Real interiors stay far below it (walls on
    /// floors, objects on counters: a few pieces per face on average); near-copies of one mesh
    /// cut each other into grids (51 copies of a 12-face room, offset by 10⁻⁴ of its size: 2,500
    /// pieces per face, 1.5 million in all, 53 s and 2.6 GB on 2 cores before the limit).
    pub const DEFAULT_MAX_PIECES_PER_POLYGON: usize = 8;
    /// Default [`Self::max_cut_lines_per_polygon`]: 16,384. A floor under 80,000 cubes hovering
    /// within the gap gets about 320,000; looking each new cut's line up among that many took
    /// minutes, while the faces of real interiors get tens to hundreds.
    pub const DEFAULT_MAX_CUT_LINES_PER_POLYGON: usize = 16_384;
    /// The pieces always allowed, however few the input polygons.
    pub const MIN_PIECE_LIMIT: usize = 100_000;

    /// `tolerance` and `gap` with the default bounds.
    pub fn new(tolerance: f32, gap: f32) -> Self {
        ArrangementOptions {
            tolerance,
            gap,
            max_pairs: Self::DEFAULT_MAX_PAIRS,
            max_pieces: Self::DEFAULT_MAX_PIECES,
            max_pieces_per_polygon: Self::DEFAULT_MAX_PIECES_PER_POLYGON,
            max_vertices: Self::DEFAULT_MAX_VERTICES,
            max_cut_lines_per_polygon: Self::DEFAULT_MAX_CUT_LINES_PER_POLYGON,
        }
    }

    /// The most pieces an arrangement of `polygons` input polygons may make: [`Self::max_pieces`],
    /// or [`Self::max_pieces_per_polygon`] per input polygon (at least
    /// [`Self::MIN_PIECE_LIMIT`]) if that is fewer. Pieces are counted as they are cut, so a
    /// split that would pass the limit stops at it, before the pieces' own cost (welding,
    /// sealing, the scene rebuilt from them) is paid.
    pub fn piece_limit(&self, polygons: usize) -> usize {
        let relative = polygons
            .saturating_mul(self.max_pieces_per_polygon)
            .max(Self::MIN_PIECE_LIMIT);
        self.max_pieces.min(relative)
    }
}
