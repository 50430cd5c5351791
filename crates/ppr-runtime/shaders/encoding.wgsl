// Intermediate-buffer encoding: four packing bases, mirrored fractions, atomicMin order.
// The CPU reference is crates/ppr-runtime/src/encoding.rs; a GPU test holds the two
// bit-for-bit equal. Read the Rust module's docs for the design; keep both in step.

const PPR_CLEAR_VALUE: u32 = 0xffffffffu;
const PPR_OFFSET_SUBPIXEL_BITS: u32 = 5u;
const PPR_TANGENT_BITS: u32 = 8u;
const PPR_FRACTION_SCALE_NUMERATOR: i32 = 181;

// EncodingParams of encoding.rs, byte for byte.
struct EncodingParams {
    major_int_bits: u32,
    major_frac_bits: u32,
    minor_int_bits: u32,
    minor_frac_bits: u32,
    major_decode_scale: f32,
    minor_decode_scale: f32,
    // 1: mirror the fraction along the offset direction (the seed's behaviour).
    mirror_fractions: u32,
    _pad: u32,
}

// A decoded value in its packing basis: (minor, major).
struct PprDecoded {
    whole: vec2<i32>,
    fract: vec2<f32>,
    basis: u32,
}

// Finite test on the bits: shader compilers may rewrite comparisons with NaN (`!(x < y)`
// into `x >= y`), so `x == x`-style tests are not reliable.
fn ppr_is_finite(x: f32) -> bool {
    return (bitcast<u32>(x) & 0x7f800000u) != 0x7f800000u;
}

fn ppr_is_finite2(v: vec2<f32>) -> bool {
    return ppr_is_finite(v.x) && ppr_is_finite(v.y);
}

fn ppr_is_finite3(v: vec3<f32>) -> bool {
    return ppr_is_finite(v.x) && ppr_is_finite(v.y) && ppr_is_finite(v.z);
}

fn ppr_basis_index(o: vec2<i32>) -> u32 {
    if (abs(o.x) >= abs(o.y)) {
        return select(1u, 0u, o.x >= 0);
    }
    return select(3u, 2u, o.y >= 0);
}

// Screen space -> packing basis (minor, major): basis 0 (-y, x), 1 (y, -x), 2 (x, y),
// 3 (-x, -y), as a swap for the x bases and a sign for the odd ones (two selects, no
// branch).
fn ppr_to_basis(v: vec2<i32>, basis: u32) -> vec2<i32> {
    let swapped = select(v, vec2<i32>(-v.y, v.x), basis < 2u);
    return select(swapped, -swapped, (basis & 1u) != 0u);
}

// Packing basis (minor, major) -> screen space.
fn ppr_to_screen(v: vec2<f32>, basis: u32) -> vec2<f32> {
    switch basis {
        case 0u: { return vec2<f32>(v.y, -v.x); }
        case 1u: { return vec2<f32>(-v.y, v.x); }
        case 2u: { return v; }
        default: { return -v; }
    }
}

// encoding.rs's div_round: a / b rounded half away from zero, (2|a| + b) / (2b) with a's
// sign, for b > 0 and |a| <= 256 b (the tangent's range: |minor| <= major). Without an
// integer division: a float estimate of a quotient of at most 256.5 (off by under 0.001)
// and a one-step correction, which make it exact.
fn ppr_div_round(a: i32, b: i32) -> i32 {
    let n = u32(2 * abs(a) + b);
    let d = u32(2 * b);
    var q = min(u32(f32(n) / f32(d)), 257u);
    if (q * d > n) {
        q -= 1u;
    } else if ((q + 1u) * d <= n) {
        q += 1u;
    }
    return select(-i32(q), i32(q), a >= 0);
}

// encoding.rs's quantise_fraction: min(num / ((8192 / 2^bits) * den), 2^bits - 1) with
// num = 181 p + 4096 den (> 0). Without an integer division (bits <= 3, den <= 2^17, num <
// 2^31): num / (2^(13 - bits) * den) = (num >> (13 - bits)) / den for whole numbers, and
// that quotient is estimated with `inv_den` (1 / den, shared by both of an offset's
// fractions) and corrected by one step, which makes it exact (estimates of quotients up
// to 2^bits + 1 are off by under 0.01; larger ones are capped, then clamped below).
fn ppr_quantise_fraction(p: i32, den: i32, bits: u32, inv_den: f32) -> u32 {
    let mult = 1u << bits;
    let num = u32(PPR_FRACTION_SCALE_NUMERATOR * p + 4096 * den);
    let n = num >> (13u - bits);
    let d = u32(den);
    var q = min(u32(f32(n) * inv_den), mult);
    if (q * d > n) {
        q -= 1u;
    } else if ((q + 1u) * d <= n) {
        q += 1u;
    }
    return min(q, mult - 1u);
}

// Encodes a screen-space offset (target point - source pixel centre), split as the seed
// does: whole part floor(o + 0.5), fraction in [-0.5, 0.5).
fn ppr_encode(offset: vec2<f32>, enc: EncodingParams) -> u32 {
    if (!ppr_is_finite2(offset) || any(abs(offset) >= vec2<f32>(65536.0))) {
        return PPR_CLEAR_VALUE;
    }
    let whole = floor(offset + 0.5);
    return ppr_encode_parts(vec2<i32>(whole), offset - whole, enc);
}

