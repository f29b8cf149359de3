//! The implicit kd-tree over compact photons: layout, parallel build and `validate`.
//!
//! Layout: photons are reordered so every node covers a contiguous range, split at its
//! middle (`mid = lo + (hi − lo) / 2`), down to leaves of at most [`LEAF_CAPACITY`]
//! photons. Node ranges follow from the photon count alone, so no per-node pointers or
//! ranges are stored: only each inner node's split value and axis, in heap (Eytzinger)
//! order with the root at 1. Positions are kept apart from the 8-byte payloads, one array
//! per axis, so leaf scans read only coordinates and vectorise.

use crate::error::BuildError;
use crate::photon::Photon;
use crate::photon::{CompactPhoton, kind_code_of_bits};
use crate::power_code::PowerScale;
use glam::Vec3;
use rayon::prelude::*;
use std::sync::atomic::{AtomicU64, Ordering};

/// Most photons in a leaf.
pub const LEAF_CAPACITY: usize = 32;
// Leaf scans mark candidates in a u64.
const _: () = assert!(LEAF_CAPACITY <= 64);
/// Below this many photons a subtree is built on one thread.
const PARALLEL_MIN: usize = 32 * 1024;

/// A kd-tree of photons in an implicit layout (no per-node pointers).
///
/// Build it once with [`PhotonTree::build`], then query it from many threads with
/// [`PhotonTree::nearest_k`] and [`PhotonTree::for_each_within`]. Indices returned by
/// queries are positions in tree order, for [`PhotonTree::get`] and [`PhotonTree::power`].
///
/// Photon powers are stored relative to the tree's [`PowerScale`], the largest power channel
/// of its photons: [`PhotonTree::power`] returns watts, and a sum of
/// [`CompactPhoton::relative_power`] times [`PowerScale::watts`] is the same in one multiply.
#[derive(Clone, Debug)]
pub struct PhotonTree {
    pub(crate) xs: Vec<f32>,
    pub(crate) ys: Vec<f32>,
    pub(crate) zs: Vec<f32>,
    pub(crate) payload: Vec<u64>,
    /// Split value of inner node `i` (root at 1; index 0 unused).
    pub(crate) splits: Vec<f32>,
    /// Split axis (0, 1, 2) of inner node `i`.
    pub(crate) axes: Vec<u8>,
    /// Levels of inner nodes: the tree has `2^depth` leaves.
    pub(crate) depth: u32,
    /// Smallest and largest photon coordinates: the root cell, so that a query outside the
    /// photons' bounds starts with the right distance bound instead of zero.
    pub(crate) bounds: [[f32; 3]; 2],
    /// Watts of the top power code.
    pub(crate) scale: PowerScale,
    /// Finite positive power channels below the smallest code, stored as zero.
    pub(crate) below_range: u64,
}

impl Default for PhotonTree {
    /// An empty tree (one empty leaf), the same as building from no photons.
    fn default() -> Self {
        PhotonTree {
            xs: Vec::new(),
            ys: Vec::new(),
            zs: Vec::new(),
            payload: Vec::new(),
            splits: vec![0.0],
            axes: vec![0],
            depth: 0,
            bounds: [[f32::INFINITY; 3], [f32::NEG_INFINITY; 3]],
            scale: PowerScale::default(),
            below_range: 0,
        }
    }
}

/// An invariant of a [`PhotonTree`] that does not hold (from [`PhotonTree::validate`]).
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[error("photon tree invariant broken at node {node}: {what}")]
pub struct InvariantError {
    /// Inner node (heap index, root 1), or 0 for whole-tree checks.
    pub node: usize,
    /// What is wrong.
    pub what: String,
}

/// Split decisions of one subtree: (heap index, split value, axis).
type Splits = Vec<(usize, f32, u8)>;

/// The largest photon coordinate magnitude a tree accepts, in metres (10¹⁸). Squared
/// distances between points within it stay finite in f32 (3 · (2 · 10¹⁸)² ≈ 1.2 · 10³⁷ <
/// 3.4 · 10³⁸); [`PhotonTree::build`] refuses photons beyond it with
/// [`BuildError::PositionOutOfRange`], and queries from points beyond it find nothing.
pub const MAX_COORDINATE: f32 = 1e18;

