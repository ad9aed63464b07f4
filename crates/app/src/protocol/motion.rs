//! The classification of a steady state as the page receives it: the
//! solver's [`solver::steady::Motion`] in a serializable form. Every
//! sentence the page says about whether a motion repeats is built from it
//! (`crate::story`), so the summary, the keys, the panel titles and the
//! text alternatives cannot contradict each other.

use serde::{Deserialize, Serialize};
use solver::steady::Motion;

/// How a steady state was classified (the solver's `Motion`).
#[derive(Debug, Clone, Copy, PartialEq, Default, Serialize, Deserialize)]
#[serde(tag = "kind", rename_all = "kebab-case")]
pub enum MotionClass {
    /// A periodic orbit found by shooting, and stable.
    PeriodicExact {
        /// Period in mesh periods.
        period: u32,
        /// The largest Floquet multiplier's modulus (below 1).
        max_multiplier_modulus: f64,
    },
    /// The recorded samples repeat after `period` mesh periods; no orbit
    /// was confirmed by shooting.
    Periodic {
        /// Period in mesh periods.
        period: u32,
    },
    /// The samples repeat only after more mesh periods than are classified.
    PeriodAboveMaximum {
        /// The shortest repeat found.
        period: u32,
    },
    /// The samples still approach a repeat of `period` mesh periods when
    /// the transient budget ran out.
    StillSettling {
        /// The period they approach.
        period: u32,
    },
    /// No repeat within the recorded periods.
    #[default]
    NotPeriodic,
}

impl MotionClass {
    /// The period, where the motion has one within the maximum.
    pub fn period(self) -> Option<u32> {
        match self {
            MotionClass::PeriodicExact { period, .. } | MotionClass::Periodic { period } => {
                Some(period)
            }
            _ => None,
        }
    }

    /// Whether the orbit was found by shooting.
    pub fn is_exact(self) -> bool {
        matches!(self, MotionClass::PeriodicExact { .. })
    }

    /// The solver's name for it (as in the CLI's JSON `motion`).
    pub fn name(self) -> &'static str {
        match self {
            MotionClass::PeriodicExact { .. } => "periodic-exact",
            MotionClass::Periodic { .. } => "periodic",
            MotionClass::PeriodAboveMaximum { .. } => "period-above-maximum",
            MotionClass::StillSettling { .. } => "still-settling",
            MotionClass::NotPeriodic => "not-periodic",
        }
    }
}

impl From<&Motion> for MotionClass {
    fn from(m: &Motion) -> Self {
        match *m {
            Motion::PeriodicExact {
                period,
                max_multiplier_modulus,
                ..
            } => MotionClass::PeriodicExact {
                period,
                max_multiplier_modulus,
            },
            Motion::Periodic { period } => MotionClass::Periodic { period },
            Motion::PeriodAboveMaximum { period } => MotionClass::PeriodAboveMaximum { period },
            Motion::StillSettling { period } => MotionClass::StillSettling { period },
            Motion::NotPeriodic => MotionClass::NotPeriodic,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Every solver verdict keeps its name and period through the page's
    /// form and through JSON.
    #[test]
    fn the_solver_verdict_survives_the_boundary() {
        let all = [
            Motion::PeriodicExact {
                period: 2,
                max_multiplier_modulus: 0.5,
                newton_iterations: 3,
            },
            Motion::Periodic { period: 3 },
            Motion::PeriodAboveMaximum { period: 40 },
            Motion::StillSettling { period: 11 },
            Motion::NotPeriodic,
        ];
        for m in &all {
            let c = MotionClass::from(m);
            assert_eq!(c.name(), m.name());
            assert_eq!(c.period(), m.period());
            assert_eq!(c.is_exact(), m.is_exact());
            let back: MotionClass =
                serde_json::from_str(&serde_json::to_string(&c).unwrap()).unwrap();
            assert_eq!(back, c);
        }
    }
}
