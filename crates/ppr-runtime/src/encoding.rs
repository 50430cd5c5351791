//! The intermediate-buffer encoding: four packing bases, mirrored fractions, `atomicMin` order.
//!
//! This is the CPU reference of `crates/ppr-runtime/shaders/encoding.wgsl`; a GPU test holds the two
//! bit-for-bit equal. It follows the seed (Cichocki, "Optimized pixel-projected
//! reflections", `PPR_EncodeIntermediateBufferValue`):
//!
//! - the offset (reflecting pixel − reflected pixel, in pixels) is expressed in the one of
//!   four bases (+x, −x, +y, −y) closest to its direction, so that its *major* component is
//!   non-negative and sits in the most significant bits: `atomicMin` keeps the shortest
//!   offset, i.e. the closest reflected surface;
//! - the offset is split into a whole part `floor(o + 0.5)` and a fraction in
//!   `[-0.5, 0.5)`; the fraction is mirrored along the offset direction (so filtered
//!   reflections do not swim under motion), scaled by 0.707 and quantised.
//!
//! Two deliberate differences from the seed's HLSL, both to make the function exact:
//!
//! 1. **Integer arithmetic.** The seed mirrors the fraction with `normalize`, whose
//!    rounding differs between GPUs (and from the CPU). Here the offset is first rounded
//!    to 1/32 px; the mirror direction is `(t, 1)` in the packing basis with the tangent
//!    `t = minor / major` rounded to 1/256, which needs no square root: reflecting `f`
//!    across the line orthogonal to `(t, 1)` is `f − 2 (t, 1) (t f.x + f.y) / (1 + t²)`,
//!    a ratio of integers. The quantised fraction is then an integer division. 0.707 is
//!    taken as 181/256 = 0.70703125. Every GPU and the CPU produce the same bits. The
//!    fraction is quantised to its bin (the seed rounds to the nearest step but decodes
//!    the bin's centre: a half-step bias).
//! 2. **A layout chosen from the resolution** ([`EncodingLayout::for_resolution`]). The
//!    seed's layout ([`EncodingLayout::SEED`]: 12-bit major, 12-bit signed minor, 3+3
//!    fraction bits) overflows once an offset's minor component reaches ±2048 px, which
//!    a diagonal offset does at 3840×2160 (minor up to 2160). Offsets that do not fit the
//!    layout are not written (never wrapped into a wrong value).

use glam::{IVec2, Vec2};

/// The value the intermediate buffer is cleared to: "no reflection here".
pub const CLEAR_VALUE: u32 = u32::MAX;
/// Offsets are rounded to `1 / 2^OFFSET_SUBPIXEL_BITS` px before encoding.
pub const OFFSET_SUBPIXEL_BITS: u32 = 5;
/// The mirror direction's tangent is rounded to `1 / 2^TANGENT_BITS`.
pub const TANGENT_BITS: u32 = 8;
/// Numerator of the fraction scale 181/256 ≈ 0.707 (the seed's `_fract *= 0.707`).
pub const FRACTION_SCALE_NUMERATOR: i32 = 181;
/// Most fraction bits a field may have (the integer quantisation is exact up to 3).
pub const MAX_FRACTION_BITS: u32 = 3;
/// Bits of the packing-basis index.
pub const BASIS_BITS: u32 = 2;

/// How the 32 bits of an intermediate-buffer value are split, most significant first:
/// major whole | major fraction | minor whole (signed, biased) | minor fraction | basis.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub struct EncodingLayout {
    /// Bits of the major (non-negative) whole part.
    pub major_int_bits: u32,
    /// Bits of the major fraction (at most [`MAX_FRACTION_BITS`]).
    pub major_frac_bits: u32,
    /// Bits of the minor whole part, sign included (stored with a bias of half its range).
    pub minor_int_bits: u32,
    /// Bits of the minor fraction (at most [`MAX_FRACTION_BITS`]).
    pub minor_frac_bits: u32,
    /// Mirror the fraction along the offset direction (the seed's cure for filtered
    /// reflections swimming under motion). Off only to show that artefact.
    pub mirror_fractions: bool,
}

