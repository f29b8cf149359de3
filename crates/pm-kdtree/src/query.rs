//! Queries on a [`PhotonTree`]: the k nearest within a maximum distance (with a kind filter)
//! into a reusable buffer, and a visit-everything-within query.
//!
//! Both descend to the query's own leaf first, then visit the far side of a split only when
//! a lower bound on the distance to that side (built incrementally per axis, see
//! [`Metric::grow_bound`]) does not exceed the current k-th distance. Leaves are scanned in two
//! passes, ranks first (vectorisable) and then the few candidates, so the scan is branch-light.

use crate::metric::Metric;
use crate::photon::KindMask;
use crate::photon::kind_bit_of_bits;
use crate::tree::LEAF_CAPACITY;
use crate::tree::PhotonTree;
use glam::Vec3;

/// One found photon.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Neighbour {
    /// Index into the tree ([`crate::PhotonTree::get`]).
    pub index: u32,
    /// Distance from the query point under the query's metric (not squared).
    pub distance: f32,
}

/// Reusable result buffer of a k-nearest query; keep one per thread.
///
/// It grows to `k` entries on first use; later queries with the same or smaller `k`
/// allocate nothing.
#[derive(Clone, Debug, Default)]
pub struct Neighbours {
    found: Vec<Neighbour>,
    extent: f32,
    partial: bool,
}

impl Neighbours {
    /// An empty buffer.
    pub fn new() -> Self {
        Self::default()
    }
    /// An empty buffer with room for queries of up to `k` neighbours (no allocation in later
    /// queries; a search holds up to `2k` candidates before it trims them to `k`).
    pub fn with_capacity(k: usize) -> Self {
        Self {
            found: Vec::with_capacity(k.saturating_mul(2)),
            ..Self::default()
        }
    }
    /// The neighbours found, in no particular order (see [`Neighbours::sort_by_distance`]).
    pub fn as_slice(&self) -> &[Neighbour] {
        &self.found
    }
    /// Sorts the neighbours found by increasing distance (ties in no particular order).
    pub fn sort_by_distance(&mut self) {
        self.found
            .sort_unstable_by(|a, b| a.distance.total_cmp(&b.distance));
    }
    /// Number of neighbours found.
    pub fn len(&self) -> usize {
        self.found.len()
    }
    /// True when nothing was found.
    pub fn is_empty(&self) -> bool {
        self.found.is_empty()
    }
    /// The search extent: the k-th distance, or the maximum distance when fewer than k were found.
    pub fn extent(&self) -> f32 {
        self.extent
    }
    /// True when fewer than k photons lay within the maximum distance.
    pub fn is_partial(&self) -> bool {
        self.partial
    }
}

impl PhotonTree {
    /// The `k` nearest photons to `query` under metric `M` within `max_distance` whose kind is
    /// in `kinds`, written into `out` (in no particular order; see [`Neighbours`]).
    ///
    /// A photon at distance exactly `max_distance` counts as within. When fewer than `k`
    /// photons qualify, all of them are returned, [`Neighbours::extent`] is `max_distance` and
    /// [`Neighbours::is_partial`] is true. Edge cases: `k = 0` finds nothing, with extent 0 and
    /// not partial; a negative or NaN `max_distance` or a non-finite `query` finds nothing
    /// (partial, extent `max_distance`); an infinite `max_distance` is allowed. Allocates nothing once `out` holds `k`.
    pub fn nearest_k<M: Metric>(
        &self,
        query: Vec3,
        k: usize,
        max_distance: f32,
        kinds: KindMask,
        out: &mut Neighbours,
    ) {
        out.found.clear();
        if k == 0 {
            out.extent = 0.0;
            out.partial = false;
            return;
        }
        out.extent = max_distance;
        out.partial = true;
        if max_distance.is_nan() || max_distance < 0.0 || !in_range(query) || self.is_empty() {
            return;
        }
        // The candidates never outnumber the tree: a huge k must not reserve for it.
        out.found.reserve(k.saturating_mul(2).min(self.len()));
        let max_rank = M::distance_to_rank(max_distance);
        let mut search = Knn::<M> {
            tree: self,
            query,
            k,
            worst: max_rank,
            all_kinds: kinds.accepts_all(),
            kinds: kinds.0,
            found: &mut out.found,
            metric: std::marker::PhantomData,
        };
        let (bound, offsets) = self.root_bound::<M>(query);
        if bound <= max_rank {
            self.descend::<M, _>(query, &mut search, 1, 0, self.len(), 0, bound, offsets);
        }
        if search.found.len() >= k {
            search.keep_nearest_k();
        }
        for n in out.found.iter_mut() {
            n.distance = M::rank_to_distance(n.distance);
        }
        if out.found.len() == k {
            // `keep_nearest_k` left the k-th nearest last.
            out.extent = out.found[k - 1].distance;
            out.partial = false;
        }
    }