// The sub-pixel fraction in 1/2^PPR_OFFSET_SUBPIXEL_BITS steps, rounded and kept inside
// [-half, half) of a pixel.
fn ppr_subpixel_fraction(fract_in: vec2<f32>) -> vec2<i32> {
    let one = 1 << PPR_OFFSET_SUBPIXEL_BITS;
    let half = one / 2;
    return clamp(vec2<i32>(round(fract_in * f32(one))), vec2<i32>(-half), vec2<i32>(half - 1));
}

// The whole offset and its sub-pixel fraction as one fixed-point offset (what picks the basis).
fn ppr_subpixel_offset(whole_s: vec2<i32>, fract_s: vec2<i32>) -> vec2<i32> {
    return whole_s * (1 << PPR_OFFSET_SUBPIXEL_BITS) + fract_s;
}

// Encodes an offset in parts: whole = target pixel - source pixel, fract = the target
// point in its pixel relative to the pixel's centre, in [-0.5, 0.5).
fn ppr_encode_parts(whole_s: vec2<i32>, fract_in: vec2<f32>, enc: EncodingParams) -> u32 {
    if (!ppr_is_finite2(fract_in) || any(abs(fract_in) >= vec2<f32>(2.0)) || any(abs(whole_s) >= vec2<i32>(65536))) {
        return PPR_CLEAR_VALUE;
    }
    let fract_s = ppr_subpixel_fraction(fract_in);
    let os = ppr_subpixel_offset(whole_s, fract_s);
    let basis = ppr_basis_index(os);
    let o = ppr_to_basis(os, basis);
    let whole = ppr_to_basis(whole_s, basis);
    let fract = ppr_to_basis(fract_s, basis);
    let max_major = (1 << enc.major_int_bits) - 1;
    let minor_bias = 1 << (enc.minor_int_bits - 1u);
    if (whole.y > max_major || whole.x < -minor_bias || whole.x >= minor_bias) {
        return PPR_CLEAR_VALUE;
    }
    // Mirrored fraction = (p_minor, p_major) / den.
    var p_minor = fract.x;
    var p_major = fract.y;
    var den = 1;
    if (enc.mirror_fractions != 0u) {
        var t = 0;
        if (o.y > 0) {
            t = ppr_div_round(o.x << PPR_TANGENT_BITS, o.y);
        }
        let k = 1 << PPR_TANGENT_BITS;
        let s = t * fract.x + k * fract.y;
        den = t * t + k * k;
        p_minor = fract.x * den - 2 * t * s;
        p_major = fract.y * den - 2 * k * s;
    }
    let inv_den = 1.0 / f32(den);
    let q_minor = ppr_quantise_fraction(p_minor, den, enc.minor_frac_bits, inv_den);
    let q_major = ppr_quantise_fraction(p_major, den, enc.major_frac_bits, inv_den);

    let major_field = (u32(whole.y) << enc.major_frac_bits) | q_major;
    let minor_field = (u32(whole.x + minor_bias) << enc.minor_frac_bits) | q_minor;
    let minor_bits = enc.minor_int_bits + enc.minor_frac_bits;
    return (((major_field << minor_bits) | minor_field) << 2u) | basis;
}

// The major whole part, in its packing basis, of the value ppr_encode_parts makes of these
// parts (where it makes one), without the encoding's divisions. It is the value's top
// field: a value whose major whole part exceeds another's is larger, whatever the rest.
fn ppr_parts_major_whole(whole_s: vec2<i32>, fract_in: vec2<f32>) -> i32 {
    let os = ppr_subpixel_offset(whole_s, ppr_subpixel_fraction(fract_in));
    return ppr_to_basis(whole_s, ppr_basis_index(os)).y;
}

// The major whole part of an encoded value (PPR_CLEAR_VALUE: larger than any value's).
fn ppr_value_major_whole(value: u32, enc: EncodingParams) -> i32 {
    return i32((value >> 2u) >> (enc.minor_int_bits + enc.minor_frac_bits + enc.major_frac_bits));
}

// Decodes a value that is not PPR_CLEAR_VALUE (check first).
fn ppr_decode(value: u32, enc: EncodingParams) -> PprDecoded {
    let basis = value & 3u;
    let rest = value >> 2u;
    let minor_bits = enc.minor_int_bits + enc.minor_frac_bits;
    let minor_field = rest & ((1u << minor_bits) - 1u);
    let major_field = rest >> minor_bits;
    let minor_bias = 1 << (enc.minor_int_bits - 1u);
    let q_minor = i32(minor_field & ((1u << enc.minor_frac_bits) - 1u));
    let q_major = i32(major_field & ((1u << enc.major_frac_bits) - 1u));
    var d: PprDecoded;
    d.whole = vec2<i32>(i32(minor_field >> enc.minor_frac_bits) - minor_bias, i32(major_field >> enc.major_frac_bits));
    d.fract = vec2<f32>(
        f32(2 * q_minor + 1 - (1 << enc.minor_frac_bits)) * enc.minor_decode_scale,
        f32(2 * q_major + 1 - (1 << enc.major_frac_bits)) * enc.major_decode_scale,
    );
    d.basis = basis;
    return d;
}

// Screen-space offset with fractions (filtered sample).
fn ppr_decoded_offset(d: PprDecoded) -> vec2<f32> {
    return ppr_to_screen(vec2<f32>(d.whole) + d.fract, d.basis);
}

// Screen-space offset without fractions (unfiltered sample).
fn ppr_decoded_whole_offset(d: PprDecoded) -> vec2<f32> {
    return ppr_to_screen(vec2<f32>(d.whole), d.basis);
}
