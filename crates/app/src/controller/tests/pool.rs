//! The worker pool's tests: its size from the machine's cores, and the
//! fixed chains dealt round robin over it.

use super::super::*;
use super::posts;

#[test]
fn the_pool_leaves_one_core_to_the_page_within_two_to_eight_workers() {
    // (logical cores, workers): one core for the page's main thread.
    for (cores, workers) in [
        (None, 2),
        (Some(0), 2),
        (Some(1), 2),
        (Some(2), 2),
        (Some(3), 2),
        (Some(4), 3),
        (Some(8), 7),
        (Some(9), 8),
        (Some(64), 8),
    ] {
        assert_eq!(pool_size(cores), workers, "{cores:?} cores");
    }
    // Chains depend on the points only: one per 50, 2 to 8.
    for (points, chains) in [
        (1, 1),
        (2, 2),
        (49, 2),
        (100, 2),
        (150, 3),
        (200, 4),
        (400, 8),
        (5000, 8),
    ] {
        assert_eq!(chain_count(points), chains, "{points} points");
    }
    // Out-of-range pools are clamped.
    assert_eq!(Controller::with_workers("", 0.0, 0).0.workers(), 1);
    assert_eq!(Controller::with_workers("", 0.0, 30).0.workers(), 8);
}

#[test]
fn a_larger_pool_deals_the_fixed_chains_round_robin_and_shares_the_map_rows() {
    let (mut c, _) =
        Controller::with_workers("bif_points=400&lyap_points=150&map_value_points=16", 0.0, 5);
    assert_eq!(c.workers(), 5);
    let mut fx = Vec::new();
    for w in 0..5 {
        fx.extend(c.worker_message(w, r#"{"type":"ready"}"#, 1.0));
    }
    let p = posts(&fx);
    let shards = |kind: JobKind| -> Vec<(usize, u32, u32)> {
        let mut v: Vec<(usize, u32, u32)> =
            p.iter()
                .filter_map(|(w, m)| match m {
                    ToWorker::Run { job, .. } if job.kind() == kind => match job {
                        JobSpec::Bif { chains, shard, .. }
                        | JobSpec::Lyap { chains, shard, .. } => Some((*w, *chains, *shard)),
                        JobSpec::Map { shards, shard, .. } => Some((*w, *shards, *shard)),
                        _ => Some((*w, 0, 0)),
                    },
                    _ => None,
                })
                .collect();
        v.sort_by_key(|s| s.2);
        v
    };
    // 8 sweep chains over 5 workers: chain c on worker c mod 5.
    let bif = shards(JobKind::Bif);
    assert_eq!(bif.len(), 8);
    for (w, chains, shard) in &bif {
        assert_eq!((*chains, *w), (8, *shard as usize % 5));
    }
    // 3 Lyapunov chains (150 points), on workers 0, 1, 2.
    assert_eq!(shards(JobKind::Lyap), vec![(0, 3, 0), (1, 3, 1), (2, 3, 2)]);
    // Map rows are independent: one share per worker but the first, which
    // holds the shooting branches, and the last, the boundaries.
    let map = shards(JobKind::Map);
    assert_eq!(map.iter().map(|s| s.0).collect::<Vec<_>>(), vec![1, 2, 3]);
    assert!(map.iter().all(|s| s.1 == 3));
    // The selected Omega on worker 0, the branch on the last worker.
    assert_eq!(shards(JobKind::Omega), vec![(0, 0, 0)]);
    assert_eq!(shards(JobKind::HarmonicBalance), vec![(4, 0, 0)]);
    assert_eq!((c.hbm_worker(), c.pinned_hbm_worker()), (4, 3));
    // The test status says how many workers run.
    assert_eq!(c.status(2.0)["workers"], 5);
    // A cancel reaches every worker.
    let p = posts(&c.set_key("lyap_points", "0", 3.0).unwrap());
    let cancelled: Vec<usize> = p
        .iter()
        .filter(|(_, m)| {
            matches!(
                m,
                ToWorker::Cancel {
                    kind: Some(JobKind::Lyap),
                    ..
                }
            )
        })
        .map(|(w, _)| *w)
        .collect();
    assert_eq!(cancelled, vec![0, 1, 2, 3, 4]);
}

/// The map's rows go to the workers the long jobs (the shooting branches on
/// the first, the boundaries on the last) leave free, to all but the
/// boundaries' when each holds one, to all of them when none runs or the
/// map is much larger than the default; a map restarted after the
/// branches ended takes every worker again.
#[test]
fn the_map_rows_go_to_the_workers_the_long_jobs_leave_free() {
    let map_workers = |p: &[(usize, ToWorker)]| -> Vec<(usize, u32)> {
        let mut v: Vec<(usize, u32)> = p
            .iter()
            .filter_map(|(w, m)| match m {
                ToWorker::Run {
                    job: JobSpec::Map { shards, .. },
                    ..
                } => Some((*w, *shards)),
                _ => None,
            })
            .collect();
        v.sort_unstable();
        v
    };
    let start = |query: &str| {
        let (mut c, _) = Controller::new(query, 0.0);
        let p = super::ready(&mut c);
        (c, p)
    };
    // Two workers, at the defaults: the branches on the first, the
    // boundaries on the last; each holds one, so the rows go where the
    // boundaries, the longer, do not run.
    assert_eq!(map_workers(&start("").1), vec![(0, 1)]);
    assert_eq!(map_workers(&start("boundaries=on").1), vec![(0, 1)]);
    // The boundaries alone: the rows on the first.
    assert_eq!(map_workers(&start("branches=off").1), vec![(0, 1)]);
    // The branches alone: the rows on the second.
    let (mut c, p) = start("boundaries=off");
    assert_eq!(map_workers(&p), vec![(1, 1)]);
    assert_eq!(
        map_workers(&start("boundaries=off&branches=off").1),
        vec![(0, 2), (1, 2)]
    );
    // A map ten times the default's cells shares both workers: the
    // branches would end long before it.
    assert_eq!(
        map_workers(&start("map_omega_points=100&map_value_points=64").1),
        vec![(0, 2), (1, 2)]
    );
    // The branches ended: a change of the map alone takes both workers.
    c.main.status_mut(JobKind::Orbits).finished_ms = Some(5.0);
    let p = posts(&c.set_key("map_to", "150", 6.0).unwrap());
    assert_eq!(map_workers(&p), vec![(0, 2), (1, 2)]);
    // Still running: the second worker alone.
    c.main.status_mut(JobKind::Orbits).finished_ms = None;
    let p = posts(&c.set_key("map_to", "120", 7.0).unwrap());
    assert_eq!(map_workers(&p), vec![(1, 1)]);
}

/// The two long jobs, the shooting branches and the map's boundaries, run
/// on different workers of a pool of two, so neither waits for the other.
#[test]
fn the_boundaries_and_the_shooting_branches_run_side_by_side() {
    let (mut c, _) = Controller::new("boundaries=on", 0.0);
    assert!(c.issues.is_empty(), "{:?}", c.issues);
    let p = super::ready(&mut c);
    let workers = |kind: JobKind| -> Vec<usize> {
        p.iter()
            .filter_map(|(w, m)| match m {
                ToWorker::Run { job, .. } if job.kind() == kind => Some(*w),
                _ => None,
            })
            .collect()
    };
    assert_eq!(workers(JobKind::Orbits), vec![0]);
    assert_eq!(workers(JobKind::Boundaries), vec![1]);
}
