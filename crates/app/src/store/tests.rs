//! The computation's tests: a reply changes only the computation whose
//! current job it answers, and says what changed.

use super::*;
use crate::store::status::JobStatus;
use figures::protocol::{BifMesh, BifSample, HbmMesh, HbmSample, JobKind, KindSet, Regime};

fn branch(omegas: &[f64]) -> Vec<HbmSample> {
    omegas
        .iter()
        .map(|&omega| HbmSample {
            omega,
            meshes: vec![HbmMesh {
                rel_min_um: 1.0,
                rel_max_um: 2.0,
                regime: Regime::NoImpact,
            }],
            stable: Some(true),
            bifurcation: None,
            piece: 0,
        })
        .collect()
}

fn sweep_point(index: u32) -> BifSample {
    BifSample {
        index,
        omega: 0.5,
        up: true,
        meshes: vec![BifMesh {
            x_um: vec![1.0],
            rel_min_um: 1.0,
            rel_max_um: 1.0,
            regime: Regime::NoImpact,
            dynamic_factor: None,
        }],
        worst_mesh: 0,
        period: Some(1),
        motion: figures::protocol::Motion::Periodic { period: 1 },
        error: None,
    }
}

/// A computation whose branch is job `hbm` and sweep job `bif` (2 points).
fn computation(hbm: u64, bif: u64) -> Computation {
    let mut c = Computation {
        hbm: HbmStore::new(5),
        bif: BifStore::new(2),
        ..Computation::default()
    };
    *c.status_mut(JobKind::HarmonicBalance) = JobStatus::start(hbm, 0.0, 100);
    *c.status_mut(JobKind::Bif) = JobStatus::start(bif, 0.0, 2);
    c
}

#[test]
fn a_reply_changes_only_the_computation_whose_job_it_answers() {
    let mut a = computation(1, 2);
    let mut b = computation(3, 4);
    let msg = FromWorker::HbmPoints {
        id: 3,
        points: branch(&[0.2, 0.4]),
        progress: 0.5,
        finished: false,
        error: None,
        notes: Vec::new(),
    };
    let mut dirty = Dirty::default();
    assert!(!a.feed(&msg, 10.0, 0.1, &mut dirty).matched);
    assert!(a.hbm.points.is_empty() && dirty.jobs.is_empty());
    assert!(b.feed(&msg, 10.0, 0.1, &mut dirty).matched);
    assert_eq!(b.hbm.points.len(), 2);
    assert_eq!(b.status(JobKind::HarmonicBalance).done, 50);
    assert_eq!(dirty.jobs, JobKind::HarmonicBalance.set());
    // Id 0 (an unreadable message's failure) answers no job.
    let zero = FromWorker::Failed {
        id: 0,
        message: "x".into(),
    };
    assert!(!b.feed(&zero, 11.0, 0.1, &mut dirty).matched);
    // A failure ends exactly the job it names.
    let failed = FromWorker::Failed {
        id: 4,
        message: "no sweep".into(),
    };
    let fed = b.feed(&failed, 12.0, 0.1, &mut dirty);
    assert!(fed.matched && fed.issues.is_empty());
    assert_eq!(b.status(JobKind::Bif).error.as_deref(), Some("no sweep"));
    assert!(b.status(JobKind::HarmonicBalance).error.is_none());
}

#[test]
fn a_failed_branch_is_partial_and_says_where_it_stopped() {
    let mut c = computation(1, 2);
    let msg = FromWorker::HbmPoints {
        id: 1,
        points: branch(&[0.2, 0.3]),
        progress: 0.3,
        finished: true,
        error: Some("the solver did not converge at Ω 0.31.".into()),
        notes: Vec::new(),
    };
    let fed = c.feed(&msg, 5.0, 0.1, &mut Dirty::default());
    assert_eq!(
        fed.issues,
        vec![
            "The frequency response stops at Ω 0.3: the solver did not converge at Ω 0.31. \
             The branch shown is partial."
                .to_string()
        ]
    );
    let st = c.status(JobKind::HarmonicBalance);
    assert_eq!(st.error.as_ref(), fed.issues.first());
    assert_eq!(st.finished_ms, Some(5.0));
    assert_eq!(c.hbm.points.len(), 2, "the points before the failure stay");
}

#[test]
fn without_an_overlay_the_sweeps_end_redraws_the_frequency_response() {
    let mut c = computation(1, 2);
    let mut dirty = Dirty::default();
    let first = FromWorker::BifPoints {
        id: 2,
        points: vec![sweep_point(0)],
    };
    c.feed(&first, 1.0, 0.1, &mut dirty);
    assert!(dirty.jobs.contains(JobKind::Bif));
    let last = FromWorker::BifPoints {
        id: 2,
        points: vec![sweep_point(1)],
    };
    let mut dirty = Dirty::default();
    c.feed(&last, 2.0, 0.1, &mut dirty);
    assert_eq!(dirty.jobs, KindSet::of(&[JobKind::Bif, JobKind::Overlay]));
    assert_eq!(c.status(JobKind::Bif).finished_ms, Some(2.0));
}