impl PhotonTree {
    /// Builds the tree from photons in full precision (reorders them). Errors on non-finite
    /// positions and on coordinates beyond [`MAX_COORDINATE`].
    ///
    /// The power scale is the largest finite power channel of any photon
    /// ([`PowerScale::for_photons`]), so every channel within 2⁻⁴⁰ of it keeps 0.7 % (unbiased);
    /// positive channels further below are stored as zero and counted
    /// ([`PhotonTree::channels_below_range`]). The photons are encoded into 20 bytes each and
    /// dropped before the tree is built. Median selection per node, O(n log n); subtrees
    /// above 32k photons are built in parallel with rayon.
    pub fn build(photons: Vec<Photon>) -> Result<Self, BuildError> {
        let (compact, scale, below_range) = encode_all(&photons)?;
        drop(photons);
        Ok(Self::build_compact(compact, scale, below_range))
    }

    /// [`PhotonTree::build`] from a slice (the photons are encoded, not copied).
    pub fn from_photons(photons: &[Photon]) -> Result<Self, BuildError> {
        let (compact, scale, below_range) = encode_all(photons)?;
        Ok(Self::build_compact(compact, scale, below_range))
    }

    /// Builds from photons already encoded (and position-checked) relative to `scale`.
    fn build_compact(mut photons: Vec<CompactPhoton>, scale: PowerScale, below_range: u64) -> Self {
        let n = photons.len();
        let depth = depth_for(n);
        let inner = 1usize << depth;
        let mut splits = vec![0.0; inner];
        let mut axes = vec![0u8; inner];
        for (node, split, axis) in build_node(&mut photons, 1, depth) {
            splits[node] = split;
            axes[node] = axis;
        }
        let mut tree = PhotonTree {
            xs: Vec::with_capacity(n),
            ys: Vec::with_capacity(n),
            zs: Vec::with_capacity(n),
            payload: Vec::with_capacity(n),
            splits,
            axes,
            depth,
            bounds: [[f32::INFINITY; 3], [f32::NEG_INFINITY; 3]],
            scale,
            below_range,
        };
        for p in &photons {
            let [x, y, z] = p.position_array();
            for (axis, c) in [x, y, z].into_iter().enumerate() {
                tree.bounds[0][axis] = tree.bounds[0][axis].min(c);
                tree.bounds[1][axis] = tree.bounds[1][axis].max(c);
            }
            tree.xs.push(x);
            tree.ys.push(y);
            tree.zs.push(z);
            tree.payload.push(p.bits());
        }
        tree
    }

    /// Bytes this tree holds on the heap: 20 per photon (position and packed payload) plus
    /// 5 per inner node (split value and axis), one inner node per leaf of up to
    /// [`LEAF_CAPACITY`] photons: under 20.3 bytes per photon in all.
    pub fn heap_bytes(&self) -> usize {
        (self.xs.capacity() + self.ys.capacity() + self.zs.capacity() + self.splits.capacity())
            * size_of::<f32>()
            + self.payload.capacity() * size_of::<u64>()
            + self.axes.capacity()
    }

