//! The largest Lyapunov exponent over Omega (`ViewId::Lyap`, under the
//! bifurcation diagram): the store that collects both chains' points, how
//! an exponent reads, and the exports.

use crate::protocol::LyapSample;

/// Lyapunov points as they arrive from both chains, for one job.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct LyapStore {
    /// The job (0: none, or the curve is off).
    pub id: u64,
    /// Points in arrival order.
    pub points: Vec<LyapSample>,
    /// Points in all.
    pub total: usize,
    /// Periods each exponent averages over.
    pub periods: u32,
}

impl LyapStore {
    /// An empty store for a new job.
    pub fn new(id: u64, total: usize, periods: u32) -> Self {
        LyapStore {
            id,
            points: Vec::new(),
            total,
            periods,
        }
    }

    /// Every point by rising Omega, whatever order the workers' chains
    /// delivered them in (so the exports are the same on any pool).
    fn by_omega(&self) -> Vec<&LyapSample> {
        let mut v: Vec<&LyapSample> = self.points.iter().collect();
        v.sort_by(|a, b| a.omega.total_cmp(&b.omega));
        v
    }

    /// The computed exponents per mesh period, sorted by Omega.
    pub fn curve(&self) -> Vec<(f64, f64)> {
        let mut v: Vec<(f64, f64)> = self
            .points
            .iter()
            .filter_map(|p| p.per_period.map(|l| (p.omega, l)))
            .filter(|(_, l)| l.is_finite())
            .collect();
        v.sort_by(|a, b| a.0.total_cmp(&b.0));
        v
    }

    /// The failed points (Omega, why).
    pub fn failed(&self) -> Vec<(f64, String)> {
        self.points
            .iter()
            .filter_map(|p| p.error.as_ref().map(|e| (p.omega, e.clone())))
            .collect()
    }
}

/// How an exponent of the map reads: the band around zero is
/// [`LYAP_ZERO_BAND`] wide on each side.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum LyapKind {
    /// Negative: a stable periodic response.
    Periodic,
    /// About zero: quasi-periodic (or at a bifurcation).
    Neutral,
    /// Positive: chaos.
    Chaotic,
}

/// Half-width of the band of exponents read as zero (per mesh period): an
/// average over ~100 periods is not sharper than this.
pub const LYAP_ZERO_BAND: f64 = 0.01;

/// Reads an exponent per mesh period.
pub fn lyap_kind(per_period: f64) -> LyapKind {
    if per_period > LYAP_ZERO_BAND {
        LyapKind::Chaotic
    } else if per_period < -LYAP_ZERO_BAND {
        LyapKind::Periodic
    } else {
        LyapKind::Neutral
    }
}

/// The Lyapunov curve as CSV (the format of `gearshock lyapunov --format csv`).
pub fn lyap_csv(store: &LyapStore) -> String {
    let mut s = String::from("omega,exponent_per_period,exponent_per_s\n");
    for p in store.by_omega() {
        let f = |x: Option<f64>| x.map_or(String::new(), |v| v.to_string());
        s.push_str(&format!("{},{},{}\n", p.omega, f(p.per_period), f(p.per_s)));
    }
    s
}

/// The Lyapunov curve as JSON (field names as in `gearshock lyapunov`).
pub fn lyap_json(store: &LyapStore) -> serde_json::Value {
    let points: Vec<serde_json::Value> = store
        .by_omega()
        .into_iter()
        .map(|p| {
            serde_json::json!({
                "omega": p.omega,
                "exponent_per_period": p.per_period,
                "exponent_per_s": p.per_s,
                "error": p.error,
            })
        })
        .collect();
    serde_json::json!({ "periods": store.periods, "points": points })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn exponents_read_by_sign() {
        assert_eq!(lyap_kind(-0.3), LyapKind::Periodic);
        assert_eq!(lyap_kind(0.001), LyapKind::Neutral);
        assert_eq!(lyap_kind(0.2), LyapKind::Chaotic);
    }

    #[test]
    fn exports_match_the_cli_formats() {
        let mut l = LyapStore::new(3, 2, 100);
        l.points.push(LyapSample {
            index: 0,
            omega: 0.5,
            per_period: Some(-0.25),
            per_s: Some(-100.0),
            error: None,
        });
        assert_eq!(
            lyap_csv(&l),
            "omega,exponent_per_period,exponent_per_s\n0.5,-0.25,-100\n"
        );
        assert_eq!(lyap_json(&l)["points"][0]["exponent_per_s"], -100.0);
    }
}
