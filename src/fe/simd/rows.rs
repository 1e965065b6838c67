//! Padded nodal rows [x, y, z, 0] stored 32-byte aligned, so that each row is exactly one
//! aligned 256-bit vector.
//!
//! The one-thread element loop adds every node's internal force into its row with one
//! 256-bit load, add and store (`Lanes::add_node_rows`). A `Vec<[f64; 4]>` is only 8-byte
//! aligned, so every row would straddle a 32-byte boundary and every second one a cache
//! line (docs/performance.md has the measured cost).

use std::ops::{Deref, DerefMut};

/// One padded row, 32-byte aligned.
#[derive(Debug, Clone, Copy, Default, PartialEq)]
#[repr(C, align(32))]
struct Row([f64; 4]);

/// Nodal rows [x, y, z, 0] (the unit is the caller's: N for forces), 32-byte aligned; reads
/// and writes as a slice of `[f64; 4]`.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct Rows4(Vec<Row>);

impl Rows4 {
    /// `n` rows of zeros.
    pub fn zeros(n: usize) -> Self {
        Rows4(vec![Row::default(); n])
    }
}

impl Deref for Rows4 {
    type Target = [[f64; 4]];
    fn deref(&self) -> &[[f64; 4]] {
        // SAFETY: Row is repr(C) around [f64; 4] with no padding (size 32 = 4 x 8), so the
        // vector's buffer is `len` consecutive [f64; 4]; alignment 32 ≥ 8.
        unsafe { std::slice::from_raw_parts(self.0.as_ptr().cast(), self.0.len()) }
    }
}

impl DerefMut for Rows4 {
    fn deref_mut(&mut self) -> &mut [[f64; 4]] {
        // SAFETY: as in `deref`, with the unique borrow of the vector.
        unsafe { std::slice::from_raw_parts_mut(self.0.as_mut_ptr().cast(), self.0.len()) }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn rows_are_aligned_and_read_back() {
        let mut r = Rows4::zeros(5);
        r[3] = [1.0, 2.0, 3.0, 0.0];
        assert_eq!(r.as_ptr() as usize % 32, 0);
        assert_eq!(r.len(), 5);
        assert_eq!(r[3], [1.0, 2.0, 3.0, 0.0]);
        assert_eq!(r.iter().flatten().sum::<f64>(), 6.0);
    }
}
