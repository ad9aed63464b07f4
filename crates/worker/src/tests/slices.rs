//! Every long job yields to a newer selected-Omega job within one slice:
//! the Lyapunov curve, the time-integration overlay and the regime map
//! pause inside a point, and their points are the bits of the unsliced
//! solver runs.

use super::{drain, run_msg, steps_to_omega};
use crate::jobs::SLICE_STEPS;
use crate::WorkerCore;
use figures::protocol::{
    FromWorker, JobSpec, LyapSample, MapSample, MeshExtremes, OmegaSpec, RunOptions,
};
use solver::lyapunov::{largest_exponent, LyapunovOptions};
use solver::map::{MapSpec, RegimeMap};
use solver::model::Model;
use solver::params::ModelParams;
use solver::steady::{steady_state, SteadyOptions};
use solver::sweep::SweepSpec;

/// The run of every slice test's Omega job (and of the jobs it preempts).
const RUN: RunOptions = RunOptions {
    transient_periods: 300,
    record_periods: 40,
};

/// Sends `core` a new Omega job (id 1) and steps it until its result:
/// every step goes to it, as many as its own steps need slices. Returns
/// the messages of those steps.
fn new_omega_job_has_every_step(core: &mut WorkerCore, p: &ModelParams) -> Vec<FromWorker> {
    let omega_job = JobSpec::Omega(OmegaSpec {
        omega: 1.1,
        mesh: None,
        run: RUN,
        samples_per_period: 32,
        max_order: 8.0,
    });
    core.handle(&run_msg(1, p, omega_job));
    let (msgs, steps) = steps_to_omega(core);
    let result = msgs
        .iter()
        .find_map(|m| match m {
            FromWorker::Omega { id: 1, result } => Some(result),
            _ => None,
        })
        .expect("the new Omega result");
    assert_eq!(
        steps,
        result.steps.div_ceil(SLICE_STEPS) as usize,
        "steps taken by the older job before the new run's result"
    );
    msgs
}

/// Starts `job` (id 7) and steps it once: it must pause inside its first
/// point (`data` finds no data message). Then an Omega job arrives: every
/// step goes to it until its result. Returns the first job's data (what
/// `data` reads from its messages) once the worker is idle.
fn yields_to_a_new_omega_job<T: Clone>(
    job: JobSpec,
    data: fn(&FromWorker) -> Option<&Vec<T>>,
) -> Vec<T> {
    let mut core = WorkerCore::new();
    let p = ModelParams::default();
    let mut out = core.handle(&run_msg(7, &p, job));
    let first = core.step();
    assert!(
        !first.iter().any(|m| data(m).is_some()),
        "one slice computed a whole point: make the point longer"
    );
    out.extend(first);
    let msgs = new_omega_job_has_every_step(&mut core, &p);
    assert!(!msgs.iter().any(|m| data(m).is_some()));
    out.extend(drain(&mut core));
    assert!(out.iter().any(|m| matches!(m, FromWorker::Done { id: 7 })));
    out.iter().filter_map(data).flatten().cloned().collect()
}

fn model() -> Model {
    Model::new(&ModelParams::default()).expect("default model")
}

#[test]
fn a_lyapunov_point_pauses_for_a_new_omega_job_and_keeps_its_bits() {
    let (from, to, points) = (0.8, 1.3, 3);
    let got: Vec<LyapSample> = yields_to_a_new_omega_job(
        JobSpec::Lyap {
            omega_from: from,
            omega_to: to,
            points,
            chains: 1,
            shard: 0,
            transient_periods: 100,
            periods: 40,
        },
        |m| match m {
            FromWorker::LyapPoints { points, .. } => Some(points),
            _ => None,
        },
    );
    // The same chain, one-shot: each point continued from the last.
    let m = model();
    let mut state: Option<Vec<f64>> = None;
    assert_eq!(got.len(), points as usize);
    for (i, s) in got.iter().enumerate() {
        let omega = from + (to - from) / f64::from(points - 1) * i as f64;
        let mut o = LyapunovOptions::new(omega);
        o.transient_periods = 100;
        o.periods = 40;
        let l = largest_exponent(&m, &o, state.as_deref()).expect("one-shot run");
        assert_eq!(s.omega.to_bits(), omega.to_bits());
        assert_eq!(s.per_period.map(f64::to_bits), Some(l.per_period.to_bits()));
        assert_eq!(s.per_s.map(f64::to_bits), Some(l.per_s.to_bits()));
        state = Some(l.end_state);
    }
}