impl EncodingLayout {
    /// The seed's layout: major below 4096 px, minor within ±2048 px (enough for 2560×1440).
    pub const SEED: Self = Self {
        major_int_bits: 12,
        major_frac_bits: 3,
        minor_int_bits: 12,
        minor_frac_bits: 3,
        mirror_fractions: true,
    };

    /// The layout with the most fraction bits that encodes every on-screen offset of a
    /// `width × height` viewport: the major whole part needs to hold `max(w, h)`, the
    /// minor `±min(w, h)`; what is left of 32 bits goes to the fractions (major first, at
    /// most [`MAX_FRACTION_BITS`] each) and any rest to the major whole part. Gives
    /// [`EncodingLayout::SEED`] up to 2560×1440.
    ///
    /// # Panics
    /// If the viewport is so large (beyond 16K × 16K) that no fraction bit is left.
    pub fn for_resolution(width: u32, height: u32) -> Self {
        let bits_for = |v: u32| 32 - v.leading_zeros();
        // +1 so that the all-ones value (the clear value) can never be a valid offset.
        let major_int_bits = bits_for(width.max(height) + 1);
        let minor_int_bits = bits_for(width.min(height) + 1) + 1;
        let left = (32 - BASIS_BITS)
            .checked_sub(major_int_bits + minor_int_bits)
            .filter(|&left| left >= 1)
            .unwrap_or_else(|| panic!("viewport {width}x{height} too large for a 32-bit encoding"));
        let major_frac_bits = left.div_ceil(2).min(MAX_FRACTION_BITS);
        let minor_frac_bits = (left - major_frac_bits).min(MAX_FRACTION_BITS);
        let spare = left - major_frac_bits - minor_frac_bits;
        Self {
            major_int_bits: major_int_bits + spare,
            major_frac_bits,
            minor_int_bits,
            minor_frac_bits,
            mirror_fractions: true,
        }
    }

    /// Total bits used (at most 32).
    pub fn total_bits(&self) -> u32 {
        self.major_int_bits + self.major_frac_bits + self.minor_int_bits + self.minor_frac_bits + BASIS_BITS
    }

    /// Largest encodable major whole part.
    pub fn max_major(&self) -> i32 {
        (1 << self.major_int_bits) - 1
    }

    /// Largest encodable magnitude of the minor whole part (the range is `[-bias, bias)`).
    pub fn minor_bias(&self) -> i32 {
        1 << (self.minor_int_bits - 1)
    }

    /// Whether every on-screen offset of a `width × height` viewport fits.
    pub fn fits_viewport(&self, width: u32, height: u32) -> bool {
        (width.max(height) as i32) < self.max_major() && (width.min(height) as i32) < self.minor_bias()
    }

    /// Size of one fraction step of the decoded offset along the major axis, in pixels.
    pub fn major_step(&self) -> f32 {
        fraction_step(self.major_frac_bits)
    }

    /// Size of one fraction step of the decoded offset along the minor axis, in pixels.
    pub fn minor_step(&self) -> f32 {
        fraction_step(self.minor_frac_bits)
    }

    /// What decoding multiplies `2q + 1 − 2^bits` by to get the fraction of a field with
    /// `bits` fraction bits: `(q + 0.5) / 2^bits − 0.5`, divided by 0.70703125. Rounded
    /// once here and handed to the GPU, so both sides multiply by the same f32.
    pub fn decode_scale(bits: u32) -> f32 {
        (256.0 / (f64::from(FRACTION_SCALE_NUMERATOR) * 2.0 * f64::from(1u32 << bits))) as f32
    }

    /// The layout as the GPU reads it (see `EncodingParams` in `encoding.wgsl`).
    pub fn gpu_params(&self) -> EncodingParams {
        EncodingParams {
            major_int_bits: self.major_int_bits,
            major_frac_bits: self.major_frac_bits,
            minor_int_bits: self.minor_int_bits,
            minor_frac_bits: self.minor_frac_bits,
            major_decode_scale: Self::decode_scale(self.major_frac_bits),
            minor_decode_scale: Self::decode_scale(self.minor_frac_bits),
            mirror_fractions: u32::from(self.mirror_fractions),
            _pad: 0,
        }
    }
}

