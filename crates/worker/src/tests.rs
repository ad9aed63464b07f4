//! The worker job runner's tests: real jobs on small models.

use super::*;
use crate::jobs::hbm::HBM_CHUNK;
use figures::protocol::{encode, JobKind, JobSpec, OmegaSpec, OrbitSample, RunOptions};
use serde_json::Map;
use solver::keys;
use solver::params::ModelParams;

fn params(p: &ModelParams) -> Map<String, Value> {
    keys::to_json(p)
}

fn run_msg(id: JobId, p: &ModelParams, job: JobSpec) -> String {
    encode(&ToWorker::Run {
        target: Target::Main,
        id,
        params: params(p),
        job,
    })
}

fn quick() -> RunOptions {
    RunOptions {
        transient_periods: 20,
        record_periods: 8,
    }
}

fn drain(core: &mut WorkerCore) -> Vec<FromWorker> {
    let mut out = Vec::new();
    let mut guard = 0;
    while core.has_work() && guard < 10_000 {
        out.extend(core.step());
        guard += 1;
    }
    out
}

#[test]
fn map_and_lyapunov_jobs_share_the_worker_and_cover_their_shares() {
    let mut core = WorkerCore::new();
    let p = ModelParams::defaults(solver::ModelKind::GearPair);
    core.handle(&run_msg(
        3,
        &p,
        JobSpec::Map {
            key: "backlash_um".into(),
            omega_from: 0.5,
            omega_to: 1.5,
            omega_points: 3,
            value_from: 0.0,
            value_to: 100.0,
            value_points: 3,
            mesh: None,
            shards: 2,
            shard: 1,
            run: quick(),
        },
    ));
    core.handle(&run_msg(
        4,
        &p,
        JobSpec::Lyap {
            omega_from: 0.5,
            omega_to: 1.5,
            points: 3,
            chains: 1,
            shard: 0,
            transient_periods: 20,
            periods: 20,
        },
    ));
    let out = drain(&mut core);
    let cells: Vec<(u32, u32)> = out
        .iter()
        .flat_map(|m| match m {
            FromWorker::MapCells { id: 3, cells } => {
                cells.iter().map(|c| (c.row, c.column)).collect()
            }
            _ => Vec::new(),
        })
        .collect();
    // Shard 1 of 2 over 3 rows is row 1 only.
    assert_eq!(cells, vec![(1, 0), (1, 1), (1, 2)]);
    let lyap: Vec<f64> = out
        .iter()
        .flat_map(|m| match m {
            FromWorker::LyapPoints { id: 4, points } => {
                points.iter().filter_map(|p| p.per_period).collect()
            }
            _ => Vec::new(),
        })
        .collect();
    assert_eq!(lyap.len(), 3);
    assert!(lyap.iter().all(|l| l.is_finite()));
    assert!(out.iter().any(|m| matches!(m, FromWorker::Done { id: 3 })));
    assert!(out.iter().any(|m| matches!(m, FromWorker::Done { id: 4 })));
}

/// A job of `target` (an overlay of two points) as its message.
fn target_msg(target: Target, id: JobId, p: &ModelParams) -> String {
    encode(&ToWorker::Run {
        target,
        id,
        params: params(p),
        job: JobSpec::Overlay {
            omega_from: 0.5,
            omega_to: 1.0,
            points: 2,
            chains: 1,
            shard: 0,
            run: quick(),
        },
    })
}

fn finished(out: &[FromWorker], id: JobId) -> bool {
    out.iter()
        .any(|m| matches!(m, FromWorker::Done { id: i } if *i == id))
}

#[test]
fn every_computation_runs_beside_the_others_and_is_cancelled_alone() {
    let mut core = WorkerCore::new();
    let p = ModelParams::defaults(solver::ModelKind::GearPair);
    let targets = [
        Target::Main,
        Target::A,
        Target::Member(1),
        Target::Member(2),
    ];
    // The same kind for every target: all of them run.
    for (i, t) in targets.into_iter().enumerate() {
        core.handle(&target_msg(t, i as JobId + 1, &p));
    }
    let out = drain(&mut core);
    for id in 1..=4 {
        assert!(finished(&out, id), "job {id} did not finish");
    }
    // Cancelling one target's job (or all its jobs) leaves the others'.
    for (i, t) in targets.into_iter().enumerate() {
        core.handle(&target_msg(t, i as JobId + 11, &p));
    }
    core.handle(&encode(&ToWorker::Cancel {
        target: Target::A,
        kind: Some(JobKind::Overlay),
    }));
    core.handle(&encode(&ToWorker::Cancel {
        target: Target::Member(1),
        kind: None,
    }));
    let out = drain(&mut core);
    assert!(finished(&out, 11) && finished(&out, 14));
    for id in [12, 13] {
        assert!(!out
            .iter()
            .any(|m| matches!(m, FromWorker::OverlayPoints { id: i, .. } if *i == id)));
    }
    // Member 0 is the current state; a member past the cap is refused.
    for bad in [0, 99] {
        let out = core.handle(&target_msg(Target::Member(bad), 6, &p));
        assert!(
            matches!(&out[..], [FromWorker::Failed { id: 6, .. }]),
            "{out:?}"
        );
    }
}

