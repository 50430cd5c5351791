//! Encoding: every offset round-trips within its fraction step; the atomicMin order
//! follows the offset length where it can (and where it cannot, by how much); the layout
//! chosen from the resolution holds every on-screen offset up to 7680×4320.

use glam::{DVec2, Vec2};
use ppr_runtime::EncodingLayout;
use ppr_runtime::encoding::{CLEAR_VALUE, decode, encode};

fn layouts() -> [(&'static str, EncodingLayout); 4] {
    [
        ("seed", EncodingLayout::SEED),
        ("1920x1080", EncodingLayout::for_resolution(1920, 1080)),
        ("3840x2160", EncodingLayout::for_resolution(3840, 2160)),
        ("7680x4320", EncodingLayout::for_resolution(7680, 4320)),
    ]
}

/// The seed's definition of the stored fraction, in f64: whole = floor(o + 0.5), the
/// fraction (rounded to the encoding's 1/32 px input, kept in its pixel) mirrored along
/// the offset direction.
fn ideal_fraction(o: Vec2) -> DVec2 {
    let whole = (o + 0.5).floor().as_dvec2();
    let f = ((o.as_dvec2() - whole) * 32.0).round().clamp(DVec2::splat(-16.0), DVec2::splat(15.0)) / 32.0;
    let o = whole + f;
    if o.length() == 0.0 {
        return f;
    }
    let d = o / o.length();
    f - 2.0 * d * d.dot(f)
}

#[test]
fn every_offset_round_trips_within_its_fraction_step() {
    for (name, layout) in layouts() {
        // Dense near the origin (1/16 px grid), then along rays out to the layout's limits.
        let mut offsets: Vec<Vec2> = Vec::new();
        for y in -320..=320 {
            for x in -320..=320 {
                offsets.push(Vec2::new(x as f32, y as f32) / 16.0);
            }
        }
        let max = layout.max_major().min(layout.minor_bias()) as f32 - 1.0;
        for a in 0..3600 {
            let dir = Vec2::from_angle(a as f32 * std::f32::consts::TAU / 3600.0);
            for r in [17.3, 255.9, 1000.45, max * 0.999] {
                offsets.push(dir * r);
            }
        }
        let step = layout.major_step().max(layout.minor_step());
        let (mut worst, mut whole_errors) = (0.0f64, 0usize);
        for &o in &offsets {
            let v = encode(o, &layout);
            let d = decode(v, &layout).unwrap_or_else(|| panic!("{name}: {o} must fit"));
            let whole = d.whole_offset();
            whole_errors += usize::from(whole != (o + 0.5).floor());
            let fract = (d.offset() - whole).as_dvec2();
            worst = worst.max((fract - ideal_fraction(o)).length());
        }
        // Half a quantisation step per axis, plus the 1/256 tangent rounding
        // (≤ 0.71 px × 2/256 rad). (The input is rounded to 1/32 px first, as defined.)
        let bound = f64::from(step) * 0.5 * std::f64::consts::SQRT_2 + 0.006;
        eprintln!(
            "{name}: {} offsets, whole parts exact: {}, worst fraction error {worst:.4} px (bound {bound:.4}; steps {:.4}/{:.4} px)",
            offsets.len(),
            whole_errors == 0,
            layout.major_step(),
            layout.minor_step()
        );
        assert_eq!(whole_errors, 0, "{name}");
        assert!(worst <= bound, "{name}: {worst} > {bound}");
    }
}

#[test]
fn atomic_min_order_follows_offset_length() {
    let layout = EncodingLayout::for_resolution(3840, 2160);
    // (a) Along one direction (what competes for one target pixel of a planar mirror:
    // sources on one reflected ray), the order is the length order except within the
    // whole pixel where the mirrored fraction reverses it.
    let mut worst_same_direction = 0.0f32;
    for a in 0..3600 {
        let dir = Vec2::from_angle(a as f32 * std::f32::consts::TAU / 3600.0);
        let values: Vec<(f32, u32)> =
            (1..2000).map(|i| (i as f32 * 0.25, encode(dir * (i as f32 * 0.25), &layout))).collect();
        for (i, &(li, vi)) in values.iter().enumerate() {
            for &(lj, vj) in &values[i + 1..(i + 12).min(values.len())] {
                if vj < vi {
                    worst_same_direction = worst_same_direction.max(lj - li);
                }
            }
        }
    }
    // (b) Across directions the order is the major component's (an L∞ norm within each
    // basis), so a longer offset can win against a shorter one by up to √2 in length.
    let (mut pairs, mut inversions, mut worst_ratio) = (0u64, 0u64, 1.0f32);
    let grid: Vec<Vec2> =
        (-24..=24).flat_map(|y| (-24..=24).map(move |x| Vec2::new(x as f32, y as f32) * 5.3)).collect();
    for &p in &grid {
        for &q in &grid {
            let (lp, lq) = (p.length(), q.length());
            if lp < 8.0 || lq < lp + 1.0 {
                continue;
            }
            pairs += 1;
            if encode(q, &layout) < encode(p, &layout) {
                inversions += 1;
                worst_ratio = worst_ratio.max(lq / lp);
            }
        }
    }
    eprintln!(
        "same direction: inverted only within {worst_same_direction:.2} px; across directions: {inversions} of {pairs} pairs inverted ({:.1}%), longest/shortest ≤ {worst_ratio:.3}",
        100.0 * inversions as f64 / pairs as f64
    );
    assert!(worst_same_direction <= 1.5, "{worst_same_direction}");
    assert!(worst_ratio <= std::f32::consts::SQRT_2 * 1.02, "{worst_ratio}");
}

#[test]
fn the_resolution_layout_holds_every_on_screen_offset() {
    for (w, h) in [(1920u32, 1080u32), (3840, 2160), (7680, 4320)] {
        let ours = EncodingLayout::for_resolution(w, h);
        let (mut total, mut seed_lost, mut ours_lost) = (0u64, 0u64, 0u64);
        let (wi, hi) = (w as i32 - 1, h as i32 - 1);
        for dy in (-hi..=hi).step_by(7).chain([-hi, hi]) {
            for dx in (-wi..=wi).step_by(11).chain([-wi, wi]) {
                let o = Vec2::new(dx as f32 + 0.3, dy as f32 - 0.2)
                    .clamp(Vec2::new(-wi as f32, -hi as f32), Vec2::new(wi as f32, hi as f32));
                total += 1;
                seed_lost += u64::from(encode(o, &EncodingLayout::SEED) == CLEAR_VALUE);
                ours_lost += u64::from(encode(o, &ours) == CLEAR_VALUE);
            }
        }
        eprintln!(
            "{w}x{h}: layout {}.{}/{}.{}; of {total} offsets the seed layout cannot store {seed_lost} ({:.1}%), ours {ours_lost}",
            ours.major_int_bits,
            ours.major_frac_bits,
            ours.minor_int_bits,
            ours.minor_frac_bits,
            100.0 * seed_lost as f64 / total as f64
        );
        assert_eq!(ours_lost, 0, "{w}x{h}");
        if w >= 3840 {
            assert!(seed_lost > 0, "the seed's 12-bit minor overflows at {w}x{h}");
        } else {
            assert_eq!(seed_lost, 0);
        }
    }
}
