//! The harmonic-balance continuation on the settings a user reaches with the
//! page's sliders: backlash 0, 20, 50, 100, 200 um x TE 0, 20, 60 um x mesh
//! damping ratio 0.02, 0.06 over Omega 0.1..2 at H = 5 with the default
//! (exact) method. Every branch finishes without error and covers the whole
//! range: by pieces, with automatic restarts where a piece cannot go on,
//! or by reported left-out intervals (poles of the linear mesh's response,
//! tangles of folds), each restart and interval with a note.

// Tests may panic: that is how they fail.
#![allow(clippy::unwrap_used, clippy::expect_used, clippy::panic)]

use solver::hbm::{BranchPoint, FrfContinuation, FrfSpec, LeftOutReason};
use test_support::models::model;

/// Runs one case; returns the branch and the continuation.
fn run(b: f64, te: f64, zeta: f64, points: u32) -> (Vec<BranchPoint>, FrfContinuation) {
    let m = model(&[
        &format!("backlash_um={b}"),
        &format!("te_um={te}"),
        &format!("damping_ratio={zeta}"),
    ]);
    let spec = FrfSpec::new(0.1, 2.0, points);
    let mut c = FrfContinuation::new(&m, spec).expect("spec");
    let mut out = Vec::new();
    while !c.is_finished() {
        match c.advance(64) {
            Ok(p) => out.extend(p),
            Err(e) => panic!("backlash {b} um, TE {te} um, damping {zeta}: {e}"),
        }
    }
    (out, c)
}

#[test]
fn every_branch_of_the_slider_grid_covers_the_range() {
    let mut restarted = 0;
    let mut total_points = 0;
    for zeta in [0.02, 0.06] {
        for b in [0.0, 20.0, 50.0, 100.0, 200.0] {
            for te in [0.0, 20.0, 60.0] {
                let case = format!("backlash {b} um, TE {te} um, damping {zeta}");
                let (pts, c) = run(b, te, zeta, 150);
                total_points += pts.len();
                assert!(c.is_finished(), "{case}");
                assert!(!c.left_at_start(), "{case}: rest of the range not reached");
                // The pieces together cover the range: the first piece
                // starts at 0.1, and every Omega is between two
                // consecutive points of some piece.
                let covered = |omega: f64| {
                    pts.windows(2).any(|w| {
                        w[0].piece == w[1].piece
                            && (w[0].omega - omega) * (w[1].omega - omega) <= 0.0
                    })
                };
                for i in 0..=190 {
                    let omega = 0.1 + 0.01 * f64::from(i);
                    let omega = omega.min(2.0);
                    // A pole of the periodic response is covered from both
                    // sides, up to the divergence threshold.
                    let left_out = c
                        .left_out()
                        .iter()
                        .any(|l| l.from <= omega && omega <= l.to);
                    assert!(
                        left_out || covered(omega),
                        "{case}: Omega {omega} not covered"
                    );
                }
                // What is left out is reported and bounded: poles only where
                // the mesh is linear (no backlash), each a small fraction of
                // the range; tangles of folds narrower than 15 % of it.
                let mut tangled = 0.0;
                for l in c.left_out() {
                    match l.reason {
                        LeftOutReason::Unbounded => {
                            assert!(b == 0.0 && l.to - l.from < 1e-3, "{case}: {l:?}");
                        }
                        LeftOutReason::Tangle => tangled += l.to - l.from,
                        LeftOutReason::NotFollowed | LeftOutReason::RestartsUsed => {
                            panic!("{case}: {l:?} is shooting's")
                        }
                    }
                }
                assert!(tangled < 0.15 * 1.9, "{case}: {tangled} of Omega left out");
                // Restarts are reported, with a note each, and the pieces
                // are numbered in order.
                assert_eq!(
                    c.notes().len(),
                    c.restarts().len() + c.left_out().len(),
                    "{case}"
                );
                let last_piece = pts.last().map_or(0, |p| p.piece);
                // (A restart whose start failed has no points.)
                assert!(last_piece as usize <= c.restarts().len(), "{case}");
                assert!(pts.windows(2).all(|w| w[0].piece <= w[1].piece), "{case}");
                if !c.restarts().is_empty() {
                    restarted += 1;
                    eprintln!("{case}: {:?}", c.notes());
                }
                eprintln!("{case}: {} points", pts.len());
            }
        }
    }
    eprintln!("{restarted} of 30 cases restarted, {total_points} points in all");
}
