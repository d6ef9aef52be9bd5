//! Median and spread of a series of timings.

use serde::Serialize;

/// Median, extremes and the 10th / 90th percentiles of some milliseconds.
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct Spread {
    /// Middle value (mean of the two middle ones for an even count).
    pub median_ms: f64,
    /// Smallest value.
    pub min_ms: f64,
    /// 10th percentile (nearest rank).
    pub p10_ms: f64,
    /// 90th percentile (nearest rank).
    pub p90_ms: f64,
    /// Largest value.
    pub max_ms: f64,
    /// How many values.
    pub count: usize,
}

impl Spread {
    /// The spread of `values`, or `None` when there are none or one is not finite.
    pub fn of(values: &[f64]) -> Option<Self> {
        if values.is_empty() || values.iter().any(|v| !v.is_finite()) {
            return None;
        }
        let mut sorted = values.to_vec();
        sorted.sort_by(f64::total_cmp);
        let n = sorted.len();
        let median = if n % 2 == 1 {
            sorted[n / 2]
        } else {
            (sorted[n / 2 - 1] + sorted[n / 2]) / 2.0
        };
        let rank = |p: f64| sorted[((p * n as f64).ceil() as usize).clamp(1, n) - 1];
        Some(Self {
            median_ms: median,
            min_ms: sorted[0],
            p10_ms: rank(0.1),
            p90_ms: rank(0.9),
            max_ms: sorted[n - 1],
            count: n,
        })
    }
}

#[cfg(test)]
mod tests {
    use super::Spread;

    #[test]
    fn median_and_percentiles() {
        let values: Vec<f64> = (1..=10).rev().map(f64::from).collect();
        let spread = Spread::of(&values).unwrap();
        assert_eq!(spread.median_ms, 5.5);
        assert_eq!((spread.min_ms, spread.max_ms), (1.0, 10.0));
        assert_eq!((spread.p10_ms, spread.p90_ms), (1.0, 9.0));
        assert_eq!(Spread::of(&[3.0, 1.0, 2.0]).unwrap().median_ms, 2.0);
        assert_eq!(Spread::of(&[]), None);
        assert_eq!(Spread::of(&[1.0, f64::NAN]), None);
    }
}
