//! The largest Lyapunov exponent over Omega (`ViewId::Lyap`, under the
//! bifurcation diagram): the store that collects both chains' points, how
//! an exponent reads, and the exports.

use crate::protocol::LyapSample;

/// Lyapunov points as they arrive from both chains, for one job.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct LyapStore {
    /// Points in arrival order.
    pub points: Vec<LyapSample>,
    /// Points in all.
    pub total: usize,
    /// Periods each exponent averages over.
    pub periods: u32,
    /// The model is linear (no backlash): a positive exponent is growth of
    /// a parametric instability, never chaos.
    pub linear: bool,
}

impl LyapStore {
    /// An empty store for a new job.
    pub fn new(total: usize, periods: u32) -> Self {
        LyapStore {
            points: Vec::new(),
            total,
            periods,
            linear: false,
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

/// How an exponent of the map reads, with the thresholds of the steady
/// run's own probe, so that this view and the summary call the same
/// motion by the same name: below `-LYAP_ZERO_BAND` periodic, from
/// [`LAMBDA_MIN`] up chaotic (growth, for a linear model), between them
/// near zero.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum LyapKind {
    /// Negative: a stable periodic response.
    Periodic,
    /// About zero: quasi-periodic, at a bifurcation, or too weak to call.
    Neutral,
    /// Positive: chaos.
    Chaotic,
    /// Positive on a linear model: the motion grows without bound (a
    /// parametric instability of the mesh stiffness), which is not chaos.
    Growth,
}

impl LyapKind {
    /// The readings in the key's order.
    pub const ALL: [LyapKind; 4] = [
        LyapKind::Periodic,
        LyapKind::Neutral,
        LyapKind::Chaotic,
        LyapKind::Growth,
    ];

    /// The reading in the key's words.
    pub fn label(self) -> &'static str {
        match self {
            LyapKind::Periodic => "λ < 0: periodic (stable)",
            LyapKind::Neutral => "λ near 0: quasi-periodic or undecided",
            LyapKind::Chaotic => "λ > 0: chaotic",
            LyapKind::Growth => {
                "λ > 0: grows without bound (parametric instability; a linear system is not chaotic)"
            }
        }
    }
}

pub use solver::steady::LAMBDA_MIN;

/// Half-width of the band of exponents read as zero (per mesh period): an
/// average over ~100 periods is not sharper than this.
pub const LYAP_ZERO_BAND: f64 = 0.01;

/// Reads an exponent per mesh period of a model, linear or not.
pub fn lyap_kind(per_period: f64, linear: bool) -> LyapKind {
    if linear && per_period > LYAP_ZERO_BAND {
        LyapKind::Growth
    } else if per_period >= LAMBDA_MIN {
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
        assert_eq!(lyap_kind(-0.3, false), LyapKind::Periodic);
        assert_eq!(lyap_kind(0.001, false), LyapKind::Neutral);
        assert_eq!(lyap_kind(0.03, false), LyapKind::Neutral);
        assert_eq!(lyap_kind(0.2, false), LyapKind::Chaotic);
        assert_eq!(lyap_kind(0.2, true), LyapKind::Growth);
        assert_eq!(lyap_kind(-0.2, true), LyapKind::Periodic);
    }

    #[test]
    fn exports_match_the_cli_formats() {
        let mut l = LyapStore::new(2, 100);
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
