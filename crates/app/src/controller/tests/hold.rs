//! The page's start: the jobs off the first screen wait until the
//! frequency response's branch and the selected Omega's steady state have
//! ended, then go to the same workers as without the wait.

use super::super::*;
use super::{hbm_points, posts, ready};

/// The messages of `p` that run a job, as (worker, kind).
fn runs(p: &[(usize, ToWorker)]) -> Vec<(usize, JobKind)> {
    p.iter()
        .filter_map(|(w, m)| match m {
            ToWorker::Run { job, .. } => Some((*w, job.kind())),
            _ => None,
        })
        .collect()
}

#[test]
fn the_jobs_off_the_first_screen_wait_for_the_first_screens_jobs() {
    // Without the wait: every job posted once the workers are ready.
    let (mut plain, _) = Controller::new("", 0.0);
    let all = ready(&mut plain);
    assert!(runs(&all).len() > 2, "{all:?}");

    let (mut c, fx) = Controller::new("", 0.0);
    assert!(fx.is_empty());
    c.hold_off_screen();
    let first = ready(&mut c);
    // Only the selected Omega (worker 0) and the branch (the last worker).
    assert_eq!(
        runs(&first),
        vec![
            (0, JobKind::Omega),
            (c.hbm_worker(), JobKind::HarmonicBalance)
        ]
    );
    // The steady state ends: the branch still runs, nothing more is posted.
    let omega = c.main.status(JobKind::Omega).id;
    let failed = encode(&FromWorker::Failed {
        id: omega,
        message: "no luck".into(),
    });
    assert!(c.worker_message(0, &failed, 5.0).is_empty());
    // A part of the branch: still nothing.
    let hbm = c.main.status(JobKind::HarmonicBalance).id;
    assert!(c
        .worker_message(1, &hbm_points(hbm, &[0.1, 0.2], false, None), 6.0)
        .is_empty());
    // The branch ends: the rest follows, the very messages the page
    // without the wait posted at once (the same jobs, ids and workers).
    let rest = posts(&c.worker_message(1, &hbm_points(hbm, &[0.3], true, None), 7.0));
    let mut both = first.clone();
    both.extend(rest.iter().cloned());
    let text = |p: &[(usize, ToWorker)]| {
        let mut t: Vec<(usize, String)> = p.iter().map(|(w, m)| (*w, encode(m))).collect();
        t.sort();
        t
    };
    assert_eq!(text(&both), text(&all));
    assert!(rest.iter().all(|(_, m)| matches!(m, ToWorker::Run { .. })));
    // Nothing is held any more: a new job of the map goes out at once.
    let fx = posts(&c.set_key("map_value_points", "10", 8.0).unwrap());
    assert!(runs(&fx).iter().any(|(_, k)| *k == JobKind::Map), "{fx:?}");
}

#[test]
fn a_cancel_while_jobs_wait_posts_them_first() {
    let (mut c, _) = Controller::new("", 0.0);
    c.hold_off_screen();
    ready(&mut c);
    // Switching the shooting branches off cancels their job: the held
    // jobs go out first, so the cancel reaches the worker after the job
    // it cancels.
    let fx = posts(&c.set_key("branches", "off", 5.0).unwrap());
    let cancel = fx
        .iter()
        .position(|(_, m)| matches!(m, ToWorker::Cancel { .. }))
        .expect("a cancel");
    let orbits = fx
        .iter()
        .position(|(_, m)| matches!(m, ToWorker::Run { job, .. } if job.kind() == JobKind::Orbits))
        .expect("the held shooting branches");
    assert!(orbits < cancel, "{fx:?}");
}

#[test]
fn a_failed_worker_ends_the_wait() {
    let (mut c, _) = Controller::new("", 0.0);
    c.hold_off_screen();
    ready(&mut c);
    // The selected Omega's worker crashes mid-job: its job never ends, so
    // the held jobs go out now, once, to the workers they were meant for.
    let fx = posts(&c.stop_holding(6.0));
    assert!(runs(&fx).iter().any(|(_, k)| *k == JobKind::Map), "{fx:?}");
    assert_eq!(c.main.status(JobKind::Map).posted_ms, Some(6.0));
    assert!(c.stop_holding(7.0).is_empty());
}

#[test]
fn a_held_message_keeps_the_kind_it_was_queued_with() {
    let (mut c, _) = Controller::new("", 0.0);
    c.hold_off_screen();
    ready(&mut c);
    // A new map job while the first screen computes: held beside those
    // queued before the workers were ready.
    assert!(c.set_key("map_value_points", "10", 2.0).unwrap().is_empty());
    let held = c
        .held
        .clone()
        .expect("the jobs off the first screen are held");
    let mut kinds = Vec::new();
    for (_, out) in &held {
        // What was noted beside the message is what its JSON says.
        let ToWorker::Run {
            target, id, job, ..
        } = serde_json::from_str(&out.text).unwrap()
        else {
            panic!("only jobs are held: {}", out.text)
        };
        let run = out.run.expect("a held job's target, kind and id");
        assert_eq!((run.target, run.kind, run.id), (target, job.kind(), id));
        kinds.push(job.kind());
    }
    // The defaults' jobs off the first screen, and the new map's.
    for kind in [JobKind::Bif, JobKind::Map, JobKind::Lyap, JobKind::Orbits] {
        assert!(kinds.contains(&kind), "{kind:?} in {kinds:?}");
    }
    assert!(kinds.iter().all(|&k| !KindSet::FIRST_SCREEN.contains(k)));
    assert!(kinds.iter().filter(|&&k| k == JobKind::Map).count() >= 2);
}

#[test]
fn a_held_job_counts_as_posted_from_its_release() {
    let (mut c, _) = Controller::new("", 0.0);
    c.hold_off_screen();
    ready(&mut c);
    // The first screen's jobs were posted at their start (the page's, 0).
    for kind in [JobKind::Omega, JobKind::HarmonicBalance] {
        assert_eq!(c.main.status(kind).posted_ms, Some(0.0), "{kind:?}");
    }
    // The others started at 0 too, but are not posted while held.
    let held = [JobKind::Bif, JobKind::Map, JobKind::Lyap, JobKind::Orbits];
    for kind in held {
        let s = c.main.status(kind);
        assert!(s.running(), "{kind:?}");
        assert_eq!((s.started_ms, s.posted_ms), (0.0, None), "{kind:?}");
    }
    // The first screen ends at 7 ms: the held jobs go out then.
    let omega = c.main.status(JobKind::Omega).id;
    let failed = encode(&FromWorker::Failed {
        id: omega,
        message: "no luck".into(),
    });
    c.worker_message(0, &failed, 5.0);
    let hbm = c.main.status(JobKind::HarmonicBalance).id;
    let rest = posts(&c.worker_message(1, &hbm_points(hbm, &[0.3], true, None), 7.0));
    assert!(runs(&rest).iter().any(|(_, k)| *k == JobKind::Bif));
    for kind in held {
        let s = c.main.status(kind);
        assert_eq!((s.started_ms, s.posted_ms), (0.0, Some(7.0)), "{kind:?}");
    }
    // A job started later is posted at its start.
    c.set_key("map_value_points", "10", 9.0).unwrap();
    assert_eq!(c.main.status(JobKind::Map).posted_ms, Some(9.0));
}