    /// Calls `f(index, distance)` for every photon within `radius` of `query` under `M`
    /// (a photon at distance exactly `radius` included), in no particular order. A negative or
    /// NaN radius, or a non-finite query, visits nothing.
    pub fn for_each_within<M: Metric>(&self, query: Vec3, radius: f32, mut f: impl FnMut(u32, f32)) {
        if radius.is_nan() || radius < 0.0 || !in_range(query) || self.is_empty() {
            return;
        }
        let mut search = Within::<M, _> {
            tree: self,
            query,
            limit: M::distance_to_rank(radius),
            f: &mut f,
            metric: std::marker::PhantomData,
        };
        let (bound, offsets) = self.root_bound::<M>(query);
        if bound <= search.limit {
            self.descend::<M, _>(query, &mut search, 1, 0, self.len(), 0, bound, offsets);
        }
    }

    /// The traversal every search shares: from `node` (holding photons `lo..hi`, at `level`,
    /// whose region is at least `bound` from `query` with per-axis `offsets`), the nearer child
    /// first, then the farther one only while its bound is within `search.limit()`.
    #[allow(clippy::too_many_arguments)]
    fn descend<M: Metric, S: LeafSearch>(
        &self,
        query: Vec3,
        search: &mut S,
        node: usize,
        lo: usize,
        hi: usize,
        level: u32,
        bound: f32,
        offsets: [f32; 3],
    ) {
        if level == self.depth {
            search.scan_leaf(lo, hi);
            return;
        }
        let axis = self.axes[node] as usize;
        let delta = query[axis] - self.splits[node];
        let mid = lo + (hi - lo) / 2;
        let (near, near_lo, near_hi, far, far_lo, far_hi) = if delta < 0.0 {
            (2 * node, lo, mid, 2 * node + 1, mid, hi)
        } else {
            (2 * node + 1, mid, hi, 2 * node, lo, mid)
        };
        self.descend::<M, S>(query, search, near, near_lo, near_hi, level + 1, bound, offsets);
        let offset = M::axis_rank(delta);
        let far_bound = M::grow_bound(bound, offsets[axis], offset);
        if far_bound <= search.limit() {
            let mut far_offsets = offsets;
            far_offsets[axis] = offset;
            self.descend::<M, S>(
                query,
                search,
                far,
                far_lo,
                far_hi,
                level + 1,
                far_bound,
                far_offsets,
            );
        }
    }

    /// The lower bound on the rank of every photon from `query`, and its per-axis offsets:
    /// the distance from `query` to the photons' bounding box. Without it a query outside the
    /// box (a dark room beside a lit one in a single map) would prune nothing along the axes
    /// it lies outside on, and visit every leaf in a slab through the whole tree.
    #[inline]
    fn root_bound<M: Metric>(&self, query: Vec3) -> (f32, [f32; 3]) {
        let [lo, hi] = self.bounds;
        let mut offsets = [0.0; 3];
        let mut bound = 0.0;
        for (axis, offset) in offsets.iter_mut().enumerate() {
            let q = query[axis];
            let outside = (lo[axis] - q).max(q - hi[axis]).max(0.0);
            *offset = M::axis_rank(outside);
            bound = M::grow_bound(bound, 0.0, *offset);
        }
        (bound, offsets)
    }

    /// Ranks of the photons `lo..hi` (at most [`LEAF_CAPACITY`]) from `query`, into `ranks`.
    #[inline(always)]
    fn leaf_ranks<M: Metric>(
        &self,
        query: Vec3,
        lo: usize,
        hi: usize,
        ranks: &mut [f32; LEAF_CAPACITY],
    ) -> usize {
        let len = (hi - lo).min(LEAF_CAPACITY);
        let (xs, ys, zs) = (
            &self.xs[lo..lo + len],
            &self.ys[lo..lo + len],
            &self.zs[lo..lo + len],
        );
        for (((r, &x), &y), &z) in ranks[..len].iter_mut().zip(xs).zip(ys).zip(zs) {
            *r = M::rank(Vec3::new(x - query.x, y - query.y, z - query.z));
        }
        len
    }
}

