//! The 64-bit hash of a cache file: its payload's checksum and the scene's fingerprint, one
//! word at a time, every step a bijection so that any change to one word always shows.

/// Odd multiplier of each step (FxHash's); multiplying by an odd number is a bijection.
const K: u64 = 0x517c_c1b7_2722_0a95;

/// A running 64-bit hash of words and bytes.
///
/// Each 8-byte word `w` does `h = (rotl(h, 23) ^ w) · K`: for a fixed `h` a bijection of `w`
/// and for a fixed `w` a bijection of `h`, so two inputs that differ in one word (any bit
/// flips within 8 aligned bytes) always hash apart. The length is hashed at the end and the
/// result passes SplitMix64's finaliser. Not a cryptographic hash: it finds corruption, it
/// does not resist forgery.
#[derive(Clone, Debug)]
pub struct Hash64 {
    state: u64,
    tail: [u8; 8],
    tail_len: usize,
    len: u64,
}

impl Default for Hash64 {
    fn default() -> Self {
        Hash64 {
            state: 0x243f_6a88_85a3_08d3,
            tail: [0; 8],
            tail_len: 0,
            len: 0,
        }
    }
}

impl Hash64 {
    /// A new hash.
    pub fn new() -> Self {
        Self::default()
    }

    fn step(&mut self, word: u64) {
        self.state = (self.state.rotate_left(23) ^ word).wrapping_mul(K);
    }

    /// Hashes `bytes`, as if appended to everything hashed before.
    pub fn write(&mut self, mut bytes: &[u8]) {
        self.len += bytes.len() as u64;
        if self.tail_len > 0 {
            let take = (8 - self.tail_len).min(bytes.len());
            self.tail[self.tail_len..self.tail_len + take].copy_from_slice(&bytes[..take]);
            self.tail_len += take;
            bytes = &bytes[take..];
            if self.tail_len < 8 {
                return;
            }
            self.step(u64::from_le_bytes(self.tail));
            self.tail_len = 0;
        }
        let mut words = bytes.chunks_exact(8);
        for word in &mut words {
            let mut w = [0u8; 8];
            w.copy_from_slice(word);
            self.step(u64::from_le_bytes(w));
        }
        let rest = words.remainder();
        self.tail[..rest.len()].copy_from_slice(rest);
        self.tail_len = rest.len();
    }

    /// Hashes a `u64` (little-endian bytes).
    pub fn write_u64(&mut self, x: u64) {
        self.write(&x.to_le_bytes());
    }

    /// Hashes a text with its length (so that texts one after the other cannot run together).
    pub fn write_text(&mut self, text: &str) {
        self.write_u64(text.len() as u64);
        self.write(text.as_bytes());
    }

    /// The hash of everything written.
    pub fn finish(&self) -> u64 {
        let mut copy = self.clone();
        if copy.tail_len > 0 {
            copy.tail[copy.tail_len..].fill(0);
            copy.step(u64::from_le_bytes(copy.tail));
        }
        copy.step(self.len);
        let mut z = copy.state;
        z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
        z ^ (z >> 31)
    }
}

/// The checksum a cache file stores of its payload ([`Hash64`] of the bytes).
pub fn payload_checksum(payload: &[u8]) -> u64 {
    let mut hash = Hash64::new();
    hash.write(payload);
    hash.finish()
}
