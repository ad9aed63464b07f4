//! One story: every phrase the page says about a steady state, built from
//! its one classification ([`Motion`]: the solver's verdict) and its
//! impact regime read against the mesh's backlash. The summary, the keys,
//! the panel titles and the text alternatives all take their words from
//! here, so that no sentence can say "repeats every mesh period" while
//! another says "does not repeat", and no mesh without backlash is said to
//! cross one.

use crate::protocol::{Motion, Regime};
use solver::steady::MAX_PERIOD;

/// A backlash (µm) below this counts as none: the mesh is a linear spring.
const NO_BACKLASH_UM: f64 = 1e-6;

/// Whether a mesh of backlash half-width `backlash_um` has any backlash.
pub fn has_backlash(backlash_um: f64) -> bool {
    backlash_um.abs() >= NO_BACKLASH_UM
}

/// The motion's period in a few words, for titles, keys and labels:
/// "period 1 (exact)", "period 2", "period 11 (still settling)", "repeats
/// after 40 periods (above 16)", "not periodic".
pub fn motion_tag(m: Motion) -> String {
    match m {
        Motion::PeriodicExact { period, .. } => format!("period {period} (exact)"),
        Motion::Periodic { period } => format!("period {period}"),
        Motion::StillSettling { period } => format!("period {period} (still settling)"),
        Motion::PeriodAboveMaximum { period } => {
            format!("repeats after {period} periods (above {MAX_PERIOD})")
        }
        Motion::NotPeriodic => "not periodic".into(),
    }
}

/// The motion's period for a small panel's title: [`motion_tag`] with the
/// still-settling words shortened to a star (the key explains it).
pub fn motion_tag_short(m: Motion) -> String {
    match m {
        Motion::StillSettling { period } => format!("period {period}*"),
        Motion::PeriodAboveMaximum { .. } => format!("period above {MAX_PERIOD}"),
        m => motion_tag(m),
    }
}

/// What the star of [`motion_tag_short`] means, for a key.
pub const STILL_SETTLING_KEY: &str =
    "*: still settling, more transient periods may show another period";

/// Whether the motion repeats, as the student summary says it, after
/// `periods_run` transient periods.
pub fn motion_sentence(m: Motion, periods_run: u32) -> String {
    let every = |n: u32| {
        if n == 1 {
            "every mesh period".to_string()
        } else {
            format!("every {n} mesh periods")
        }
    };
    match m {
        Motion::PeriodicExact { period, .. } => format!(
            "the motion repeats exactly {} (period {period}: the periodic orbit itself was found, and it is stable)",
            every(period)
        ),
        Motion::Periodic { period } => format!(
            "the motion repeats {} within the recorded periods (period {period})",
            every(period)
        ),
        Motion::StillSettling { period } => format!(
            "the motion is still settling towards a repeat {} after {periods_run} transient periods, so more transient periods (in the settings) may show another period",
            every(period)
        ),
        Motion::PeriodAboveMaximum { period } => format!(
            "the motion repeats only after {period} mesh periods, longer than the longest period classified ({MAX_PERIOD})"
        ),
        Motion::NotPeriodic => {
            "the motion does not repeat within the recorded periods (quasi-periodic or chaotic)"
                .into()
        }
    }
}

/// The impact regime in a few words, read against the mesh's backlash:
/// without backlash the mesh is a linear spring and nothing impacts.
pub fn contact_tag(regime: Regime, backlash_um: f64) -> &'static str {
    if !has_backlash(backlash_um) {
        return Regime::NoGap.label();
    }
    regime.label()
}

/// What the teeth do, as the student summary says it.
pub fn contact_sentence(regime: Regime, backlash_um: f64) -> &'static str {
    let regime = if has_backlash(backlash_um) {
        regime
    } else {
        Regime::NoGap
    };
    match regime {
        Regime::NoGap => {
            "there is no backlash, so no gap: the teeth stay in contact, the mesh a linear spring"
        }
        Regime::NoImpact => "the teeth stay in contact all the time (no impact)",
        Regime::SingleSided => {
            "the teeth separate and strike the driving flank again (single-sided impact)"
        }
        Regime::DoubleSided => {
            "the teeth cross the whole backlash and also hit the back flank (double-sided impact)"
        }
        Regime::NoContact => "the teeth never touch (no contact)",
    }
}

/// What the frequency response's harmonic-balance branch says at one Ω:
/// the period-1 orbits it holds there.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum BranchAt {
    /// Some orbit the branch holds here is stable.
    Stable,
    /// The branch covers this Ω, but every orbit it holds here is unstable.
    Unstable,
    /// The branch does not reach this Ω (or is still computing).
    NotCovered,
}

/// The sentence that joins the steady state found at one Ω with what the
/// frequency response's branch says there, when they tell different
/// stories; `None` when they agree (or the branch has nothing to say).
/// Both are true at once: the branch holds the period-1 orbits, the run
/// finds the motion the gears reach from its start, and several motions
/// may coexist.
pub fn branch_agreement(m: Motion, branch: BranchAt) -> Option<String> {
    match (m, branch) {
        (Motion::PeriodicExact { period: 1, .. }, BranchAt::Unstable) => Some(
            "The frequency response's branch is unstable here, but shooting found this stable period-1 orbit: the gears follow the orbit found (drawn), which the harmonic balance misses or holds on another stretch.".into(),
        ),
        (Motion::PeriodicExact { period, .. }, BranchAt::Unstable) => Some(format!(
            "The frequency response's branch holds only period-1 orbits, unstable here: the gears settle on this stable period-{period} orbit instead."
        )),
        (Motion::Periodic { period }, BranchAt::Unstable) if period > 1 => Some(format!(
            "The frequency response's branch holds only period-1 orbits, unstable here: the gears move with period {period} instead."
        )),
        (
            Motion::NotPeriodic
            | Motion::PeriodAboveMaximum { .. }
            | Motion::StillSettling { .. },
            BranchAt::Stable,
        ) => Some(
            "The frequency response's branch holds a stable period-1 orbit here too: two motions coexist, and the run's start decided which one the gears reached (another start, or a sweep from the other side, may end on the branch).".into(),
        ),
        _ => None,
    }
}

#[cfg(test)]
mod tests;
