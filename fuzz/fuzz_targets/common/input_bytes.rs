//! The fuzzer's input read as a stream of choices, shared by the targets that build structured
//! inputs from bytes (`bake_differential`, `water_query`). Each target uses the part it needs.
#![allow(dead_code)]

/// The input, read a byte at a time; zeros once it runs out, so every input, however short,
/// makes a whole set of choices.
pub struct Bytes<'a>(pub &'a [u8]);

impl Bytes<'_> {
    /// The next byte.
    pub fn byte(&mut self) -> u8 {
        match self.0.split_first() {
            Some((b, rest)) => {
                self.0 = rest;
                *b
            }
            None => 0,
        }
    }

    /// The next eight bytes, big-endian.
    pub fn u64(&mut self) -> u64 {
        (0..8).fold(0, |v, _| v << 8 | u64::from(self.byte()))
    }

    /// One of `items`.
    pub fn pick<T: Copy>(&mut self, items: &[T]) -> T {
        items[usize::from(self.byte()) % items.len()]
    }

    /// A number in [lo, hi].
    pub fn range(&mut self, lo: u32, hi: u32) -> u32 {
        lo + u32::from(self.byte()) % (hi - lo + 1)
    }
}
