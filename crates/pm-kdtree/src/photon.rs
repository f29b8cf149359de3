//! Photons: the decoded form used while tracing, and the 20-byte compact form stored in trees.
//!
//! The 8 bytes after the position hold, from the lowest bit of a little-endian `u64`:
//! red, green, blue power as 12-bit logarithmic codes (bits 0–35), the travel direction as
//! a 2 × 12-bit octahedral code (bits 36–59), the kind (bits 60–61) and 2 spare bits. The
//! direction code is the best of the four grid points around the exact projection, chosen by
//! squared distance (an f32 dot product near 1 cannot rank directions 0.02° apart); the
//! worst error measured over 300,000 random directions is 0.040°.
//!
//! Power is stored per channel on a log scale rather than with a shared exponent (as Ward's
//! RGBE and Jensen's 4-byte power do): a shared exponent gives the largest channel 0.4 %
//! precision but a channel 10× smaller only 4 %, and photon powers after a few coloured
//! bounces routinely differ by 10–100× between channels. The codes are relative to a
//! [`PowerScale`] that the photon map keeps (its brightest channel), not absolute: code 4095
//! is the scale and each code below it is 2^(1/100) smaller, down to about 2⁻⁴¹ (5·10⁻¹³)
//! times the scale; code 0 is zero. So every channel stays within one step (0.7 %) at any
//! absolute power in f32's normal range, whether a scene emits 10⁻⁶ W or 10¹² W and whether it
//! is traced with a thousand photons or a billion, and photons of one map may differ by up to
//! 2⁴⁰ (10¹²).
//!
//! The rounding is *stochastic* and unbiased: a channel between two codes takes the upper one
//! with the probability that makes the decoded power's expectation the exact power (linear
//! interpolation between the two decoded values). Rounding to the nearest code would put the
//! same error, up to ±0.35 %, on every photon of a light of one colour, and sums of photons
//! would keep that bias however many photons are traced. The uniform number comes from a hash
//! of the photon itself (position, direction, kind and channel), so encoding stays
//! deterministic: the same photon always gets the same code, whatever order or thread encodes
//! it.
//! Decoding is a lookup in a 4096-entry table computed at compile time and one multiply by the
//! scale (which an estimator does once per query, after summing): no `exp` in the hot loop.

pub use crate::power_code::PowerScale;
use crate::power_code::{
    POWER_BITS, POWER_MAX_CODE, POWER_TABLE, encode_channel, largest_channel, rounding_uniforms,
};
use glam::{Vec2, Vec3};

/// How a photon got where it is stored.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
#[repr(u8)]
pub enum PhotonKind {
    /// First diffuse hit straight from the light.
    Direct = 0,
    /// After at least one diffuse bounce.
    Indirect = 1,
    /// After only specular bounces since the light.
    Caustic = 2,
}

/// A set of photon kinds accepted by a query.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub struct KindMask(pub u8);

impl KindMask {
    /// Every photon.
    pub const ALL: KindMask = KindMask(0b111);
    /// Every photon but direct ones (for shadow-ray rendering).
    pub const NOT_DIRECT: KindMask = KindMask(0b110);
    /// Only `kind`.
    pub const fn only(kind: PhotonKind) -> KindMask {
        KindMask(1 << kind as u8)
    }
    /// True when `kind` is accepted.
    pub const fn accepts(self, kind: PhotonKind) -> bool {
        self.0 & (1 << kind as u8) != 0
    }
    /// True when every kind is accepted (queries then skip the filter).
    pub const fn accepts_all(self) -> bool {
        self.0 & 0b111 == 0b111
    }
}

/// A photon in full precision.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Photon {
    /// Where it landed (metres).
    pub position: Vec3,
    /// Power per RGB channel (watts).
    pub power: Vec3,
    /// Unit direction of travel (towards the surface).
    pub direction: Vec3,
    /// How it got here.
    pub kind: PhotonKind,
}

/// A photon in 20 bytes: position as 3×f32 and 8 bytes of encoded power, direction and kind.
///
/// See the [module docs](self) for the layout and precision: power within one step of
/// 2^(1/100) (0.7 %) per channel, unbiased (stochastic rounding), relative to a [`PowerScale`] (from the scale down to about 2⁻⁴¹ times it), direction
/// within 0.05°. The scale is not stored in the photon: a [`crate::PhotonTree`] keeps one for
/// all its photons.
#[derive(Clone, Copy, Debug, PartialEq)]
#[repr(C)]
pub struct CompactPhoton {
    position: [f32; 3],
    packed: [u32; 2],
}

