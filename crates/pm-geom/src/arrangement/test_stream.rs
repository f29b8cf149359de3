//! A fixed stream of numbers in [0, 1) for the arrangement's tests (xorshift64), so that the
//! random cases are the same on every run without a dependency.

/// The stream: each call gives the next number in [0, 1), from 24 bits of the state.
pub(super) fn stream() -> impl FnMut() -> f32 {
    let mut state = 0x2545_f491_4f6c_dd1du64;
    move || {
        state ^= state << 13;
        state ^= state >> 7;
        state ^= state << 17;
        (state >> 40) as f32 / (1u64 << 24) as f32
    }
}
