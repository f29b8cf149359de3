//! A photon tree's arrays laid bare and a tree rebuilt from them, checked: what a cache file
//! writes and reads back, so that a tree loaded is the bits of the tree saved.

use crate::power_code::PowerScale;
use crate::tree::{InvariantError, MAX_COORDINATE, PhotonTree, depth_for};

/// The arrays of a [`PhotonTree`], borrowed ([`PhotonTree::arrays`]). The bounds and the depth
/// are not among them: they follow from the positions and the photon count.
#[derive(Clone, Copy, Debug)]
pub struct TreeArrays<'a> {
    /// x of each photon, in tree order.
    pub xs: &'a [f32],
    /// y of each photon.
    pub ys: &'a [f32],
    /// z of each photon.
    pub zs: &'a [f32],
    /// The packed power, direction and kind of each photon (see [`crate::CompactPhoton`]).
    pub payload: &'a [u64],
    /// Split value of each inner node slot ([`PhotonTree::inner_slots`] of them, slot 0 unused).
    pub splits: &'a [f32],
    /// Split axis of each inner node slot.
    pub axes: &'a [u8],
    /// The power scale's watts ([`PowerScale::watts`]).
    pub scale_watts: f32,
    /// [`PhotonTree::channels_below_range`].
    pub below_range: u64,
}

/// The arrays of a [`PhotonTree`], owned, for [`PhotonTree::from_arrays`].
#[derive(Clone, Debug, Default)]
pub struct OwnedTreeArrays {
    /// x of each photon, in tree order.
    pub xs: Vec<f32>,
    /// y of each photon.
    pub ys: Vec<f32>,
    /// z of each photon.
    pub zs: Vec<f32>,
    /// The packed payload of each photon.
    pub payload: Vec<u64>,
    /// Split value of each inner node slot.
    pub splits: Vec<f32>,
    /// Split axis of each inner node slot.
    pub axes: Vec<u8>,
    /// The power scale's watts.
    pub scale_watts: f32,
    /// Channels stored as zero.
    pub below_range: u64,
}

impl PhotonTree {
    /// The number of inner node slots (split values and axes) of a tree of `len` photons:
    /// `2^depth`, the depth being the fewest levels that leave at most [`crate::LEAF_CAPACITY`]
    /// photons a leaf.
    pub fn inner_slots(len: usize) -> usize {
        1usize << depth_for(len)
    }

    /// The tree's arrays, borrowed: with [`PhotonTree::from_arrays`] they give this tree back,
    /// bit for bit (photon order, splits, power scale).
    pub fn arrays(&self) -> TreeArrays<'_> {
        TreeArrays {
            xs: &self.xs,
            ys: &self.ys,
            zs: &self.zs,
            payload: &self.payload,
            splits: &self.splits,
            axes: &self.axes,
            scale_watts: self.scale.watts(),
            below_range: self.below_range,
        }
    }

    /// The tree of these arrays, checked as [`PhotonTree::validate`] checks a built one, and
    /// more: every split value finite, every axis below 3 (unused slots too), every
    /// coordinate within [`MAX_COORDINATE`], the scale positive and finite. The bounds and
    /// depth are recomputed, not trusted. Arrays from [`PhotonTree::arrays`] give the same
    /// tree back.
    pub fn from_arrays(arrays: OwnedTreeArrays) -> Result<Self, InvariantError> {
        let whole = |what: String| Err(InvariantError { node: 0, what });
        let n = arrays.xs.len();
        if arrays.ys.len() != n || arrays.zs.len() != n || arrays.payload.len() != n {
            return whole("position and payload arrays differ in length".into());
        }
        let inner = Self::inner_slots(n);
        if arrays.splits.len() != inner || arrays.axes.len() != inner {
            return whole(format!("expected {inner} split slots for {n} photons"));
        }
        if let Some(i) = arrays.splits.iter().position(|s| !s.is_finite()) {
            return whole(format!("split slot {i} is not finite"));
        }
        if let Some(i) = arrays.axes.iter().position(|&a| a > 2) {
            return whole(format!("split slot {i} has axis {}", arrays.axes[i]));
        }
        if !(arrays.scale_watts > 0.0 && arrays.scale_watts.is_finite()) {
            return whole(format!("power scale {} W", arrays.scale_watts));
        }
        let mut bounds = [[f32::INFINITY; 3], [f32::NEG_INFINITY; 3]];
        for i in 0..n {
            let p = [arrays.xs[i], arrays.ys[i], arrays.zs[i]];
            if !p.iter().all(|c| c.is_finite() && c.abs() <= MAX_COORDINATE) {
                return whole(format!(
                    "photon {i} at {p:?}: not finite or beyond {MAX_COORDINATE}"
                ));
            }
            for axis in 0..3 {
                bounds[0][axis] = bounds[0][axis].min(p[axis]);
                bounds[1][axis] = bounds[1][axis].max(p[axis]);
            }
        }
        let tree = PhotonTree {
            xs: arrays.xs,
            ys: arrays.ys,
            zs: arrays.zs,
            payload: arrays.payload,
            splits: arrays.splits,
            axes: arrays.axes,
            depth: depth_for(n),
            bounds,
            scale: PowerScale::new(arrays.scale_watts),
            below_range: arrays.below_range,
        };
        tree.validate()?;
        Ok(tree)
    }
}