    /// Number of photons.
    pub fn len(&self) -> usize {
        self.xs.len()
    }
    /// True when empty.
    pub fn is_empty(&self) -> bool {
        self.xs.is_empty()
    }
    /// Photon `index` (tree order), encoded: its power is relative to
    /// [`PhotonTree::power_scale`]. Panics when `index >= len()`, like slice indexing.
    #[inline]
    pub fn get(&self, index: u32) -> CompactPhoton {
        let i = index as usize;
        CompactPhoton::from_parts([self.xs[i], self.ys[i], self.zs[i]], self.payload[i])
    }
    /// Power of photon `index` (tree order) in watts per channel.
    #[inline]
    pub fn power(&self, index: u32) -> Vec3 {
        self.get(index).power(self.scale)
    }
    /// Photon `index` (tree order) decoded, power in watts.
    pub fn photon(&self, index: u32) -> Photon {
        self.get(index).decode(self.scale)
    }
    /// The scale the photons' power codes are relative to: the largest power channel of the
    /// photons the tree was built from (1 W for a tree without positive power).
    #[inline]
    pub fn power_scale(&self) -> PowerScale {
        self.scale
    }
    /// How many finite positive power channels of the photons lay more than about 2⁻⁴¹ below
    /// [`PhotonTree::power_scale`] and are stored as zero. Zero unless one map holds photons
    /// whose powers differ by more than 10¹².
    pub fn channels_below_range(&self) -> u64 {
        self.below_range
    }
    /// Position of photon `index` (tree order), without decoding the rest.
    pub fn position(&self, index: u32) -> Vec3 {
        let i = index as usize;
        Vec3::new(self.xs[i], self.ys[i], self.zs[i])
    }
    /// The photons in tree order.
    pub fn iter(&self) -> impl ExactSizeIterator<Item = CompactPhoton> + '_ {
        (0..self.len() as u32).map(|i| self.get(i))
    }
    /// Bytes of heap memory held (positions, payloads and split nodes).
    pub fn memory_bytes(&self) -> usize {
        (self.xs.capacity() + self.ys.capacity() + self.zs.capacity()) * 4
            + self.payload.capacity() * 8
            + self.splits.capacity() * 4
            + self.axes.capacity()
    }

    /// Checks every invariant: array lengths, finite positions, valid kinds and axes, leaf
    /// sizes, and that each inner node's left range lies at or below its split value and its
    /// right range at or above.
    pub fn validate(&self) -> Result<(), InvariantError> {
        let n = self.len();
        let whole = |what: String| Err(InvariantError { node: 0, what });
        if self.ys.len() != n || self.zs.len() != n || self.payload.len() != n {
            return whole("position and payload arrays differ in length".into());
        }
        let outside = |p: [f32; 3]| (0..3).any(|a| p[a] < self.bounds[0][a] || p[a] > self.bounds[1][a]);
        if (0..n).any(|i| outside([self.xs[i], self.ys[i], self.zs[i]])) {
            return whole("a photon lies outside the recorded bounds".into());
        }
        let inner = 1usize << self.depth;
        if self.splits.len() != inner || self.axes.len() != inner {
            return whole(format!("expected {inner} split slots"));
        }
        if n.div_ceil(inner) > LEAF_CAPACITY || (self.depth > 0 && n.div_ceil(inner / 2) <= LEAF_CAPACITY) {
            return whole(format!("depth {} does not fit {n} photons", self.depth));
        }
        for i in 0..n {
            if !(self.xs[i].is_finite() && self.ys[i].is_finite() && self.zs[i].is_finite()) {
                return whole(format!("photon {i} has a non-finite position"));
            }
            if kind_code_of_bits(self.payload[i]) == 3 {
                return whole(format!("photon {i} has the unused kind code 3"));
            }
        }
        self.validate_node(1, 0, n, 0)
    }

    fn validate_node(&self, node: usize, lo: usize, hi: usize, level: u32) -> Result<(), InvariantError> {
        if level == self.depth {
            return Ok(());
        }
        let axis = self.axes[node] as usize;
        let fail = |what: String| Err(InvariantError { node, what });
        if axis > 2 {
            return fail(format!("axis {axis}"));
        }
        let coords = [&self.xs, &self.ys, &self.zs][axis];
        let split = self.splits[node];
        let mid = lo + (hi - lo) / 2;
        if let Some(i) = (lo..mid).find(|&i| coords[i] > split) {
            return fail(format!("left photon {i} lies above split {split} on axis {axis}"));
        }
        if let Some(i) = (mid..hi).find(|&i| coords[i] < split) {
            return fail(format!(
                "right photon {i} lies below split {split} on axis {axis}"
            ));
        }
        self.validate_node(2 * node, lo, mid, level + 1)?;
        self.validate_node(2 * node + 1, mid, hi, level + 1)
    }
}

/// Levels of inner nodes for `n` photons: the fewest that leave at most [`LEAF_CAPACITY`]
/// photons a leaf.
pub(crate) fn depth_for(n: usize) -> u32 {
    let mut depth = 0;
    while (n >> depth) + usize::from(n & ((1 << depth) - 1) != 0) > LEAF_CAPACITY {
        depth += 1;
    }
    depth
}