#[test]
fn omega_job_returns_history_poincare_and_cli_json() {
    let mut core = WorkerCore::new();
    let p = ModelParams::defaults(solver::ModelKind::GearPair);
    let out = core.handle(&run_msg(
        7,
        &p,
        JobSpec::Omega(OmegaSpec {
            omega: 0.8,
            mesh: None,
            run: quick(),
            samples_per_period: 32,
            max_order: 4.0,
        }),
    ));
    assert!(out.is_empty());
    let out = drain(&mut core);
    let FromWorker::Omega { id, result } = &out[0] else {
        panic!("expected an Omega result, got {out:?}");
    };
    assert_eq!(*id, 7);
    assert_eq!(result.mesh_name, "pg");
    assert_eq!(result.x_um.len(), result.xdot_m_s.len());
    assert_eq!(result.poincare_x_um.len(), 8);
    assert!(!result.spectrum_order.is_empty());
    let cli: Value = serde_json::from_str(&result.cli_json).unwrap();
    assert_eq!(cli["mesh"], "pg");
    // ISO 6336-1's K_v as `gearshock simulate` prints it: the gear pair's
    // defaults are solver::iso6336's worked input, whose hand calculation
    // gives K = C_v1 B_p + C_v2 B_f + C_v3 B_k = 0.65685; N = Omega = 0.8
    // is subcritical, K_v = 0.8 K + 1 = 1.5255.
    let kv = cli["kv_iso6336"].as_f64().unwrap();
    assert!((kv - 1.5255).abs() < 1e-4, "{kv}");
    assert_eq!(cli["all_meshes"]["pg"]["kv_iso6336"], cli["kv_iso6336"]);
    assert_eq!(cli["iso6336"]["meshes"]["pg"]["range"], "subcritical");
    // One mesh: nothing to share.
    assert!(result.load_sharing.is_empty());
    assert_eq!(out[1], FromWorker::Done { id: 7 });
    // The animation's window is the time history's: the last 8 recorded
    // periods here, and the plotted mesh's samples are the same numbers.
    let a = &result.anim;
    assert_eq!(a.x_um.len(), 1);
    assert_eq!(a.start_sample as usize, result.x_um.len() - 8 * 32);
    assert_eq!(a.x_um[0].len(), 8 * 32);
    for (k, x) in a.x_um[0].iter().enumerate() {
        assert!((x - result.x_um[a.start_sample as usize + k]).abs() < 1e-3);
    }
    assert_eq!(a.backlash_um.len(), 1);
}

#[test]
fn sharded_fr_grid_covers_every_point_once() {
    let p = ModelParams::defaults(solver::ModelKind::GearPair);
    let mut seen = Vec::new();
    for shard in 0..2 {
        let mut core = WorkerCore::new();
        let out = core.handle(&run_msg(
            1,
            &p,
            JobSpec::Overlay {
                omega_from: 0.5,
                omega_to: 1.5,
                points: 5,
                chains: 2,
                shard,
                run: quick(),
            },
        ));
        assert!(
            matches!(out[0], FromWorker::Progress { total, .. } if total == if shard == 0 { 3 } else { 2 })
        );
        for m in drain(&mut core) {
            if let FromWorker::OverlayPoints { points, .. } = m {
                for s in points {
                    assert_eq!(s.meshes.len(), 1);
                    assert!(s.meshes[0].rel_max_um >= s.meshes[0].rel_min_um);
                    seen.push(s.index);
                }
            }
        }
    }
    seen.sort_unstable();
    assert_eq!(seen, vec![0, 1, 2, 3, 4]);
}

