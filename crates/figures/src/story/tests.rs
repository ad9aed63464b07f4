//! No sentence contradicts the classification: every text the page shows
//! about a steady state, for every verdict, regime and backlash, checked
//! against what the verdict and the backlash allow a sentence to say.

use super::*;
use crate::protocol::OmegaResult;
use crate::views::test_support::omega_result;

/// Every verdict the solver can give.
fn verdicts() -> Vec<Motion> {
    vec![
        Motion::PeriodicExact {
            period: 1,
            max_multiplier_modulus: 0.97,
            newton_iterations: 0,
        },
        Motion::PeriodicExact {
            period: 2,
            max_multiplier_modulus: 0.5,
            newton_iterations: 0,
        },
        Motion::Periodic { period: 1 },
        Motion::Periodic { period: 3 },
        Motion::StillSettling { period: 11 },
        Motion::PeriodAboveMaximum { period: 40 },
        Motion::Periodic { period: 12 },
        Motion::NotPeriodic,
    ]
}

/// Every text the page shows about one steady state: the expert summary,
/// the student summary, the selected-Omega views' text alternative, the
/// Poincaré key, a family panel's title and the bifurcation diagram's
/// text alternative.
fn texts(r: &OmegaResult) -> Vec<String> {
    let mut bif = crate::views::bif::BifStore::new(1).view(
        Some(0),
        &[r.backlash_um],
        &crate::views::test_support::ctx(),
    );
    bif.points.push(crate::views::bif::BifPoint {
        omega: r.omega,
        x_um: 1.0,
        regime: r.regime,
        up: true,
    });
    bif.motions.push((r.omega, true, r.motion));
    vec![
        crate::views::omega::summary_line(r, &[]),
        crate::views::omega::student_summary(r),
        crate::views::labels::omega_label("Phase portrait", r),
        crate::plots::poincare_key(r),
        format!("TE 5 µm: {}", motion_tag_short(r.motion)),
        crate::views::labels::bif_label(&bif),
    ]
}

/// Whether `text` says "period {n}" (not "period {n}0").
fn says_period(text: &str, n: u32) -> bool {
    let p = format!("period {n}");
    text.match_indices(&p).any(|(i, _)| {
        !text[i + p.len()..]
            .chars()
            .next()
            .is_some_and(|c| c.is_ascii_digit())
    })
}

/// The phrases a text may not contain, and one of which it must contain,
/// for verdict `m`: derived from what each verdict means, not from the
/// functions under test.
fn allowed(m: Motion) -> (Vec<&'static str>, Vec<String>) {
    let aperiodic = vec![
        "not periodic",
        "does not repeat",
        "quasi-periodic",
        "chaotic",
    ];
    match m {
        Motion::PeriodicExact { period, .. } => {
            let mut no = aperiodic;
            no.extend(["settling", "nearly"]);
            (
                no,
                vec![format!("period {period} (exact)"), "exactly".into()],
            )
        }
        Motion::Periodic { period } => {
            let mut no = aperiodic;
            no.extend(["exact", "settling"]);
            (no, vec![format!("period {period}")])
        }
        Motion::StillSettling { .. } => {
            let mut no = aperiodic;
            no.extend(["exact", "repeats every"]);
            (no, vec!["settling".into(), "*".into()])
        }
        Motion::PeriodAboveMaximum { .. } => {
            let mut no = aperiodic;
            no.extend(["exact", "repeats every"]);
            (
                no,
                vec![format!("above {MAX_PERIOD}"), format!("({MAX_PERIOD})")],
            )
        }
        Motion::NotPeriodic => (
            vec!["repeats every", "repeats exactly", "exact", "settling"],
            vec!["not periodic".into(), "does not repeat".into()],
        ),
    }
}

#[test]
fn no_sentence_contradicts_the_classification() {
    for m in verdicts() {
        for regime in Regime::ALL {
            for backlash_um in [0.0, 100.0] {
                let mut r = omega_result();
                r.motion = m;
                r.period = m.period();
                r.regime = regime;
                r.backlash_um = backlash_um;
                let (never, one_of) = allowed(m);
                for t in texts(&r) {
                    let case = format!("{m:?}, {regime:?}, b {backlash_um}: {t}");
                    for w in &never {
                        assert!(!t.contains(w), "says {w:?}: {case}");
                    }
                    assert!(one_of.iter().any(|w| t.contains(w.as_str())), "{case}");
                    // A period is said only where the verdict has it.
                    for n in 1..=40 {
                        if says_period(&t, n) {
                            let own = match m {
                                Motion::PeriodicExact { period, .. }
                                | Motion::Periodic { period }
                                | Motion::StillSettling { period }
                                | Motion::PeriodAboveMaximum { period } => period,
                                Motion::NotPeriodic => 0,
                            };
                            assert_eq!(n, own, "another period: {case}");
                        }
                    }
                }
            }
        }
    }
}

/// Impact words follow the backlash: a mesh without backlash has no gap,
/// never impacts and never separates; one with backlash names its regime.
#[test]
fn impact_words_follow_the_backlash() {
    for m in verdicts() {
        for regime in Regime::ALL {
            let mut r = omega_result();
            r.motion = m;
            r.period = m.period();
            r.regime = regime;
            r.backlash_um = 0.0;
            for t in texts(&r)
                .into_iter()
                .take(3)
                .chain([crate::views::labels::omega_label("Time history", &r)])
            {
                for w in [
                    "cross",
                    "impact",
                    "hit",
                    "strike",
                    "separate and",
                    "no contact",
                ] {
                    assert!(!t.contains(w), "says {w:?} without backlash: {t}");
                }
                assert!(t.contains("no gap"), "{t}");
            }
            r.backlash_um = 40.0;
            let summary = crate::views::omega::summary_line(&r, &[]);
            assert!(summary.contains(regime.label()), "{summary}");
            if regime != Regime::NoGap {
                assert!(!summary.contains("no gap"), "{summary}");
            }
        }
    }
}

/// The expert summary gives an exact orbit's largest Floquet multiplier,
/// and only an exact orbit's.
#[test]
fn only_an_exact_orbit_has_a_multiplier() {
    for m in verdicts() {
        let mut r = omega_result();
        r.motion = m;
        let s = crate::views::omega::summary_line(&r, &[]);
        assert_eq!(s.contains("Floquet multiplier"), m.is_exact(), "{s}");
    }
}

/// Where the steady state found and the frequency response's branch tell
/// different stories, one sentence says both; where they agree, nothing
/// is added.
#[test]
fn the_branch_and_the_steady_state_are_joined_in_one_sentence() {
    use crate::story::{branch_agreement, BranchAt};
    for m in verdicts() {
        for at in [BranchAt::Stable, BranchAt::Unstable, BranchAt::NotCovered] {
            let s = branch_agreement(m, at);
            let periodic_stable =
                m.is_exact() || matches!(m, Motion::Periodic { period } if period > 1);
            let expect = match at {
                BranchAt::NotCovered => false,
                BranchAt::Unstable => periodic_stable,
                BranchAt::Stable => {
                    m.period().is_none() || matches!(m, Motion::StillSettling { .. })
                }
            };
            assert_eq!(s.is_some(), expect, "{m:?} {at:?}: {s:?}");
            if let (Some(s), Some(p)) = (&s, m.period()) {
                assert!(
                    s.contains(&format!("period-{p}")) || s.contains(&format!("period {p}")),
                    "{s}"
                );
            }
        }
    }
}
