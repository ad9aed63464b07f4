//! A steady-state run paused and resumed ([`SteadyRun::advance`]) computes
//! the same bits as the one-shot run ([`steady_state`]): the integrator's
//! state, the settle test's history and the recorder all carry over a pause.
//! The page's worker relies on this to slice one steady state without
//! changing what it shows.

// Tests may panic: that is how they fail.
#![allow(clippy::unwrap_used, clippy::expect_used, clippy::panic)]

use solver::steady::{steady_state, Model, SteadyOptions, SteadyRun, SteadyState};
use test_support::models::in_slices;

fn model() -> Model {
    test_support::models::model(&[])
}

/// Runs `opts` in slices of `slice` steps: the result and the number of
/// pauses; checks that no slice took more than `slice` steps.
fn sliced(
    model: &Model,
    opts: &SteadyOptions,
    start: Option<&[f64]>,
    slice: u64,
) -> (SteadyState, u64) {
    let mut run = SteadyRun::new(model, opts, start).expect("valid options");
    in_slices(slice, |k| {
        let before = run.steps();
        let out = run.advance(model, k).expect("the run succeeds");
        (out, run.steps() - before)
    })
}

#[test]
fn a_sliced_run_is_bit_identical_to_the_one_shot_run() {
    let m = model();
    // Rattling near the main resonance (settles early) and a run that must
    // use its whole transient, with histories of every mesh and samples.
    for (omega, transient, early) in [(1.0, 300, true), (0.45, 40, false), (1.6, 0, true)] {
        let mut opts = SteadyOptions::new(omega);
        opts.transient_periods = transient;
        opts.record_periods = 12;
        opts.early_settle = early;
        opts.samples_per_period = 32;
        opts.history_meshes = (0..m.system.meshes.len()).collect();
        let whole = steady_state(&m, &opts, None).expect("one-shot run");
        for slice in [1, 7, 250] {
            let (ss, pauses) = sliced(&m, &opts, None, slice);
            assert_eq!(ss, whole, "Omega {omega}, slices of {slice} steps");
            // Every slice but the last took the full `slice` steps (the
            // run's own, shooting's and the Lyapunov probe's).
            let st = whole.stats;
            let steps = st.integrator.steps + st.shooting_steps + st.probe_steps;
            assert_eq!(pauses, steps.div_ceil(slice) - 1, "Omega {omega}");
        }
        // Continued from another run's end state, as the sweeps do.
        let from = steady_state(&m, &SteadyOptions::new(omega * 1.05), None)
            .expect("start state")
            .end_state;
        let whole = steady_state(&m, &opts, Some(&from)).expect("continued run");
        let (ss, _) = sliced(&m, &opts, Some(&from), 13);
        assert_eq!(ss, whole, "Omega {omega} continued");
    }
}

/// The gear pair at Omega 0.84 with a 4-period transient: the recorded
/// window is still settling, shooting from its end confirms the period-2
/// orbit and the run records it afresh; paused anywhere in that, the run
/// computes the same bits.
#[test]
fn a_window_confirmed_by_shooting_is_bit_identical_in_slices() {
    let m = solver::Model::new(&solver::params::ModelParams::defaults(
        solver::params::ModelKind::GearPair,
    ))
    .expect("gear pair");
    let mut opts = SteadyOptions::new(0.84);
    opts.transient_periods = 4;
    let whole = steady_state(&m, &opts, None).expect("one-shot run");
    assert!(whole.motion.is_exact(), "{}", whole.verdict());
    assert_eq!(whole.stats.transient_periods_run, 104);
    for slice in [1, 9, 400] {
        let (ss, _) = sliced(&m, &opts, None, slice);
        assert_eq!(ss, whole, "slices of {slice} steps");
    }
}

#[test]
fn a_finished_or_failed_run_does_no_more_work() {
    let m = model();
    let mut opts = SteadyOptions::new(0.8);
    opts.transient_periods = 5;
    opts.record_periods = 2;
    let mut run = SteadyRun::new(&m, &opts, None).expect("valid options");
    assert!(run.advance(&m, u64::MAX).expect("runs").is_some());
    assert!(run.is_done());
    let steps = run.steps();
    assert!(run.advance(&m, 100).expect("no error").is_none());
    assert_eq!(run.steps(), steps);

    // A step budget too small for one period fails as the one-shot run does.
    opts.max_steps_per_period = 3;
    let whole = steady_state(&m, &opts, None)
        .expect_err("too few steps")
        .to_string();
    let mut run = SteadyRun::new(&m, &opts, None).expect("valid options");
    let err = loop {
        match run.advance(&m, 2) {
            Ok(None) => {}
            Ok(Some(_)) => panic!("a run with 3 steps per period finished"),
            Err(e) => break e.to_string(),
        }
    };
    assert_eq!(err, whole);
    assert!(run.is_done());
    // Bad options are refused when the run is made, naming the option.
    opts.record_periods = 0;
    let msg = SteadyRun::new(&m, &opts, None)
        .expect_err("refused")
        .to_string();
    assert!(msg.contains("record-periods"), "{msg}");
}
