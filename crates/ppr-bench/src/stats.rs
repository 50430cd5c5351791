//! Order statistics of timing samples: median and 95th percentile (nearest rank).

/// Median and 95th percentile of a set of samples.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Summary {
    /// Middle value (mean of the two middle values for an even count).
    pub median: f64,
    /// Nearest-rank 95th percentile: the smallest sample with at least 95 % of the
    /// samples at or below it.
    pub p95: f64,
    /// Number of samples.
    pub count: usize,
}

impl Summary {
    /// Summarises `samples` (non-finite values are dropped); `None` when none is left.
    pub fn of(samples: &[f64]) -> Option<Self> {
        let mut v: Vec<f64> = samples.iter().copied().filter(|x| x.is_finite()).collect();
        if v.is_empty() {
            return None;
        }
        v.sort_by(f64::total_cmp);
        Some(Self { median: median_of_sorted(&v), p95: percentile_of_sorted(&v, 95.0), count: v.len() })
    }
}

/// Median of sorted, non-empty samples.
fn median_of_sorted(v: &[f64]) -> f64 {
    let n = v.len();
    if n % 2 == 1 { v[n / 2] } else { 0.5 * (v[n / 2 - 1] + v[n / 2]) }
}

/// Nearest-rank percentile `p` (0 < p ≤ 100) of sorted, non-empty samples.
fn percentile_of_sorted(v: &[f64], p: f64) -> f64 {
    let rank = (p / 100.0 * v.len() as f64).ceil() as usize;
    v[rank.clamp(1, v.len()) - 1]
}

/// Median of unsorted samples (`None` when empty or all non-finite).
pub fn median(samples: &[f64]) -> Option<f64> {
    Summary::of(samples).map(|s| s.median)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn check(samples: &[f64], median: f64, p95: f64) {
        let s = Summary::of(samples).expect("samples");
        assert_eq!((s.median, s.p95), (median, p95), "{samples:?}");
    }

    #[test]
    fn median_and_p95() {
        check(&[3.0], 3.0, 3.0);
        check(&[2.0, 1.0], 1.5, 2.0);
        check(&[5.0, 1.0, 3.0], 3.0, 5.0);
        // 1..=20: the 95th percentile is the 19th value (0.95 * 20 = 19).
        let v: Vec<f64> = (1..=20).rev().map(f64::from).collect();
        check(&v, 10.5, 19.0);
        // 1..=100: 95th value.
        let v: Vec<f64> = (1..=100).map(f64::from).collect();
        check(&v, 50.5, 95.0);
        // 1..=30 (the bench's frame count): ceil(28.5) = 29th value.
        let v: Vec<f64> = (1..=30).map(f64::from).collect();
        check(&v, 15.5, 29.0);
    }

    #[test]
    fn non_finite_samples_are_dropped() {
        check(&[f64::NAN, 4.0, f64::INFINITY, 2.0], 3.0, 4.0);
        assert_eq!(Summary::of(&[]), None);
        assert_eq!(Summary::of(&[f64::NAN]), None);
        assert_eq!(median(&[7.0, 1.0, 4.0]), Some(4.0));
    }
}