#[test]
fn an_overlay_point_pauses_for_a_new_omega_job_and_keeps_its_bits() {
    let got = yields_to_a_new_omega_job(
        JobSpec::Overlay {
            omega_from: 0.5,
            omega_to: 0.9,
            points: 3,
            chains: 1,
            shard: 0,
            run: RUN,
        },
        |m| match m {
            FromWorker::OverlayPoints { points, .. } => Some(points),
            _ => None,
        },
    );
    let m = model();
    let spec = SweepSpec::new(0.5, 0.9, 3);
    let mut state: Option<Vec<f64>> = None;
    assert_eq!(got.len(), 3);
    for (i, s) in got.iter().enumerate() {
        let mut o = SteadyOptions::new(spec.omega(i as u32));
        o.transient_periods = RUN.transient_periods;
        o.record_periods = RUN.record_periods;
        o.samples_per_period = 0;
        let ss = steady_state(&m, &o, state.as_deref()).expect("one-shot run");
        let want: Vec<MeshExtremes> = ss
            .meshes
            .iter()
            .map(|x| MeshExtremes {
                rel_min_um: figures::protocol::um(x.rel_min_m),
                rel_max_um: figures::protocol::um(x.rel_max_m),
                regime: x.impact.into(),
                dynamic_factor: x.dynamic_factor,
            })
            .collect();
        assert_eq!(s.meshes, want, "point {i}");
        assert_eq!(s.period, ss.period);
        state = Some(ss.end_state);
    }
}

#[test]
fn a_map_cell_pauses_for_a_new_omega_job_and_keeps_its_bits() {
    let got: Vec<MapSample> = yields_to_a_new_omega_job(
        JobSpec::Map {
            key: "backlash_um".into(),
            omega_from: 0.5,
            omega_to: 0.9,
            omega_points: 2,
            value_from: 50.0,
            value_to: 100.0,
            value_points: 2,
            mesh: None,
            shards: 1,
            shard: 0,
            run: RUN,
        },
        |m| match m {
            FromWorker::MapCells { cells, .. } => Some(cells),
            _ => None,
        },
    );
    let mut spec = MapSpec::new((0.5, 0.9, 2), "backlash_um", (50.0, 100.0, 2));
    spec.steady.transient_periods = RUN.transient_periods;
    spec.steady.record_periods = RUN.record_periods;
    spec.shard = Some((0, 1));
    let mut map = RegimeMap::new(&ModelParams::default(), spec).expect("map");
    let want: Vec<MapSample> = map
        .advance(usize::MAX)
        .into_iter()
        .map(MapSample::from)
        .collect();
    assert_eq!(want.len(), 4);
    assert_eq!(got, want);
}

/// The shooting branches' job on the default compound set (its branch
/// steps are long: Newton with the monodromy of a 20-odd dimensional map,
/// folds and period doublings located) works in slices like every other
/// job: its first branch step pauses, a new Omega job then has every step
/// until its result, an export of a finished sweep is answered at once,
/// and the branch goes on with the point a one-shot continuation gives.
#[test]
fn a_shooting_branch_step_pauses_for_a_new_omega_job_and_keeps_its_bits() {
    use solver::orbits::{ShootFrfSpec, ShootingContinuation};
    let mut core = WorkerCore::new();
    let p = ModelParams::default();
    let (from, to, points) = (0.1, 2.0, 100);
    let orbits = JobSpec::Orbits {
        omega_from: from,
        omega_to: to,
        points,
    };
    core.handle(&run_msg(7, &p, orbits));
    let is_data =
        |m: &FromWorker| matches!(m, FromWorker::OrbitPoints { points, .. } if !points.is_empty());
    // The first point (the start orbit), then a branch step that pauses.
    assert!(core.step().iter().any(is_data));
    assert!(
        !core.step().iter().any(is_data),
        "one slice computed a whole branch step"
    );
    new_omega_job_has_every_step(&mut core, &p);
    // The branch goes on: its next points are the one-shot continuation's.
    let mut got = Vec::new();
    for _ in 0..10_000 {
        got.extend(core.step().into_iter().flat_map(|m| match m {
            FromWorker::OrbitPoints { points, .. } => points,
            _ => Vec::new(),
        }));
        if !got.is_empty() {
            break;
        }
    }
    let m = model();
    let mut c = ShootingContinuation::new(&m, ShootFrfSpec::new(from, to, points)).expect("start");
    c.first_point().expect("first point");
    let mut want = Vec::new();
    while want.len() < got.len() {
        want.extend(c.advance(1).expect("a branch step"));
    }
    assert!(!got.is_empty());
    for (g, w) in got.iter().zip(&want) {
        assert_eq!(g.omega.to_bits(), w.point.omega.to_bits());
        assert_eq!(g.bifurcation, w.point.bifurcation.map(Into::into));
    }
}