/// What the shared traversal ([`PhotonTree::descend`]) asks of a search.
trait LeafSearch {
    /// The largest rank still of interest (a k-nearest search shrinks it as it fills).
    fn limit(&self) -> f32;
    /// Looks at the photons `lo..hi` of one leaf.
    fn scan_leaf(&mut self, lo: usize, hi: usize);
}

/// State of one k-nearest search. `found` holds ranks (not distances) while searching: all
/// candidates within `worst`, trimmed to the k nearest whenever it reaches `2k`.
struct Knn<'a, M> {
    tree: &'a PhotonTree,
    query: Vec3,
    k: usize,
    /// Rank a photon must not exceed to be kept: the maximum rank at first, then the largest of
    /// the first k, then the k-th nearest at the last trim.
    worst: f32,
    all_kinds: bool,
    kinds: u8,
    found: &'a mut Vec<Neighbour>,
    metric: std::marker::PhantomData<M>,
}

impl<M: Metric> LeafSearch for Knn<'_, M> {
    #[inline]
    fn limit(&self) -> f32 {
        self.worst
    }

    #[inline]
    fn scan_leaf(&mut self, lo: usize, hi: usize) {
        let mut ranks = [0.0f32; LEAF_CAPACITY];
        let len = self.tree.leaf_ranks::<M>(self.query, lo, hi, &mut ranks);
        // A bit per candidate, computed without branches; `insert` re-checks against the
        // threshold, which tightens as candidates go in.
        let worst = self.worst;
        let mut candidates = ranks[..len]
            .iter()
            .enumerate()
            .fold(0u64, |bits, (i, &rank)| bits | u64::from(rank <= worst) << i);
        while candidates != 0 {
            let i = candidates.trailing_zeros() as usize;
            candidates &= candidates - 1;
            let index = lo + i;
            if self.all_kinds || self.kinds & kind_bit_of_bits(self.tree.payload[index]) != 0 {
                self.insert(index as u32, ranks[i]);
            }
        }
    }
}

impl<M: Metric> Knn<'_, M> {
    /// Adds a candidate. Candidates are only appended; when `2k` have piled up, a quickselect
    /// keeps the `k` nearest and tightens `worst` to the k-th rank. That costs O(1) per
    /// candidate on average, against O(log k) unpredictable branches for a binary heap, at the
    /// price of a looser bound between trims.
    #[inline]
    fn insert(&mut self, index: u32, rank: f32) {
        let full = self.found.len() >= self.k;
        if full && rank >= self.worst {
            return;
        }
        self.found.push(Neighbour {
            index,
            distance: rank,
        });
        let len = self.found.len();
        if len == self.k && !full {
            // The first k: the worst of them bounds the rest of the search.
            self.worst = self.found.iter().fold(0.0f32, |w, n| w.max(n.distance));
        } else if len == self.k.saturating_mul(2) {
            self.keep_nearest_k();
        }
    }

    /// Trims `found` (at least `k` long) to its `k` nearest, the k-th nearest last, and makes
    /// its rank the bound.
    fn keep_nearest_k(&mut self) {
        let k = self.k;
        self.found
            .select_nth_unstable_by(k - 1, |a, b| a.distance.total_cmp(&b.distance));
        self.found.truncate(k);
        self.worst = self.found[k - 1].distance;
    }
}

/// State of one visit-everything-within search.
struct Within<'a, M, F> {
    tree: &'a PhotonTree,
    query: Vec3,
    limit: f32,
    f: &'a mut F,
    metric: std::marker::PhantomData<M>,
}

impl<M: Metric, F: FnMut(u32, f32)> LeafSearch for Within<'_, M, F> {
    #[inline]
    fn limit(&self) -> f32 {
        self.limit
    }

    #[inline]
    fn scan_leaf(&mut self, lo: usize, hi: usize) {
        let mut ranks = [0.0f32; LEAF_CAPACITY];
        let len = self.tree.leaf_ranks::<M>(self.query, lo, hi, &mut ranks);
        for (i, &rank) in ranks[..len].iter().enumerate() {
            if rank <= self.limit {
                (self.f)((lo + i) as u32, M::rank_to_distance(rank));
            }
        }
    }
}

/// A finite query point within [`crate::MAX_COORDINATE`] on every axis (farther, squared
/// distances to the tree's photons could overflow and rank wrongly).
fn in_range(query: Vec3) -> bool {
    query.is_finite() && query.abs().max_element() <= crate::tree::MAX_COORDINATE
}