fn fraction_step(bits: u32) -> f32 {
    1.0 / ((1u32 << bits) as f32 * FRACTION_SCALE_NUMERATOR as f32 / 256.0)
}

/// `EncodingParams` of `encoding.wgsl`, byte for byte.
#[repr(C)]
#[derive(Clone, Copy, Debug, PartialEq, bytemuck::Pod, bytemuck::Zeroable)]
pub struct EncodingParams {
    pub major_int_bits: u32,
    pub major_frac_bits: u32,
    pub minor_int_bits: u32,
    pub minor_frac_bits: u32,
    pub major_decode_scale: f32,
    pub minor_decode_scale: f32,
    pub mirror_fractions: u32,
    pub _pad: u32,
}
const _: () = assert!(std::mem::size_of::<EncodingParams>() == 32);

/// A decoded intermediate-buffer value, in its packing basis.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct DecodedOffset {
    /// Whole parts (minor, major) in the packing basis.
    pub whole: IVec2,
    /// Mirrored fractions (minor, major) in the packing basis, pixels.
    pub fract: Vec2,
    /// Packing basis index: 0 = +x, 1 = −x, 2 = +y, 3 = −y.
    pub basis: u32,
}

impl DecodedOffset {
    /// The screen-space offset with fractions (the filtered sample's offset).
    pub fn offset(&self) -> Vec2 {
        to_screen(self.whole.as_vec2() + self.fract, self.basis)
    }

    /// The screen-space offset without fractions (the unfiltered sample's offset).
    pub fn whole_offset(&self) -> Vec2 {
        to_screen(self.whole.as_vec2(), self.basis)
    }
}

/// Packing basis of an offset (`PPR_GetPackingBasisIndexTwoBits`).
pub fn basis_index(o: IVec2) -> u32 {
    if o.x.abs() >= o.y.abs() {
        if o.x >= 0 { 0 } else { 1 }
    } else if o.y >= 0 {
        2
    } else {
        3
    }
}

/// Screen space → packing basis `(minor, major)` (the seed's `mul(basisMatrix, v)`).
pub fn to_basis(v: IVec2, basis: u32) -> IVec2 {
    match basis {
        0 => IVec2::new(-v.y, v.x),
        1 => IVec2::new(v.y, -v.x),
        2 => IVec2::new(v.x, v.y),
        _ => IVec2::new(-v.x, -v.y),
    }
}

/// Packing basis `(minor, major)` → screen space (the seed's `mul(v, basisMatrix)`).
pub fn to_screen(v: Vec2, basis: u32) -> Vec2 {
    match basis {
        0 => Vec2::new(v.y, -v.x),
        1 => Vec2::new(-v.y, v.x),
        2 => Vec2::new(v.x, v.y),
        _ => Vec2::new(-v.x, -v.y),
    }
}

/// Rounds `a / b` half away from zero, for `b > 0`.
fn div_round(a: i32, b: i32) -> i32 {
    if a >= 0 { (2 * a + b) / (2 * b) } else { -((-2 * a + b) / (2 * b)) }
}

/// The quantised fraction of a mirrored component `p / den` (in 1/32 px) with `bits` bits:
/// the index of its bin, `min(floor((p / den / 32) · 0.70703125 · 2^bits + 2^bits / 2), 2^bits − 1)`.
///
/// The seed rounds to the nearest step (`floor(x + 0.5)`) but decodes the bin's centre
/// (`(q + 0.5) / 2^bits`), a bias of half a step (0.088 px with 3 bits); taking the bin
/// index makes the decoded fraction unbiased (error ≤ half a step).
fn quantise_fraction(p: i32, den: i32, bits: u32) -> u32 {
    let mult = 1u32 << bits;
    // The mirrored fraction has length ≤ 0.7072 px, so 181·p + 4096·den > 0 (see module docs).
    let num = (FRACTION_SCALE_NUMERATOR * p + 4096 * den) as u32;
    let q = num / ((8192 / mult) * den as u32);
    q.min(mult - 1)
}