/// Shard 0 of a sweep sends the instability bands first: for the
/// default model over 0.1..2 the band 0.99-1.22 that `gearshock
/// instability` finds holds Omega 1.1 (where the set without backlash
/// diverges) and not 1.3; a backlash change sends the same bands (from
/// the cache); shard 1 sends none.
#[test]
fn the_first_shard_of_a_sweep_sends_the_instability_bands() {
    let bif = |id, shard, p: &ModelParams| {
        run_msg(
            id,
            p,
            JobSpec::Bif {
                omega_from: 0.1,
                omega_to: 2.0,
                points: 4,
                directions: "up".into(),
                chains: 2,
                shard,
                run: quick(),
            },
        )
    };
    let mut p = ModelParams::default();
    let mut core = WorkerCore::new();
    // Computed in the shard's first step, not at its start (where they
    // kept the worker's selected-Omega job waiting).
    let start = core.handle(&bif(1, 0, &p));
    assert!(!start.iter().any(|m| matches!(m, FromWorker::Bands { .. })));
    let out = core.step();
    let Some(FromWorker::Bands { id: 1, bands, .. }) = out.first() else {
        panic!("{out:?}");
    };
    let inside = |o: f64| bands.iter().any(|&(a, b)| a <= o && o <= b);
    assert!(inside(1.1) && !inside(1.3), "{bands:?}");
    let main = bands
        .iter()
        .find(|&&(a, b)| a <= 1.1 && 1.1 <= b)
        .copied()
        .unwrap();
    assert!(
        (main.0 - 0.99).abs() < 0.01 && (main.1 - 1.22).abs() < 0.01,
        "{main:?}"
    );
    // A backlash change: the same bands, from the cache, at the start.
    keys::set_assignment(&mut p, "backlash_um=10").unwrap();
    let again = core.handle(&bif(2, 0, &p));
    assert!(matches!(again.first(), Some(FromWorker::Bands { id: 2, bands: b, .. }) if b == bands));
    let mut core = WorkerCore::new();
    let mut other = core.handle(&bif(3, 1, &p));
    other.extend(core.step());
    assert!(!other.iter().any(|m| matches!(m, FromWorker::Bands { .. })));
}

#[test]
fn hbm_job_streams_the_branch_in_chunks_and_a_newer_job_replaces_it() {
    let p = ModelParams::defaults(solver::ModelKind::GearPair);
    let hbm = |id, harmonics| {
        run_msg(
            id,
            &p,
            JobSpec::HarmonicBalance {
                omega_from: 0.3,
                omega_to: 1.8,
                points: 60,
                harmonics,
                stability: true,
            },
        )
    };
    let mut core = WorkerCore::new();
    let out = core.handle(&hbm(1, 3));
    assert!(matches!(out[0], FromWorker::Progress { id: 1, .. }));
    let out = core.step();
    assert!(
        matches!(&out[..], [FromWorker::HbmPoints { id: 1, points, finished: false, error: None, .. }] if !points.is_empty() && points.len() <= HBM_CHUNK)
    );
    core.handle(&hbm(2, 3));
    let out = drain(&mut core);
    let mut omegas = Vec::new();
    let mut last = None;
    for m in &out {
        let FromWorker::HbmPoints {
            id,
            points,
            progress,
            finished,
            error,
            ..
        } = m
        else {
            panic!("unexpected {m:?}");
        };
        assert_eq!(*id, 2);
        assert!(points.len() <= HBM_CHUNK);
        for s in points {
            assert_eq!(s.meshes.len(), 1);
            assert!(s.meshes[0].rel_max_um >= s.meshes[0].rel_min_um);
            assert!(s.stable.is_some());
            omegas.push(s.omega);
        }
        last = Some((*progress, *finished, error.clone()));
    }
    assert_eq!(last, Some((1.0, true, None)));
    assert!(omegas[0] == 0.3 && omegas.len() > 30, "{omegas:?}");
    assert!(!core.has_work());
    // A cancel drops a running branch.
    core.handle(&hbm(3, 3));
    core.handle(&encode(&ToWorker::Cancel {
        target: Target::Main,
        kind: Some(JobKind::HarmonicBalance),
    }));
    assert!(!core.has_work());
    // Out-of-range harmonics fail cleanly.
    let out = core.handle(&hbm(4, 99));
    assert!(
        matches!(&out[0], FromWorker::Failed { id: 4, message } if message.contains("harmonics"))
    );
}

