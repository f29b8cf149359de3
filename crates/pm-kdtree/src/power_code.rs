//! The power codes of a compact photon: a 12-bit logarithmic code per channel, relative to the
//! map's [`PowerScale`], with unbiased (stochastic) rounding driven by a hash of the photon
//! itself, and the compile-time table that decodes them.

use glam::Vec3;

/// Power codes per octave (factor 2): a step of 2^(1/100), so rounding errs by < 0.7 %.
const CODES_PER_OCTAVE: i32 = 100;
pub(crate) const POWER_BITS: u32 = 12;
/// The top code: exactly the map's [`PowerScale`]. Code `c ≥ 1` decodes to
/// `2^((c − POWER_MAX_CODE) / 100)` times the scale; code 0 is zero.
pub(crate) const POWER_MAX_CODE: u32 = (1 << POWER_BITS) - 1;
/// `exp(x)` for small |x| by its Taylor series (compile-time table construction only).
const fn exp_series(x: f64) -> f64 {
    let mut sum = 1.0;
    let mut term = 1.0;
    let mut i = 1;
    while i < 30 {
        term = term * x / i as f64;
        sum += term;
        i += 1;
    }
    sum
}

/// Each 12-bit power code decoded relative to the scale (the top code is 1); code 0 is zero.
const POWER_TABLE_VALUES: [f32; 1 << POWER_BITS] = {
    let mut table = [0.0f32; 1 << POWER_BITS];
    let mut code = 1;
    while code < table.len() {
        let e = code as i32 - POWER_MAX_CODE as i32;
        let octave = e.div_euclid(CODES_PER_OCTAVE);
        let frac = e.rem_euclid(CODES_PER_OCTAVE);
        let whole = f64::from_bits(((1023 + octave) as u64) << 52);
        let part = exp_series(frac as f64 / CODES_PER_OCTAVE as f64 * core::f64::consts::LN_2);
        table[code] = (whole * part) as f32;
        code += 1;
    }
    table
};
pub(crate) static POWER_TABLE: [f32; 1 << POWER_BITS] = POWER_TABLE_VALUES;

/// The power of a photon map's top code: every photon power of the map is stored relative to
/// it, so the codes keep their precision at any absolute power.
///
/// A channel is stored as one of 4095 logarithmic steps of 2^(1/100) below the scale (within
/// one step, 0.7 %, rounded stochastically so that the decoded power is unbiased), from the scale itself down to [`PowerScale::SMALLEST_RELATIVE`] (about 2⁻⁴¹)
/// times it, or as zero. [`PowerScale::for_photons`] picks the largest channel of the map's
/// photons, so nothing is clamped and every channel within 2⁻⁴⁰ of the map's brightest keeps
/// its precision; [`PhotonTree::build`](crate::PhotonTree::build) counts the positive channels
/// further below, which are stored as zero
/// ([`PhotonTree::channels_below_range`](crate::PhotonTree::channels_below_range)).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct PowerScale {
    watts: f32,
    log2: f32,
}

impl Default for PowerScale {
    /// A scale of 1 W.
    fn default() -> Self {
        PowerScale::new(1.0)
    }
}

impl PowerScale {
    /// The smallest nonzero power stored, relative to the scale: 2^(−4094/100) ≈ 5.1·10⁻¹³.
    pub const SMALLEST_RELATIVE: f32 = POWER_TABLE_VALUES[1];

    /// A scale whose top code is `watts`. A zero, negative or non-finite `watts` gives 1 W
    /// (there is no positive finite power to scale to).
    pub fn new(watts: f32) -> Self {
        let watts = if watts > 0.0 && watts.is_finite() {
            watts
        } else {
            1.0
        };
        PowerScale {
            watts,
            log2: watts.log2(),
        }
    }

    /// Watts of the top code (relative power 1).
    #[inline]
    pub fn watts(self) -> f32 {
        self.watts
    }

    /// The smallest nonzero power stored (watts).
    pub fn smallest(self) -> f32 {
        Self::SMALLEST_RELATIVE * self.watts
    }

