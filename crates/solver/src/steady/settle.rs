//! The transient's tests on the Poincaré points: the early-settle test,
//! the period of a recorded window, and the deflections' running range
//! that sets their tolerance.

use super::MAX_PERIOD;
use crate::fastmath::{max, min};

fn dist_inf(a: &[f64], b: &[f64]) -> f64 {
    // fastmath::max: with f64::max this was a call per entry in wasm32.
    a.iter().zip(b).map(|(x, y)| (x - y).abs()).fold(0.0, max)
}

/// Distances between Poincaré points `p` apart used by the settle test.
pub(super) const SETTLE_DISTANCES: usize = 5;

/// The early-settle test on the last Poincaré points (newest last).
///
/// For each candidate period `p`, with `d_k` the distance between points `p`
/// apart (`d_0` newest, `k < 5`), the contraction per `p` periods is taken as
/// the worst of the observed ratios `d_k / d_(k+1)` (those above the noise
/// level `tol / 1000`) and of the slowest modal decay `rho_modal(p)` of the
/// linearized system; the transient has settled when the geometric bound
/// `d_0 rho / (1 - rho)` on the remaining drift is below `tol / 2`.
///
/// Why both: several modes decaying at once make the observed ratios beat,
/// and a lightly damped mode that turns by nearly a whole number of turns in
/// `p` periods hardly shows in `p`-step differences at all (its share of
/// `d_k` is scaled by `2 |sin(p theta / 2)|`) while it still holds most of the
/// remaining error. The modal floor keeps the bound honest for it.
pub(super) fn has_settled(hist: &[Vec<f64>], tol: f64, rho_modal_per_period: f64) -> bool {
    let n = hist.len();
    let noise = 1e-3 * tol;
    (1..=8).any(|p| {
        if n < SETTLE_DISTANCES * p + 1 {
            return false;
        }
        let d: Vec<f64> = (0..SETTLE_DISTANCES)
            .map(|k| dist_inf(&hist[n - 1 - k * p], &hist[n - 1 - (k + 1) * p]))
            .collect();
        if d[0] > tol {
            return false;
        }
        let observed = d
            .windows(2)
            .filter(|w| w[0] > noise || w[1] > noise)
            .map(|w| {
                if w[1] > 0.0 {
                    w[0] / w[1]
                } else {
                    f64::INFINITY
                }
            })
            .fold(0.0, f64::max);
        let rho = observed.max(rho_modal_per_period.powi(p as i32));
        rho < 1.0 && d[0] * rho / (1.0 - rho) <= 0.5 * tol
    })
}

/// Smallest `p` such that every recorded Poincaré point repeats after `p`
/// periods within `tol` (um); at least three repetitions must be seen.
pub(crate) fn detect_period(points: &[Vec<f64>], tol: f64) -> Option<u32> {
    let n = points.len();
    (1..=MAX_PERIOD.min(n / 3))
        .find(|&p| (0..n - p).all(|i| dist_inf(&points[i], &points[i + p]) <= tol))
        .map(|p| p as u32)
}

/// Running range of all mesh deflections (for the settle tolerance).
#[derive(Debug, Clone)]
pub(super) struct SpanTracker {
    lo: Vec<f64>,
    hi: Vec<f64>,
}

impl SpanTracker {
    pub(super) fn new(n: usize) -> Self {
        SpanTracker {
            lo: vec![f64::INFINITY; n],
            hi: vec![f64::NEG_INFINITY; n],
        }
    }
    pub(super) fn add(&mut self, deflections: &[f64]) {
        for (j, &d) in deflections.iter().enumerate() {
            self.lo[j] = min(self.lo[j], d);
            self.hi[j] = max(self.hi[j], d);
        }
    }
    pub(super) fn span_um(&self) -> f64 {
        self.lo
            .iter()
            .zip(&self.hi)
            .map(|(l, h)| h - l)
            .filter(|d| d.is_finite())
            .fold(0.0, f64::max)
            * 1e6
    }
    pub(super) fn reset_keep_last(&mut self) {
        // The span of the latest period only: the transient's start must not
        // inflate the tolerance.
        self.lo.fill(f64::INFINITY);
        self.hi.fill(f64::NEG_INFINITY);
    }
}
