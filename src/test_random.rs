//! A fixed pseudo-random sequence for unit tests (xorshift64): the same values on every run
//! and machine, so a failing case can be read again.

pub(crate) struct Sequence(u64);

impl Sequence {
    /// The sequence from `seed` (not 0).
    pub(crate) fn new(seed: u64) -> Self {
        Sequence(seed)
    }

    pub(crate) fn next_u64(&mut self) -> u64 {
        self.0 ^= self.0 << 13;
        self.0 ^= self.0 >> 7;
        self.0 ^= self.0 << 17;
        self.0
    }

    /// A number in [0, n).
    pub(crate) fn below(&mut self, n: usize) -> usize {
        (self.next_u64() % n as u64) as usize
    }

    /// A single-precision number in [0, 1), of 24 random bits.
    pub(crate) fn unit(&mut self) -> f32 {
        (self.next_u64() >> 40) as f32 / (1u32 << 24) as f32
    }
}
