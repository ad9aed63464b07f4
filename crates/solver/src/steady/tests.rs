//! The pipeline's fallback, driven directly: a shooting attempt that does
//! not converge hands the run back to integration and is said in the note.

use super::*;
use crate::params::ModelParams;
use crate::shooting::{ShootFailure, ShootOutcome};

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
    assert!(run.exact.is_none());
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
