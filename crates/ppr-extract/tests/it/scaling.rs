//! Extraction time grows linearly with the level: four times the triangles (a grid of
//! generated rooms) costs at most eight times the time (linear is 4×, n log n about 4.5×,
//! quadratic 16×; the margin is for the caches of a shared machine: 5.15× was seen while
//! other builds ran). The only timed test: each size runs
//! three times, interleaved, on one thread, and the minimum counts; the time is the
//! thread's CPU time (Linux `schedstat`, nanoseconds) where available, so other builds on
//! a shared machine do not count, else wall time.

use std::time::{Duration, Instant};

use ppr_extract::generated_levels::{RoomSpec, level_of, room_grid};
use ppr_extract::{ExtractParams, Level, extract};

/// This thread's CPU time, if the system tells it.
fn thread_cpu_time() -> Option<Duration> {
    let text = std::fs::read_to_string("/proc/thread-self/schedstat").ok()?;
    Some(Duration::from_nanos(text.split_whitespace().next()?.parse().ok()?))
}

fn fastest(level: &Level, params: &ExtractParams, best: &mut Duration) {
    let (t, cpu) = (Instant::now(), thread_cpu_time());
    let x = extract(level, params, &|_, _| {});
    let spent = match (cpu, thread_cpu_time()) {
        (Some(a), Some(b)) => b.saturating_sub(a),
        _ => t.elapsed(),
    };
    *best = (*best).min(spent);
    assert!(!x.set.reflectors.is_empty());
}

#[test]
fn four_times_the_triangles_cost_well_under_quadratic_time() {
    // The rooms of examples/extract_scaling.rs (3852 triangles each): 4 × 4 and 8 × 8.
    let spec = RoomSpec { cells_per_m: 4.0, ..RoomSpec::default() };
    let small = level_of("small", &room_grid(&spec, 4, 4, 8.0));
    let large = level_of("large", &room_grid(&spec, 8, 8, 8.0));
    assert_eq!(large.triangles.len(), 4 * small.triangles.len());
    let params = ExtractParams { threads: 1, ..ExtractParams::all_planar() };
    let (mut t_small, mut t_large) = (Duration::MAX, Duration::MAX);
    for _ in 0..3 {
        fastest(&small, &params, &mut t_small);
        fastest(&large, &params, &mut t_large);
    }
    let ratio = t_large.as_secs_f64() / t_small.as_secs_f64();
    eprintln!(
        "{} triangles: {:.1} ms; {}: {:.1} ms; ratio {ratio:.2}",
        small.triangles.len(),
        t_small.as_secs_f64() * 1e3,
        large.triangles.len(),
        t_large.as_secs_f64() * 1e3
    );
    assert!(ratio <= 8.0, "4× the triangles cost {ratio:.2}× the time (quadratic would be 16×)");
}