    /// How many channels of `power` are finite and positive but below the smallest code, so
    /// that [`crate::CompactPhoton::encode`] stores them as zero.
    pub fn channels_below(self, power: Vec3) -> u32 {
        power
            .to_array()
            .into_iter()
            .filter(|&w| below_smallest_code(w, self))
            .count() as u32
    }
}

/// The largest finite positive channel of `power`, or 0.
pub(crate) fn largest_channel(power: Vec3) -> f32 {
    power
        .to_array()
        .into_iter()
        .filter(|w| w.is_finite())
        .fold(0.0, f32::max)
}

/// The code of one channel relative to `scale`, and whether a finite positive channel fell
/// below the smallest code (and is stored as zero). Above the scale (or +∞) clamps to the top.
///
/// Between two codes it takes the upper one with probability `(v − lo) / (hi − lo)` for a
/// uniform `u` in [0, 1) (`u < p` rounds up), so that the decoded value's expectation over `u`
/// is exactly the channel's relative power `v`. Exactly representable channels keep their code.
#[inline]
pub(crate) fn encode_channel(watts: f32, scale: PowerScale, u: f64) -> (u64, bool) {
    if watts.is_nan() || watts <= 0.0 {
        return (0, false);
    }
    // Logarithms, not the ratio: watts / scale could underflow or overflow in f32.
    let code = ((watts.log2() - scale.log2) * CODES_PER_OCTAVE as f32).floor() + POWER_MAX_CODE as f32;
    if code >= POWER_MAX_CODE as f32 {
        return (POWER_MAX_CODE as u64, false);
    }
    if code < 0.0 {
        return (0, watts.is_finite());
    }
    // In f64 the ratio of two f32 powers neither underflows nor overflows.
    let relative = watts as f64 / scale.watts as f64;
    // The f32 logarithm may be one code off at a boundary: step until lo ≤ v < hi.
    let mut lo = code as usize;
    while lo > 0 && (POWER_TABLE[lo] as f64) > relative {
        lo -= 1;
    }
    while lo < POWER_MAX_CODE as usize && (POWER_TABLE[lo + 1] as f64) <= relative {
        lo += 1;
    }
    if lo == POWER_MAX_CODE as usize {
        return (lo as u64, false);
    }
    if lo == 0 {
        // Below the smallest code: stored as zero, and counted.
        return (0, true);
    }
    let (low, high) = (POWER_TABLE[lo] as f64, POWER_TABLE[lo + 1] as f64);
    let up = u * (high - low) < relative - low;
    (lo as u64 + u64::from(up), false)
}

/// Whether a channel is finite, positive and below the smallest code (see
/// [`PowerScale::channels_below`]).
fn below_smallest_code(watts: f32, scale: PowerScale) -> bool {
    watts > 0.0 && watts.is_finite() && (watts as f64 / scale.watts as f64) < POWER_TABLE[1] as f64
}

/// The three uniform numbers in [0, 1) that round a photon's power channels: a hash of the
/// photon's position, direction and kind (SplitMix64 finalisers), so the same photon always
/// encodes the same way and different photons round independently.
pub(crate) fn rounding_uniforms(position: [f32; 3], direction_and_kind: u64) -> [f64; 3] {
    fn mix(mut z: u64) -> u64 {
        z = (z ^ (z >> 30)).wrapping_mul(0xbf58_476d_1ce4_e5b9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94d0_49bb_1331_11eb);
        z ^ (z >> 31)
    }
    let mut h = mix(direction_and_kind ^ 0x9e37_79b9_7f4a_7c15);
    for x in position {
        h = mix(h ^ u64::from(x.to_bits()).wrapping_mul(0x9e37_79b9_7f4a_7c15));
    }
    let mut out = [0.0; 3];
    for (c, o) in out.iter_mut().enumerate() {
        h = mix(h.wrapping_add(0x9e37_79b9_7f4a_7c15 ^ c as u64));
        // 53 bits: a uniform in [0, 1) with f64's full resolution.
        *o = (h >> 11) as f64 * (1.0 / (1u64 << 53) as f64);
    }
    out
}