#[test]
fn newer_job_replaces_older_and_bad_params_fail_cleanly() {
    let mut core = WorkerCore::new();
    let p = ModelParams::defaults(solver::ModelKind::GearPair);
    let bif = |id| {
        run_msg(
            id,
            &p,
            JobSpec::Bif {
                omega_from: 0.5,
                omega_to: 1.5,
                points: 4,
                directions: "both".into(),
                chains: 2,
                shard: 1,
                run: quick(),
            },
        )
    };
    core.handle(&bif(1));
    core.step();
    core.handle(&bif(2));
    let out = drain(&mut core);
    assert!(out.iter().all(|m| match m {
        FromWorker::BifPoints { id, .. }
        | FromWorker::Progress { id, .. }
        | FromWorker::Done { id } => *id == 2,
        _ => false,
    }));
    // Shard 1 of 2 chains over 4 points: indices 1 and 3, up and down.
    let n: usize = out
        .iter()
        .map(|m| match m {
            FromWorker::BifPoints { points, .. } => points.len(),
            _ => 0,
        })
        .sum();
    assert_eq!(n, 4);

    let mut bad = params(&p);
    bad.insert("backlash_um".into(), Value::from(-5));
    let msg = encode(&ToWorker::Run {
        target: Target::Main,
        id: 9,
        params: bad,
        job: JobSpec::Omega(OmegaSpec {
            omega: 1.0,
            mesh: Some(0),
            run: quick(),
            samples_per_period: 16,
            max_order: 4.0,
        }),
    });
    let out = core.handle(&msg);
    assert!(
        matches!(&out[0], FromWorker::Failed { id: 9, message } if message.contains("backlash_um"))
    );
    assert!(matches!(
        core.handle("{not json")[0],
        FromWorker::Failed { id: 0, .. }
    ));
}

#[test]
fn exported_shards_merge_into_the_cli_format() {
    let p = ModelParams::defaults(solver::ModelKind::GearPair);
    let mut cores = [WorkerCore::new(), WorkerCore::new()];
    for (w, core) in cores.iter_mut().enumerate() {
        core.handle(&run_msg(
            5,
            &p,
            JobSpec::Bif {
                omega_from: 0.6,
                omega_to: 1.2,
                points: 4,
                directions: "up".into(),
                chains: 2,
                shard: w as u32,
                run: quick(),
            },
        ));
        drain(core);
    }
    let FromWorker::Export { text: shard1, .. } = cores[1].handle(&encode(&ToWorker::ExportBif {
        id: 5,
        mesh: Some(0),
        other: vec![],
    }))[0]
        .clone()
    else {
        panic!("no export");
    };
    let FromWorker::Export { text, .. } = cores[0].handle(&encode(&ToWorker::ExportBif {
        id: 5,
        mesh: Some(0),
        other: vec![shard1],
    }))[0]
        .clone()
    else {
        panic!("no merged export");
    };
    let v: Value = serde_json::from_str(&text).unwrap();
    assert_eq!(v["spec"]["chains"], 2);
    assert_eq!(v["spec"]["shard"], Value::Null);
    let idx: Vec<i64> = v["points"]
        .as_array()
        .unwrap()
        .iter()
        .map(|p| p["index"].as_i64().unwrap())
        .collect();
    assert_eq!(idx, vec![0, 1, 2, 3]);
    // An export of an unknown or unfinished sweep is an error, not a panic.
    assert!(matches!(
        cores[0].handle(&encode(&ToWorker::ExportBif {
            id: 99,
            mesh: None,
            other: vec![]
        }))[0],
        FromWorker::Failed { .. }
    ));
}

/// The messages of `core`'s steps until one carries an Omega result: the
/// result and the number of steps taken.
fn steps_to_omega(core: &mut WorkerCore) -> (Vec<FromWorker>, usize) {
    let mut out = Vec::new();
    for n in 1..100_000 {
        let msgs = core.step();
        let got = msgs
            .iter()
            .any(|m| matches!(m, FromWorker::Omega { .. } | FromWorker::Failed { .. }));
        out.extend(msgs);
        if got {
            return (out, n);
        }
    }
    panic!("no Omega result");
}

