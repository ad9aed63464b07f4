//! A Lyapunov run paused and resumed ([`LyapunovRun::advance`]) computes the
//! same bits as the one-shot run ([`largest_exponent`]): the transient's
//! steady-state run, both trajectories' integrators, the sum of logarithms
//! and the period count all carry over a pause. The page's worker relies
//! on this to slice one Lyapunov point without changing what it shows.

// Tests may panic: that is how they fail.
#![allow(clippy::unwrap_used, clippy::expect_used, clippy::panic)]

use solver::lyapunov::{largest_exponent, Lyapunov, LyapunovOptions, LyapunovRun};
use solver::steady::Model;
use test_support::models::in_slices;

fn model() -> Model {
    test_support::models::model(&[])
}

/// Runs `opts` in slices of `slice` steps: the result, the number of pauses
/// and the steps taken; checks that no slice took more than `slice` steps.
fn sliced(
    model: &Model,
    opts: &LyapunovOptions,
    start: Option<&[f64]>,
    slice: u64,
) -> (Lyapunov, u64, u64) {
    let mut run = LyapunovRun::new(model, opts, start).expect("valid options");
    let (l, pauses) = in_slices(slice, |k| {
        let before = run.steps();
        let out = run.advance(model, k).expect("the run succeeds");
        (out, run.steps() - before)
    });
    (l, pauses, run.steps())
}

/// Bit-for-bit equality (f64's `==` would let -0 equal 0 and fail on NaN).
fn same_bits(a: &Lyapunov, b: &Lyapunov) -> bool {
    let bits = |v: &[f64]| v.iter().map(|x| x.to_bits()).collect::<Vec<_>>();
    a.omega.to_bits() == b.omega.to_bits()
        && a.per_period.to_bits() == b.per_period.to_bits()
        && a.per_s.to_bits() == b.per_s.to_bits()
        && bits(&a.running) == bits(&b.running)
        && bits(&a.end_state) == bits(&b.end_state)
}

#[test]
fn a_sliced_lyapunov_run_is_bit_identical_to_the_one_shot_run() {
    let m = model();
    // A stable period-1 orbit (settles early in the transient), a run with
    // no periodic motion (uses its whole transient) and one without any.
    for (omega, transient) in [(0.3, 60), (1.3, 150), (0.9, 0)] {
        let mut opts = LyapunovOptions::new(omega);
        opts.transient_periods = transient;
        opts.periods = 12;
        let whole = largest_exponent(&m, &opts, None).expect("one-shot run");
        assert!(whole.per_period.is_finite() && whole.running.len() == 12);
        let mut total = None;
        for slice in [1, 7, 3000, u64::MAX] {
            let (l, pauses, steps) = sliced(&m, &opts, None, slice);
            assert!(
                same_bits(&l, &whole),
                "Omega {omega}, slices of {slice} steps"
            );
            // Every slice but the last took the full `slice` steps.
            assert_eq!(pauses, steps.div_ceil(slice) - 1, "Omega {omega}");
            assert_eq!(*total.get_or_insert(steps), steps, "Omega {omega}");
        }
        assert!(
            total.is_some_and(|s| s > 3000),
            "Omega {omega}: the run fits one slice of 3000 steps ({total:?})"
        );
        // Continued from another run's end state, as the page's chains do.
        let from = largest_exponent(&m, &LyapunovOptions::new(omega * 1.05), None)
            .expect("start state")
            .end_state;
        let whole = largest_exponent(&m, &opts, Some(&from)).expect("continued run");
        for slice in [13, 3000] {
            let (l, _, _) = sliced(&m, &opts, Some(&from), slice);
            assert!(same_bits(&l, &whole), "Omega {omega} continued");
        }
    }
}

#[test]
fn a_finished_lyapunov_run_does_no_more_work_and_bad_options_are_refused() {
    let m = model();
    let mut opts = LyapunovOptions::new(0.8);
    opts.transient_periods = 5;
    opts.periods = 3;
    let mut run = LyapunovRun::new(&m, &opts, None).expect("valid options");
    assert!(!run.is_done());
    assert!(run.advance(&m, u64::MAX).expect("runs").is_some());
    assert!(run.is_done());
    let steps = run.steps();
    assert!(steps > 0);
    assert!(run.advance(&m, 100).expect("no error").is_none());
    assert_eq!(run.steps(), steps);
    // Bad options are refused when the run is made, naming the option.
    opts.periods = 0;
    let msg = LyapunovRun::new(&m, &opts, None)
        .expect_err("refused")
        .to_string();
    assert!(msg.contains("periods"), "{msg}");
}