const DIRECTION_BITS: u32 = 12;
/// Even, so the middle code decodes to exactly 0 and the six axis directions are exact.
const DIRECTION_MAX_CODE: u32 = (1 << DIRECTION_BITS) - 2;
const DIRECTION_SHIFT: u32 = 3 * POWER_BITS;
const KIND_SHIFT: u32 = DIRECTION_SHIFT + 2 * DIRECTION_BITS;

fn decode_direction(u: u32, v: u32) -> Vec3 {
    decode_direction_l1(u, v).normalize()
}

/// The octahedral decode before normalising: unit L1 norm.
#[inline]
fn decode_direction_l1(u: u32, v: u32) -> Vec3 {
    // (2u − M) / M is exact at u = M/2 and at both ends.
    let m = DIRECTION_MAX_CODE as i32;
    let x = (2 * u as i32 - m) as f32 / m as f32;
    let y = (2 * v as i32 - m) as f32 / m as f32;
    let z = 1.0 - x.abs() - y.abs();
    let (x, y) = if z < 0.0 {
        ((1.0 - y.abs()).copysign(x), (1.0 - x.abs()).copysign(y))
    } else {
        (x, y)
    };
    Vec3::new(x, y, z)
}

/// Octahedral code of a direction; of the four grid points around the exact projection it
/// keeps the one that decodes nearest (Cigolle et al. 2014, "precise" variant).
fn encode_direction(direction: Vec3) -> (u32, u32) {
    // Scale to a largest component of 1 first, so that neither a tiny direction (whose squared
    // length underflows) nor a huge one (whose L1 norm overflows) loses its direction.
    let largest = direction.abs().max_element();
    if !(largest > 0.0 && largest.is_finite()) {
        return encode_direction(Vec3::Z);
    }
    let direction = direction / largest;
    let l1 = direction.x.abs() + direction.y.abs() + direction.z.abs();
    if !(l1 > 0.0 && l1.is_finite()) {
        return encode_direction(Vec3::Z);
    }
    let n = direction / l1;
    let mut p = Vec2::new(n.x, n.y);
    if n.z < 0.0 {
        p = Vec2::new((1.0 - n.y.abs()).copysign(n.x), (1.0 - n.x.abs()).copysign(n.y));
    }
    let grid = (p + 1.0) * (0.5 * DIRECTION_MAX_CODE as f32);
    let unit = direction.normalize();
    let mut best = (0, 0);
    // Compared by squared distance, not by dot product: near 1 an f32 dot product cannot
    // tell apart directions 0.02° apart.
    let mut best_error = f32::INFINITY;
    for du in 0..2 {
        for dv in 0..2 {
            let u = (grid.x.floor() + du as f32).clamp(0.0, DIRECTION_MAX_CODE as f32) as u32;
            let v = (grid.y.floor() + dv as f32).clamp(0.0, DIRECTION_MAX_CODE as f32) as u32;
            let error = (decode_direction(u, v) - unit).length_squared();
            if error < best_error {
                best_error = error;
                best = (u, v);
            }
        }
    }
    best
}

impl CompactPhoton {
    /// Encodes a photon with its power relative to `scale` (the map's; see [`PowerScale`]).
    /// Zero, negative or NaN power channels become zero, and so do positive channels below
    /// the smallest code ([`PowerScale::channels_below`] counts them); channels above the
    /// scale are clamped to it. The direction is normalised (a zero or non-finite direction
    /// becomes +z). The position is kept as is: [`crate::PhotonTree::build`] rejects
    /// non-finite ones.
    pub fn encode(photon: &Photon, scale: PowerScale) -> Self {
        Self::encode_counting(photon, scale).0
    }

    /// [`CompactPhoton::encode`], and how many channels fell below the smallest code.
    pub(crate) fn encode_counting(photon: &Photon, scale: PowerScale) -> (Self, u32) {
        let power = photon.power;
        let (u, v) = encode_direction(photon.direction);
        let direction_and_kind = (u as u64) << DIRECTION_SHIFT
            | (v as u64) << (DIRECTION_SHIFT + DIRECTION_BITS)
            | (photon.kind as u64) << KIND_SHIFT;
        let [ur, ug, ub] = rounding_uniforms(photon.position.to_array(), direction_and_kind);
        let (r, r_low) = encode_channel(power.x, scale, ur);
        let (g, g_low) = encode_channel(power.y, scale, ug);
        let (b, b_low) = encode_channel(power.z, scale, ub);
        let bits = r | g << POWER_BITS | b << (2 * POWER_BITS) | direction_and_kind;
        let low = u32::from(r_low) + u32::from(g_low) + u32::from(b_low);
        (Self::from_parts(photon.position.to_array(), bits), low)
    }

