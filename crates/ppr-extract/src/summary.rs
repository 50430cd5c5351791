//! The summary table printed after extraction: shapes, area, coverage, occluders, and time
//! per stage in milliseconds and triangles per second.

use std::fmt::Write as _;
use std::time::Duration;

use ppr_format::ReflectorKind;

use crate::{Extraction, Stage};

/// The summary of `x`; `timings` are every stage's times (the library's plus load and write).
pub fn summary_table(x: &Extraction, timings: &[(Stage, Duration)]) -> String {
    let mut s = String::new();
    let rs = &x.set.reflectors;
    let count = |k: ReflectorKind| rs.iter().filter(|r| r.kind == k).count();
    let area: f64 = rs.iter().map(|r| r.area()).fold(0.0, |a, b| a + b);
    let mean_cov =
        if rs.is_empty() { 0.0 } else { rs.iter().map(|r| r.coverage).sum::<f64>() / rs.len() as f64 };
    let weighted_cov =
        if area > 0.0 { rs.iter().map(|r| r.coverage * r.area()).sum::<f64>() / area } else { 0.0 };
    let st = &x.stats;
    let degenerate = x
        .warnings
        .iter()
        .find_map(|w| if let crate::Warning::DegenerateTriangles(n) = w { Some(*n) } else { None })
        .unwrap_or(0);
    let _ = writeln!(
        s,
        "shapes            {:>10}   (opaque {}, transparent {}, water {})",
        rs.len(),
        count(ReflectorKind::Opaque),
        count(ReflectorKind::Transparent),
        count(ReflectorKind::Water)
    );
    let _ = writeln!(s, "total area        {area:>10.3}   m²");
    let _ = writeln!(s, "mean coverage     {mean_cov:>10.3}   (area-weighted {weighted_cov:.3})");
    let _ = writeln!(s, "occluder pairs    {:>10}", st.occluder_pairs);
    let _ = writeln!(s, "parallel groups   {:>10}", st.parallel_groups);
    let _ = writeln!(
        s,
        "triangles         {:>10}   (candidates {}, degenerate skipped {degenerate})",
        st.triangles, st.candidates
    );
    let _ = writeln!(
        s,
        "regions           {:>10}   (kept {}, level diagonal {:.3} m)",
        st.regions, st.regions_kept, st.diagonal
    );
    let _ = writeln!(s);
    let _ = writeln!(s, "stage          time (ms)    triangles/s");
    let mut total = Duration::ZERO;
    for stage in Stage::ALL {
        let Some(d) = timings.iter().filter(|(t, _)| *t == stage).map(|(_, d)| *d).reduce(|a, b| a + b)
        else {
            continue;
        };
        total += d;
        let _ = writeln!(s, "{:<12} {:>11.2}    {}", stage.name(), ms(d), rate(st.triangles, d));
    }
    let _ = writeln!(s, "{:<12} {:>11.2}    {}", "total", ms(total), rate(st.triangles, total));
    if !x.warnings.is_empty() {
        let _ = writeln!(s);
        for w in &x.warnings {
            let _ = writeln!(s, "note: {w}");
        }
    }
    s
}

fn ms(d: Duration) -> f64 {
    d.as_secs_f64() * 1e3
}

/// Triangles per second, human-sized.
pub fn rate(triangles: usize, d: Duration) -> String {
    let secs = d.as_secs_f64();
    if secs <= 0.0 {
        return "-".into();
    }
    let r = triangles as f64 / secs;
    if r >= 1e6 {
        format!("{:.2} M", r / 1e6)
    } else if r >= 1e3 {
        format!("{:.1} k", r / 1e3)
    } else {
        format!("{r:.0}")
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn rates_read_well() {
        assert_eq!(rate(52_000, Duration::from_millis(100)), "520.0 k");
        assert_eq!(rate(5_000_000, Duration::from_secs(1)), "5.00 M");
        assert_eq!(rate(10, Duration::ZERO), "-");
    }
}