/// Encodes a screen-space offset (target point − source pixel centre, pixels), split as
/// the seed does: whole part `floor(o + 0.5)`, fraction in `[-0.5, 0.5)`.
/// Returns [`CLEAR_VALUE`] for offsets that do not fit the layout or are not finite.
pub fn encode(offset: Vec2, layout: &EncodingLayout) -> u32 {
    if !offset.is_finite() || offset.abs().max_element() >= 65536.0 {
        return CLEAR_VALUE;
    }
    let whole = (offset + 0.5).floor();
    encode_parts(whole.as_ivec2(), offset - whole, layout)
}

/// Encodes an offset given in parts: `whole` = target pixel − source pixel (integers) and
/// `fract` = the target point's position in its pixel relative to the pixel's centre, in
/// `[-0.5, 0.5)`. The projection pass calls this: with integer pixels the whole part
/// always points exactly at the source pixel, which `floor(o + 0.5)` on a rounded f32
/// offset does not guarantee. Returns [`CLEAR_VALUE`] when the offset does not fit.
pub fn encode_parts(whole: IVec2, fract: Vec2, layout: &EncodingLayout) -> u32 {
    const ONE: i32 = 1 << OFFSET_SUBPIXEL_BITS;
    const HALF: i32 = ONE / 2;
    if !fract.is_finite() || whole.abs().max_element() >= 65536 {
        return CLEAR_VALUE;
    }
    // The fraction in 1/32 px (exact: scaling by a power of two and rounding are exact in
    // f32), kept inside its pixel so the whole part stays the integer one.
    let fract = IVec2::new(
        ((fract.x * ONE as f32).round_ties_even() as i32).clamp(-HALF, HALF - 1),
        ((fract.y * ONE as f32).round_ties_even() as i32).clamp(-HALF, HALF - 1),
    );
    let o = whole * ONE + fract;
    let basis = basis_index(o);
    let (o, whole, fract) = (to_basis(o, basis), to_basis(whole, basis), to_basis(fract, basis));
    if whole.y > layout.max_major() || whole.x < -layout.minor_bias() || whole.x >= layout.minor_bias() {
        return CLEAR_VALUE;
    }
    // Mirror the fraction along the direction (t, 1), t = minor / major rounded to 1/256:
    // the mirrored fraction is (p_minor, p_major) / den.
    let (p_minor, p_major, den) = if layout.mirror_fractions {
        let t = if o.y > 0 { div_round(o.x << TANGENT_BITS, o.y) } else { 0 };
        let k = 1 << TANGENT_BITS;
        let s = t * fract.x + k * fract.y;
        let den = t * t + k * k;
        (fract.x * den - 2 * t * s, fract.y * den - 2 * k * s, den)
    } else {
        (fract.x, fract.y, 1)
    };
    let q_minor = quantise_fraction(p_minor, den, layout.minor_frac_bits);
    let q_major = quantise_fraction(p_major, den, layout.major_frac_bits);

    let major_field = ((whole.y as u32) << layout.major_frac_bits) | q_major;
    let minor_field = (((whole.x + layout.minor_bias()) as u32) << layout.minor_frac_bits) | q_minor;
    let minor_bits = layout.minor_int_bits + layout.minor_frac_bits;
    (((major_field << minor_bits) | minor_field) << BASIS_BITS) | basis
}