#[test]
fn a_new_omega_job_preempts_a_running_steady_state_within_one_slice() {
    use crate::jobs::omega::{omega_result, with_iso6336, OmegaJob};
    use crate::jobs::SLICE_STEPS;
    let mut core = WorkerCore::new();
    let p = ModelParams::default();
    let run = RunOptions {
        transient_periods: 300,
        record_periods: 40,
    };
    let omega_job = |omega| {
        JobSpec::Omega(OmegaSpec {
            omega,
            mesh: None,
            run,
            samples_per_period: 32,
            max_order: 8.0,
        })
    };
    // A bifurcation shard waits behind the Omega jobs.
    core.handle(&run_msg(
        7,
        &p,
        JobSpec::Bif {
            omega_from: 0.5,
            omega_to: 1.5,
            points: 4,
            directions: "up".into(),
            chains: 1,
            shard: 0,
            run,
        },
    ));
    // The sweep's first point pauses after a slice, inside its steady state.
    let out = core.step();
    assert!(
        out.iter()
            .all(|m| !matches!(m, FromWorker::BifPoints { .. })),
        "one slice computed a whole sweep point"
    );
    core.handle(&run_msg(1, &p, omega_job(0.9)));
    // The old steady state is paused after a slice, mid-run.
    let first = core.step();
    assert!(
        first.iter().all(|m| !matches!(m, FromWorker::Omega { .. })),
        "one slice finished the whole run: make the run longer"
    );
    // The slider moves: the next step already works on the new job.
    core.handle(&run_msg(2, &p, omega_job(1.1)));
    let (out, steps) = steps_to_omega(&mut core);
    let result = out
        .iter()
        .find_map(|m| match m {
            FromWorker::Omega { id, result } => Some((*id, result)),
            _ => None,
        })
        .expect("an Omega result");
    assert_eq!(result.0, 2, "the old job's result arrived");
    // Every step went to the new run: as many as its slices, no more.
    let slices = result.1.steps.div_ceil(SLICE_STEPS) as usize;
    assert_eq!(
        steps, slices,
        "steps taken by other jobs before the new run's result"
    );
    assert!(slices > 1, "the run fits one slice: it tests no pause");
    assert!(out
        .iter()
        .all(|m| !matches!(m, FromWorker::BifPoints { .. })));
    // Sliced, the result is the one-shot run's, bit for bit.
    let model = solver::model::Model::new(&p).expect("model");
    let JobSpec::Omega(spec) = omega_job(1.1) else {
        panic!("not an Omega job");
    };
    let job = OmegaJob { id: 2, model, spec };
    let mut whole = omega_result(&job, None).expect("one-shot run");
    // The worker's run adds ISO 6336-1's K_v to its CLI JSON.
    with_iso6336(
        &mut whole,
        &p,
        &job.model,
        &solver::iso6336::IsoInputs::default(),
    );
    assert_eq!(*result.1.as_ref(), whole);
    // Then the sweep runs.
    assert!(drain(&mut core)
        .iter()
        .any(|m| matches!(m, FromWorker::BifPoints { id: 7, .. })));
}

/// The shooting branches' job streams orbits whose Poincaré samples are
/// the steady state's: at the range's start, the first orbit's x on the
/// gear pair equals the selected-Omega run's (a transient integrated, then
/// the steady pipeline), and the job ends by itself.
#[test]
fn the_orbits_job_streams_orbits_that_the_steady_state_confirms() {
    let mut core = WorkerCore::new();
    let p = ModelParams::defaults(solver::ModelKind::GearPair);
    core.handle(&run_msg(
        3,
        &p,
        JobSpec::Orbits {
            omega_from: 0.15,
            omega_to: 0.6,
            points: 20,
        },
    ));
    let out = drain(&mut core);
    let points: Vec<&OrbitSample> = out
        .iter()
        .flat_map(|m| match m {
            FromWorker::OrbitPoints { id: 3, points, .. } => points.iter().collect(),
            _ => Vec::new(),
        })
        .collect();
    assert!(points.len() > 3, "{out:?}");
    assert!(out.iter().any(|m| matches!(
        m,
        FromWorker::OrbitPoints {
            finished: true,
            error: None,
            ..
        }
    )));
    let first = points[0];
    assert_eq!((first.omega, first.period), (0.15, 1));
    assert_eq!(first.x_um.len(), 1);
    core.handle(&run_msg(
        4,
        &p,
        JobSpec::Omega(OmegaSpec {
            omega: 0.15,
            mesh: None,
            run: RunOptions {
                transient_periods: 300,
                record_periods: 4,
            },
            samples_per_period: 32,
            max_order: 4.0,
        }),
    ));
    let out = drain(&mut core);
    let Some(FromWorker::Omega { result, .. }) = out.first() else {
        panic!("expected an Omega result, got {out:?}");
    };
    assert_eq!(result.motion.period(), Some(1), "{:?}", result.motion);
    for x in &result.poincare_x_um {
        assert!(
            (x - first.x_um[0][0]).abs() < 1e-3,
            "{x} µm against the orbit's {} µm",
            first.x_um[0][0]
        );
    }
}

mod slices;
