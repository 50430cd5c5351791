//! Spatial hash grids' keys and tables: a fast, deterministic hasher for integer keys
//! (FxHash's multiply-rotate per word, finished with MurmurHash3's 64-bit mix so that the
//! low bits the table indexes with depend on every input bit; not for untrusted keys), and
//! [`CellTable`], a flat open-addressing table of packed cell keys for the hot grids.

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

/// Integer cell of `x` on a grid of `cell` size (saturating far outside the grid): the
/// floor of `x / cell` without a call to libm's `floor` (the baseline x86-64 target has no
/// rounding instruction), equal to `(x / cell).floor() as i64` for every input.
pub fn cell_of(x: f64, cell: f64) -> i64 {
    let q = x / cell;
    let t = q as i64;
    if (t as f64) > q { t.saturating_sub(1) } else { t }
}

/// Bits per axis of a [`packed_cell`] key.
const PACK_BITS: u32 = 21;

/// A grid cell packed into 63 bits, 21 per axis, wrapping: cells `2^21` apart along an axis
/// share a key. Users filter what they find by position (distance or box tests), so a
/// shared key merges two lists without changing any answer, as long as one query never
/// spans `2^21` cells.
pub fn packed_cell((x, y, z): (i64, i64, i64)) -> u64 {
    const MASK: u64 = (1 << PACK_BITS) - 1;
    (x as u64 & MASK) | (y as u64 & MASK) << PACK_BITS | (z as u64 & MASK) << (2 * PACK_BITS)
}

/// A flat open-addressing map from [`packed_cell`] keys to `u32` values (linear probing,
/// Fibonacci hashing, load at most one half): one flat array of key-value slots, no
/// allocation per entry, one probe per look-up in most cases; [`CellTable::prefetch`] lets
/// a caller that knows its next keys hide the memory latency of large tables.
pub struct CellTable {
    slots: Vec<(u64, u32)>,
    len: usize,
    /// `64 - log2(slots)`.
    shift: u32,
}

/// A key no packed cell has (they use 63 bits).
const EMPTY_KEY: u64 = u64::MAX;

impl CellTable {
    /// A table for about `n` entries before it grows.
    pub fn with_capacity(n: usize) -> Self {
        let slots = (2 * n).max(16).next_power_of_two();
        Self { slots: vec![(EMPTY_KEY, 0); slots], len: 0, shift: 64 - slots.trailing_zeros() }
    }

    fn home(&self, key: u64) -> usize {
        (key.wrapping_mul(0x9e37_79b9_7f4a_7c15) >> self.shift) as usize
    }

    /// The value of `key`, if present.
    pub fn get(&self, key: u64) -> Option<u32> {
        let mask = self.slots.len() - 1;
        let mut i = self.home(key);
        loop {
            let (k, v) = self.slots[i];
            if k == key {
                return Some(v);
            }
            if k == EMPTY_KEY {
                return None;
            }
            i = (i + 1) & mask;
        }
    }

    /// The value of `key`, inserted as `default` when absent.
    pub fn entry_or(&mut self, key: u64, default: u32) -> &mut u32 {
        if 2 * (self.len + 1) > self.slots.len() {
            self.grow();
        }
        let mask = self.slots.len() - 1;
        let mut i = self.home(key);
        loop {
            let k = self.slots[i].0;
            if k == EMPTY_KEY {
                self.slots[i] = (key, default);
                self.len += 1;
            }
            if k == key || k == EMPTY_KEY {
                return &mut self.slots[i].1;
            }
            i = (i + 1) & mask;
        }
    }

    /// Asks the processor to start loading the slot where a look-up of `key` begins (a
    /// hint: no effect on any result).
    pub fn prefetch(&self, key: u64) {
        prefetch(&self.slots[self.home(key)]);
    }

    fn grow(&mut self) {
        let mut bigger = Self::with_capacity(self.slots.len());
        for &(k, v) in &self.slots {
            if k != EMPTY_KEY {
                *bigger.entry_or(k, v) = v;
            }
        }
        *self = bigger;
    }
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

/// Asks the processor to start loading the cache line of `r` (a hint).
pub fn prefetch<T>(r: &T) {
    #[cfg(target_arch = "x86_64")]
    // SAFETY: a prefetch reads nothing a program can observe and never faults; `r` is a valid
    // reference, and SSE is part of every x86-64 target.
    unsafe {
        use std::arch::x86_64::{_MM_HINT_T0, _mm_prefetch};
        _mm_prefetch::<_MM_HINT_T0>((r as *const T).cast());
    }
    #[cfg(not(target_arch = "x86_64"))]
    let _ = r;
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::hash::BuildHasher;

    #[test]
    fn cell_of_is_the_floor() {
        for x in [
            -2.5,
            -2.0,
            -1e-300,
            -0.0,
            0.0,
            0.3,
            2.0,
            1e300,
            -1e300,
            f64::INFINITY,
            f64::NEG_INFINITY,
            f64::NAN,
        ] {
            for cell in [1.0, 0.04, 3.0] {
                assert_eq!(cell_of(x, cell), (x / cell).floor() as i64, "{x} / {cell}");
            }
        }
    }

    #[test]
    fn cell_table_finds_what_it_holds() {
        let mut t = CellTable::with_capacity(1);
        for k in 0..1000i64 {
            *t.entry_or(packed_cell((k, -k, 3 * k)), 7) += k as u32;
        }
        for k in 0..1000i64 {
            assert_eq!(t.get(packed_cell((k, -k, 3 * k))), Some(7 + k as u32));
        }
        assert_eq!(t.get(packed_cell((1, 1, 1))), None);
        assert_eq!(packed_cell((1 << 21, 0, 0)), packed_cell((0, 0, 0)), "wraps");
    }

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
