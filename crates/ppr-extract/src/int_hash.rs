//! A fast, deterministic hasher for the integer keys of spatial hash grids (FxHash's
//! multiply-rotate per word, finished with MurmurHash3's 64-bit mix so that the low bits
//! the table indexes with depend on every input bit; not for untrusted keys).

use std::collections::HashMap;
use std::hash::{BuildHasherDefault, Hasher};

/// Multiply-rotate hasher over 64-bit words.
#[derive(Default, Clone, Copy)]
pub struct IntHasher(u64);

const SEED: u64 = 0x51_7c_c1_b7_27_22_0a_95;

impl Hasher for IntHasher {
    fn finish(&self) -> u64 {
        let mut h = self.0;
        h ^= h >> 33;
        h = h.wrapping_mul(0xff51_afd7_ed55_8ccd);
        h ^= h >> 33;
        h = h.wrapping_mul(0xc4ce_b9fe_1a85_ec53);
        h ^ (h >> 33)
    }
    fn write(&mut self, bytes: &[u8]) {
        for &b in bytes {
            self.write_u64(u64::from(b));
        }
    }
    fn write_u64(&mut self, i: u64) {
        self.0 = (self.0.rotate_left(5) ^ i).wrapping_mul(SEED);
    }
    fn write_i64(&mut self, i: i64) {
        self.write_u64(i as u64);
    }
    fn write_u32(&mut self, i: u32) {
        self.write_u64(u64::from(i));
    }
    fn write_usize(&mut self, i: usize) {
        self.write_u64(i as u64);
    }
}

/// Integer cell of `x` on a grid of `cell` size (saturating far outside the grid).
pub fn cell_of(x: f64, cell: f64) -> i64 {
    (x / cell).floor() as i64
}

/// A hasher for grid cells `(i64, i64, i64)` that keeps space local: the low 57 bits of the
/// hash are the Morton code of the cell's low 19 bits per axis (the table index, so cells
/// near each other share cache lines), the top 7 bits a mix of every bit (the tag the
/// table compares first). Other keys hash like [`IntHasher`] with the same layout.
#[derive(Default, Clone, Copy)]
pub struct CellHasher {
    words: [u64; 3],
    count: usize,
    mixed: IntHasher,
}

impl Hasher for CellHasher {
    fn finish(&self) -> u64 {
        const LOW: u64 = (1 << 57) - 1;
        let [x, y, z] = self.words;
        (morton19(x) | morton19(y) << 1 | morton19(z) << 2) & LOW | self.mixed.finish() & !LOW
    }
    fn write(&mut self, bytes: &[u8]) {
        for &b in bytes {
            self.write_u64(u64::from(b));
        }
    }
    fn write_u64(&mut self, i: u64) {
        if self.count < 3 {
            self.words[self.count] = i;
        }
        self.count += 1;
        self.mixed.write_u64(i);
    }
    fn write_i64(&mut self, i: i64) {
        self.write_u64(i as u64);
    }
    fn write_usize(&mut self, i: usize) {
        self.write_u64(i as u64);
    }
}

/// Spreads the low 19 bits of `v` to every third bit.
fn morton19(v: u64) -> u64 {
    let mut v = v & 0x7_ffff;
    v = (v | v << 32) & 0x1f_0000_0000_ffff;
    v = (v | v << 16) & 0x1f_0000_ff00_00ff;
    v = (v | v << 8) & 0x100f_00f0_0f00_f00f;
    v = (v | v << 4) & 0x10c3_0c30_c30c_30c3;
    (v | v << 2) & 0x1249_2492_4924_9249
}

/// A map from grid cells, hashed with [`CellHasher`].
pub type CellMap<V> = HashMap<(i64, i64, i64), V, BuildHasherDefault<CellHasher>>;

#[cfg(test)]
mod tests {
    use super::*;
    use std::hash::BuildHasher;

    #[test]
    fn neighbouring_cells_get_neighbouring_indices_and_mixed_tags() {
        let build = BuildHasherDefault::<CellHasher>::default();
        let h = |c: (i64, i64, i64)| build.hash_one(c);
        assert_eq!(h((1, 0, 0)) & 0xff, 1);
        assert_eq!(h((0, 1, 0)) & 0xff, 2);
        assert_eq!(h((0, 0, 1)) & 0xff, 4);
        assert_ne!(h((1, 0, 0)) >> 57, h((0, 1, 0)) >> 57);
        assert_ne!(h((-1, 0, 0)), h((1 << 19, 0, 0)), "aliased cells differ in their tags");
    }
}