    pub(crate) fn from_parts(position: [f32; 3], bits: u64) -> Self {
        Self {
            position,
            packed: [bits as u32, (bits >> 32) as u32],
        }
    }

    pub(crate) fn bits(&self) -> u64 {
        self.packed[0] as u64 | (self.packed[1] as u64) << 32
    }

    pub(crate) fn position_array(&self) -> [f32; 3] {
        self.position
    }

    /// Decodes it, with its power relative to `scale` (the scale it was encoded with).
    pub fn decode(&self, scale: PowerScale) -> Photon {
        Photon {
            position: self.position(),
            power: self.power(scale),
            direction: self.direction(),
            kind: self.kind(),
        }
    }
    /// Position.
    pub fn position(&self) -> Vec3 {
        Vec3::from(self.position)
    }
    /// Decoded power (watts per channel), given the `scale` it was encoded with.
    #[inline]
    pub fn power(&self, scale: PowerScale) -> Vec3 {
        self.relative_power() * scale.watts()
    }
    /// Decoded power per channel relative to the scale it was encoded with (1 is the scale):
    /// three table lookups. Estimators sum these and multiply by [`PowerScale::watts`] once.
    #[inline]
    pub fn relative_power(&self) -> Vec3 {
        let bits = self.bits();
        let mask = POWER_MAX_CODE as u64;
        Vec3::new(
            POWER_TABLE[(bits & mask) as usize],
            POWER_TABLE[(bits >> POWER_BITS & mask) as usize],
            POWER_TABLE[(bits >> (2 * POWER_BITS) & mask) as usize],
        )
    }
    /// Decoded unit direction of travel.
    pub fn direction(&self) -> Vec3 {
        self.direction_l1().normalize()
    }
    /// The direction of travel scaled to unit L1 norm (`|x| + |y| + |z| = 1`): the decode
    /// without its final normalisation (a square root and a division), for uses that need the
    /// direction but not its length, such as signs of dot products or ratios of them.
    /// [`CompactPhoton::direction`] is this, normalised.
    #[inline]
    pub fn direction_l1(&self) -> Vec3 {
        let bits = self.bits();
        let mask = (1u64 << DIRECTION_BITS) - 1;
        decode_direction_l1(
            (bits >> DIRECTION_SHIFT & mask) as u32,
            (bits >> (DIRECTION_SHIFT + DIRECTION_BITS) & mask) as u32,
        )
    }
    /// Kind.
    pub fn kind(&self) -> PhotonKind {
        kind_of_bits(self.bits())
    }
}

/// The kind stored in packed bits (code 3 is never written; it reads as indirect).
#[inline]
pub(crate) fn kind_of_bits(bits: u64) -> PhotonKind {
    match bits >> KIND_SHIFT & 0b11 {
        0 => PhotonKind::Direct,
        2 => PhotonKind::Caustic,
        _ => PhotonKind::Indirect,
    }
}

/// The raw 2-bit kind code of packed bits (3 is never written).
#[inline]
pub(crate) fn kind_code_of_bits(bits: u64) -> u8 {
    (bits >> KIND_SHIFT & 0b11) as u8
}

/// The kind-mask bit of packed bits, for filtering without decoding.
#[inline]
pub(crate) fn kind_bit_of_bits(bits: u64) -> u8 {
    1 << (bits >> KIND_SHIFT & 0b11)
}

impl PowerScale {
    /// The scale for a set of photons: their largest finite positive power channel (1 W when
    /// there is none). (Here rather than with the codes: the codes know no photon.)
    pub fn for_photons(photons: &[Photon]) -> Self {
        Self::new(
            photons
                .iter()
                .map(|p| largest_channel(p.power))
                .fold(0.0, f32::max),
        )
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn power_table_is_two_to_the_code_over_a_hundred_below_the_scale() {
        assert_eq!(POWER_TABLE[0], 0.0);
        assert_eq!(POWER_TABLE[POWER_MAX_CODE as usize], 1.0);
        assert_eq!(POWER_TABLE[1], PowerScale::SMALLEST_RELATIVE);
        // Closed form at whole octaves: code 4095 − 100·m is exactly 2^−m.
        for m in 0..=40 {
            let code = POWER_MAX_CODE as usize - 100 * m as usize;
            assert_eq!(POWER_TABLE[code], 2f32.powi(-m), "code {code}");
        }
        // And in between, against f64's exp2.
        for (code, &value) in POWER_TABLE.iter().enumerate().skip(1) {
            let want = ((code as f64 - POWER_MAX_CODE as f64) / 100.0).exp2();
            assert!((value as f64 / want - 1.0).abs() < 1e-7, "code {code}");
        }
    }
}