/// Checks positions, picks the power scale and encodes: (photons, scale, channels below range).
/// Above [`PARALLEL_MIN`] photons the check and the encoding run on rayon; the first bad
/// photon is the one reported, and every photon encodes on its own, so the result is the
/// same on any number of threads.
fn encode_all(photons: &[Photon]) -> Result<(Vec<CompactPhoton>, PowerScale, u64), BuildError> {
    let bad = if photons.len() >= PARALLEL_MIN {
        photons.par_iter().position_first(|p| !position_in_range(p))
    } else {
        photons.iter().position(|p| !position_in_range(p))
    };
    if let Some(index) = bad {
        let position = photons[index].position.to_array();
        return Err(if position.iter().all(|c| c.is_finite()) {
            BuildError::PositionOutOfRange { index, position }
        } else {
            BuildError::NonFinitePosition { index, position }
        });
    }
    let scale = PowerScale::for_photons(photons);
    let below_range = AtomicU64::new(0);
    let encode = |p: &Photon| {
        let (c, below) = CompactPhoton::encode_counting(p, scale);
        if below > 0 {
            below_range.fetch_add(u64::from(below), Ordering::Relaxed);
        }
        c
    };
    let compact = if photons.len() >= PARALLEL_MIN {
        photons.par_iter().map(encode).collect()
    } else {
        photons.iter().map(encode).collect()
    };
    Ok((compact, scale, below_range.into_inner()))
}

/// Whether a photon's position is finite and within [`MAX_COORDINATE`] on every axis.
fn position_in_range(p: &Photon) -> bool {
    p.position
        .to_array()
        .iter()
        .all(|c| c.is_finite() && c.abs() <= MAX_COORDINATE)
}

/// Builds the subtree of heap node `node` over `photons` with `levels` inner levels below
/// and including it; returns its split decisions.
fn build_node(photons: &mut [CompactPhoton], node: usize, levels: u32) -> Splits {
    let mut out = Vec::new();
    if levels > 0 {
        if photons.len() >= PARALLEL_MIN {
            let (axis, split, mid) = split_node(photons);
            out.push((node, split, axis));
            let (left, right) = photons.split_at_mut(mid);
            let (a, b) = rayon::join(
                || build_node(left, 2 * node, levels - 1),
                || build_node(right, 2 * node + 1, levels - 1),
            );
            out.extend(a);
            out.extend(b);
        } else {
            build_serial(photons, node, levels, &mut out);
        }
    }
    out
}

fn build_serial(photons: &mut [CompactPhoton], node: usize, levels: u32, out: &mut Splits) {
    if levels == 0 {
        return;
    }
    let (axis, split, mid) = split_node(photons);
    out.push((node, split, axis));
    let (left, right) = photons.split_at_mut(mid);
    build_serial(left, 2 * node, levels - 1, out);
    build_serial(right, 2 * node + 1, levels - 1, out);
}

/// Moves the median along the chosen axis to the middle, everything on its left at or below
/// it and everything on its right at or above; returns (axis, split value, middle index).
///
/// The axis is the one of largest extent whose median lies strictly inside the node's range
/// on that axis. A median equal to the range's end (photons on a wall meeting a floor: most
/// share x = 0) puts equal coordinates on both sides, so a query on that wall must search
/// both; one such split near the root made cube queries scan hundreds of leaves.
fn split_node(photons: &mut [CompactPhoton]) -> (u8, f32, usize) {
    let mid = photons.len() / 2;
    if photons.is_empty() {
        return (0, 0.0, 0);
    }
    let mut lo = [f32::INFINITY; 3];
    let mut hi = [f32::NEG_INFINITY; 3];
    for p in photons.iter() {
        let pos = p.position_array();
        for a in 0..3 {
            lo[a] = lo[a].min(pos[a]);
            hi[a] = hi[a].max(pos[a]);
        }
    }
    let mut axes = [0usize, 1, 2];
    axes.sort_by(|&a, &b| (hi[b] - lo[b]).total_cmp(&(hi[a] - lo[a])));
    let select = |photons: &mut [CompactPhoton], axis: usize| {
        photons.select_nth_unstable_by(mid, |a, b| {
            a.position_array()[axis].total_cmp(&b.position_array()[axis])
        });
        photons[mid].position_array()[axis]
    };
    for &axis in &axes {
        if hi[axis] <= lo[axis] {
            break;
        }
        let split = select(photons, axis);
        if lo[axis] < split && split < hi[axis] {
            return (axis as u8, split, mid);
        }
    }
    let axis = axes[0];
    (axis as u8, select(photons, axis), mid)
}