/// Decodes an intermediate-buffer value; `None` for [`CLEAR_VALUE`].
pub fn decode(value: u32, layout: &EncodingLayout) -> Option<DecodedOffset> {
    if value == CLEAR_VALUE {
        return None;
    }
    let basis = value & 3;
    let rest = value >> BASIS_BITS;
    let minor_bits = layout.minor_int_bits + layout.minor_frac_bits;
    let minor_field = rest & ((1 << minor_bits) - 1);
    let major_field = rest >> minor_bits;
    let field = |f: u32, frac_bits: u32, bias: i32| {
        let q = (f & ((1 << frac_bits) - 1)) as i32;
        let whole = (f >> frac_bits) as i32 - bias;
        let fract = (2 * q + 1 - (1 << frac_bits)) as f32 * EncodingLayout::decode_scale(frac_bits);
        (whole, fract)
    };
    let (minor_whole, minor_fract) = field(minor_field, layout.minor_frac_bits, layout.minor_bias());
    let (major_whole, major_fract) = field(major_field, layout.major_frac_bits, 0);
    Some(DecodedOffset {
        whole: IVec2::new(minor_whole, major_whole),
        fract: Vec2::new(minor_fract, major_fract),
        basis,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn layouts_for_common_resolutions() {
        let check = |w, h, expected: [u32; 4]| {
            let l = EncodingLayout::for_resolution(w, h);
            assert_eq!(
                [l.major_int_bits, l.major_frac_bits, l.minor_int_bits, l.minor_frac_bits],
                expected,
                "{w}x{h}"
            );
            assert!(l.total_bits() <= 32 && l.fits_viewport(w, h), "{w}x{h}: {l:?}");
        };
        check(1920, 1080, [12, 3, 12, 3]);
        check(2560, 1440, [12, 3, 12, 3]);
        check(3840, 2160, [12, 3, 13, 2]);
        check(7680, 4320, [13, 2, 14, 1]);
        check(1, 1, [21, 3, 3, 3]);
        assert!(EncodingLayout::for_resolution(640, 480).mirror_fractions);
        assert_eq!(EncodingLayout::for_resolution(1920, 1080), EncodingLayout::SEED);
        assert!(EncodingLayout::SEED.fits_viewport(1920, 1080));
        assert!(!EncodingLayout::SEED.fits_viewport(3840, 2160));
    }

    #[test]
    fn round_trip_stays_within_one_fraction_step() {
        for layout in [EncodingLayout::SEED, EncodingLayout::for_resolution(3840, 2160)] {
            for &(x, y) in
                &[(0.3, 5.2), (-100.25, 3.0), (17.5, -1900.0), (0.0, 0.0), (-3.9, -3.9), (1000.1, 999.7)]
            {
                let o = Vec2::new(x, y);
                let d = decode(encode(o, &layout), &layout).expect("fits");
                let err = d.offset() - o;
                // Mirroring keeps the fraction's length, so the error is bounded by the
                // fraction's length plus its quantisation, not by the step alone; the whole
                // part is exact.
                assert!((d.whole_offset() - o).abs().max_element() <= 0.5 + 1e-6, "{o} -> {d:?}");
                assert!(err.length() <= 2.0 * 0.7072 + layout.major_step(), "{o}: error {err}");
            }
        }
    }

    #[test]
    fn shorter_offsets_along_one_direction_encode_smaller() {
        // Order is by the major whole part; within one whole pixel the mirrored fraction
        // reverses it (the seed's "flipped" fraction), so compare whole pixels only.
        let layout = EncodingLayout::for_resolution(3840, 2160);
        for dir in [Vec2::new(0.3, -1.0), Vec2::new(-1.0, 0.9), Vec2::new(1.0, 0.0)] {
            let dir = dir.normalize();
            let values: Vec<(i32, u32)> = (1..4000)
                .map(|i| {
                    let v = encode(dir * (i as f32 * 0.5), &layout);
                    (decode(v, &layout).expect("fits").whole.y, v)
                })
                .collect();
            for w in values.windows(2) {
                if w[1].0 > w[0].0 {
                    assert!(w[1].1 > w[0].1, "{dir}: {:?}", w);
                }
            }
        }
    }

    #[test]
    fn offsets_that_do_not_fit_are_not_written() {
        let l = EncodingLayout::SEED;
        assert_ne!(encode(Vec2::new(4095.0, 0.0), &l), CLEAR_VALUE);
        assert_eq!(encode(Vec2::new(4096.0, 0.0), &l), CLEAR_VALUE);
        assert_ne!(encode(Vec2::new(3000.0, -2047.0), &l), CLEAR_VALUE);
        assert_eq!(encode(Vec2::new(3000.0, -2049.0), &l), CLEAR_VALUE);
        assert_eq!(encode(Vec2::new(3840.0, 2160.0), &l), CLEAR_VALUE);
        assert_eq!(encode(Vec2::new(f32::NAN, 1.0), &l), CLEAR_VALUE);
        assert_eq!(encode(Vec2::new(1.0, f32::INFINITY), &l), CLEAR_VALUE);
        assert_eq!(decode(CLEAR_VALUE, &l), None);
    }
}
