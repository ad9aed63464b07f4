//! The pipeline's fallback, driven directly: a shooting attempt that does
//! not converge hands the run back to integration and is said in the note.

use super::*;
use crate::params::ModelParams;
use crate::shooting::{ShootFailure, ShootOutcome};
use crate::steady::verdict::PIPELINE_ITERATIONS;

/// A failed attempt (as Newton reports one) at the default set's chaotic
/// Omega 0.84: the run integrates on (recording beside the Lyapunov
/// probe), its verdict is not periodic with a positive exponent, and the
/// note says that shooting did not converge; no orbit is shown.
#[test]
fn a_failed_shooting_attempt_falls_back_to_integration_and_says_so() {
    let model = Model::new(&ModelParams::default()).expect("default model");
    let opts = SteadyOptions::new(0.84);
    let mut run = SteadyRun::new(&model, &opts, None).expect("valid options");
    let failed = ShootOutcome::Failed(ShootFailure {
        period: 3,
        iterations: PIPELINE_ITERATIONS,
        residual_um: 2.5,
        reason: "Newton did not converge in 8 iterations".into(),
        steps: 0,
    });
    run.after_shooting(&model, failed, 3, false)
        .expect("the fallback starts");
    assert!(run.shooting.exact.is_none());
    assert!(matches!(
        run.phase,
        Phase::Record { .. } | Phase::Transient { .. }
    ));
    let ss = loop {
        if let Some(ss) = run.advance(&model, u64::MAX).expect("the run succeeds") {
            break ss;
        }
    };
    assert!(!ss.motion.is_exact(), "{:?}", ss.motion);
    assert_eq!(ss.motion, Motion::NotPeriodic);
    let note = ss.shooting_note.clone().expect("a note");
    assert!(note.contains("period-3 orbit did not converge"), "{note}");
    let ev = ss.lyapunov.expect("the probe's evidence");
    assert!(ev.chaotic && ev.per_period > LAMBDA_MIN, "{ev:?}");
    assert!(ss.verdict().contains("chaotic"), "{}", ss.verdict());
}

/// A failed attempt to confirm a recorded window (the gear pair at Omega
/// 0.84 after a 4-period transient, whose window is still settling towards
/// period 2): the window is reported as it was recorded, its verdict and
/// its transient count unchanged, and the note says what shooting did.
#[test]
fn a_failed_confirmation_reports_the_window_as_recorded() {
    let model =
        Model::new(&ModelParams::defaults(crate::params::ModelKind::GearPair)).expect("gear pair");
    let mut opts = SteadyOptions::new(0.84);
    opts.transient_periods = 4;
    let mut run = SteadyRun::new(&model, &opts, None).expect("valid options");
    while run.window.is_none() {
        assert!(
            run.advance(&model, 1).expect("the run succeeds").is_none(),
            "the run ended before shooting from its window"
        );
    }
    assert!(matches!(run.phase, Phase::Shoot { period: 2, .. }));
    assert_eq!(run.periods_run, 104);
    let failed = ShootOutcome::Failed(ShootFailure {
        period: 2,
        iterations: PIPELINE_ITERATIONS,
        residual_um: 0.5,
        reason: "Newton did not converge in 8 iterations".into(),
        steps: 0,
    });
    run.after_shooting(&model, failed, 2, false)
        .expect("the window is kept");
    assert!(matches!(run.phase, Phase::Finish { .. }));
    let ss = run
        .advance(&model, 1)
        .expect("the run succeeds")
        .expect("the window is the result at once");
    assert_eq!(ss.motion, Motion::StillSettling { period: 2 });
    assert_eq!(ss.stats.transient_periods_run, 4);
    assert_eq!(ss.meshes[0].poincare_delta_m.len(), 100);
    let note = ss.shooting_note.clone().expect("a note");
    assert!(
        note.contains("after 104 periods for a period-2 orbit did not converge"),
        "{note}"
    );
    assert!(ss
        .verdict()
        .starts_with("still settling towards period 2 after 4 transient periods"));
}
