//! Bounded work per call for the shooting continuation: every integration
//! a branch step makes (an evaluation of `P^n`, with or without its
//! monodromy, and the orbit's extremes) goes through [`Replay`], which
//! charges it against the call's work budget.
//!
//! A continuation step is a deterministic function of the branch's state,
//! so when the budget runs out in the middle of a step the step is
//! abandoned ([`Halt::Pause`]), the branch's state restored, and the next
//! call runs the step again from its start: the integrations already done
//! are replayed from their recorded results, failures included (in call
//! order, checked against their inputs bit for bit), the one in progress
//! resumes where it paused.
//! A sliced run therefore computes the same points, to the bit, as a
//! one-shot run (`a_sliced_continuation_gives_the_same_points`), and a call
//! does at most its budget of new integration work plus the replay's
//! linear algebra.
//!
//! Work is counted in plain integrator steps: a step that carries the
//! `m` tangent vectors of the monodromy counts `1 + m`.

use super::ShootingContinuation;
use crate::dynamics::{tolerances, MeshOde};
use crate::error::SolverError;
use crate::hbm::BranchMesh;
use crate::ode::{Dopri5, Tolerances};
use crate::shooting::variational::MapRun;
use crate::shooting::Reduced;
use crate::steady::Impact;
use nalgebra::DMatrix;

/// Why a step stopped before its end.
#[derive(Debug)]
pub(crate) enum Halt {
    /// The solver failed (reported, or treated as a failed correction).
    Fail(SolverError),
    /// The call's work budget ran out: the step is run again by the next call.
    Pause,
}

impl From<SolverError> for Halt {
    fn from(e: SolverError) -> Self {
        Halt::Fail(e)
    }
}

/// A step's result: the value, a failure or a pause.
pub(crate) type Step<T> = std::result::Result<T, Halt>;

/// What an integration is asked: its inputs, bit for bit.
#[derive(Debug, Clone, PartialEq, Eq)]
struct Key {
    z: Vec<u64>,
    omega: u64,
    period: u32,
    /// 0: `P^n` alone, 1: with the monodromy, 2: the extremes.
    what: u8,
}

impl Key {
    fn new(z: &[f64], omega: f64, period: u32, what: u8) -> Self {
        Key {
            z: z.iter().map(|v| v.to_bits()).collect(),
            omega: omega.to_bits(),
            period,
            what,
        }
    }
}

/// A finished integration's result.
#[derive(Debug, Clone)]
enum Value {
    Map(Vec<f64>, Option<DMatrix<f64>>),
    Extremes(Vec<BranchMesh>),
    /// An evaluation of `P^n` that failed (a wild predictor far out of
    /// range, a blow-up): replayed as the same failure, so the step takes
    /// the same path again. Unrecorded, it was integrated anew in every
    /// pass, and the one after it, which the step asks next, never got
    /// past its first slice: the compound set's default branches hung
    /// at 36 points in the page (an evaluation at Omega 17.4 failing
    /// before one at 0.217 that needed more than a slice).
    Failed(SolverError),
}

/// The integrations of the step in progress.
#[derive(Debug, Clone)]
pub(crate) struct Replay {
    /// Finished, in call order, with their integrator steps.
    done: Vec<(Key, Value, u64)>,
    /// The next call's index into `done`.
    next: usize,
    /// The integration that paused, its steps so far.
    partial: Option<(Key, MapRun, u64)>,
    /// Work left in this call (plain integrator steps).
    budget: u64,
}

impl Default for Replay {
    fn default() -> Self {
        Replay {
            done: Vec::new(),
            next: 0,
            partial: None,
            budget: u64::MAX,
        }
    }
}

impl Replay {
    /// A new pass over the step in progress with `budget` of work.
    pub(crate) fn begin(&mut self, budget: u64) {
        self.next = 0;
        self.budget = budget;
    }

    /// The step is over: its record is dropped.
    pub(crate) fn finish(&mut self) {
        self.done.clear();
        self.partial = None;
        self.next = 0;
    }

    /// The recorded result of the next call, if it asks the same.
    fn recorded(&mut self, key: &Key) -> Option<(Value, u64)> {
        match self.done.get(self.next) {
            Some((k, v, taken)) if k == key => {
                self.next += 1;
                Some((v.clone(), *taken))
            }
            Some(_) => {
                // Not the same call (never expected: the step is
                // deterministic): forget the rest of the record.
                self.done.truncate(self.next);
                self.partial = None;
                None
            }
            None => None,
        }
    }

    fn record(&mut self, key: Key, value: Value, taken: u64) {
        self.done.push((key, value.clone(), taken));
        self.next = self.done.len();
    }
}

impl ShootingContinuation {
    /// `P^n(z) - z` at `omega`, with the monodromy if asked.
    pub(super) fn map(
        &mut self,
        z: &[f64],
        omega: f64,
        period: u32,
        mono: bool,
    ) -> Step<(Vec<f64>, Option<DMatrix<f64>>)> {
        let key = Key::new(z, omega, period, u8::from(mono));
        let red = Reduced::new(&self.model, omega);
        let cost = 1 + if mono { red.dim() as u64 } else { 0 };
        if let Some((v, taken)) = self.replay.recorded(&key) {
            self.stats.integrator_steps += taken;
            self.stats.work_steps += taken * cost;
            return match v {
                Value::Map(g, m) => Ok((g, m)),
                Value::Failed(e) => {
                    // Counted again as its steps are: a paused step's
                    // counters went back with its state.
                    self.stats.failed_evaluations += 1;
                    Err(Halt::Fail(e))
                }
                Value::Extremes(_) => Err(Halt::Fail(SolverError::Singular {
                    what: "a replayed evaluation".into(),
                })),
            };
        }
        let (mut run, mut taken) = match self.replay.partial.take() {
            Some((k, run, taken)) if k == key => (run, taken),
            _ => {
                if self.replay.budget == 0 {
                    return Err(Halt::Pause);
                }
                let sys = &self.model.system;
                let ode = MeshOde::new(sys, omega * sys.omega_ref_rad_s);
                let o = &self.spec.shooting;
                let tol = tolerances(
                    sys,
                    omega,
                    o.rtol,
                    o.atol_m,
                    2.0 * std::f64::consts::PI / (omega * sys.omega_ref_rad_s),
                    1e-14,
                );
                let budget = o.max_steps_per_period.saturating_mul(u64::from(period));
                let run = MapRun::new(
                    &red,
                    &ode,
                    &tol,
                    z,
                    (0.0, 0.0),
                    period,
                    mono,
                    o.tangent_atol_scale,
                    self.model.divergence_bound_m(),
                    budget,
                );
                (run, 0)
            }
        };
        let allowed = (self.replay.budget / cost).max(1);
        let before = taken;
        let out = run.advance(&red, allowed, &mut taken);
        self.replay.budget = self
            .replay
            .budget
            .saturating_sub((taken - before).saturating_mul(cost));
        let out = match out {
            Ok(out) => out,
            Err(e) => {
                self.replay.record(key, Value::Failed(e.clone()), taken);
                self.stats.integrator_steps += taken;
                self.stats.work_steps += taken * cost;
                self.stats.failed_evaluations += 1;
                return Err(Halt::Fail(e));
            }
        };
        match out {
            Some(v) => {
                let g: Vec<f64> = v.z.iter().zip(z).map(|(p, z)| p - z).collect();
                self.replay
                    .record(key, Value::Map(g.clone(), v.monodromy.clone()), taken);
                self.stats.integrator_steps += taken;
                self.stats.work_steps += taken * cost;
                Ok((g, v.monodromy))
            }
            None => {
                self.replay.partial = Some((key, run, taken));
                Err(Halt::Pause)
            }
        }
    }

    /// Every mesh's extremes over the orbit from `z` (dense output at
    /// eight points per step), charged to the budget once done.
    pub(super) fn extremes(&mut self, z: &[f64], omega: f64, period: u32) -> Step<Vec<BranchMesh>> {
        let key = Key::new(z, omega, period, 2);
        if let Some((v, taken)) = self.replay.recorded(&key) {
            self.stats.integrator_steps += taken;
            self.stats.work_steps += taken;
            return match v {
                Value::Extremes(m) => Ok(m),
                Value::Map(..) | Value::Failed(_) => Err(Halt::Fail(SolverError::Singular {
                    what: "a replayed evaluation".into(),
                })),
            };
        }
        if self.replay.budget == 0 {
            return Err(Halt::Pause);
        }
        let (meshes, taken) = self.extremes_now(z, omega, period);
        self.replay.budget = self.replay.budget.saturating_sub(taken);
        self.replay
            .record(key, Value::Extremes(meshes.clone()), taken);
        self.stats.integrator_steps += taken;
        self.stats.work_steps += taken;
        Ok(meshes)
    }

    fn extremes_now(&self, z: &[f64], omega: f64, period: u32) -> (Vec<BranchMesh>, u64) {
        let sys = &self.model.system;
        let red = Reduced::new(&self.model, omega);
        let mut ode = MeshOde::new(sys, omega * sys.omega_ref_rad_s);
        let t_end = f64::from(period) * 2.0 * std::f64::consts::PI / (omega * sys.omega_ref_rad_s);
        let o = &self.spec.shooting;
        let tol: Tolerances = tolerances(
            sys,
            omega,
            o.rtol,
            o.atol_m,
            t_end / f64::from(period),
            1e-14,
        );
        let y0 = red.to_state(z, (0.0, 0.0));
        let mut int = Dopri5::new(&mut ode, 0.0, &y0, t_end / 200.0, tol);
        let nm = sys.meshes.len();
        let mut lo = vec![(f64::INFINITY, f64::INFINITY); nm];
        let mut hi = vec![(f64::NEG_INFINITY, f64::NEG_INFINITY); nm];
        let mut buf = y0.clone();
        let mut track = |ode: &MeshOde, t: f64, y: &[f64]| {
            for j in 0..nm {
                let mi = ode.mesh_instant(j, t, y);
                lo[j] = (lo[j].0.min(mi.delta), lo[j].1.min(mi.rel));
                hi[j] = (hi[j].0.max(mi.delta), hi[j].1.max(mi.rel));
            }
        };
        track(&ode, 0.0, &y0);
        while int.t() < t_end {
            let Ok(info) = int.step(&mut ode, t_end) else {
                break;
            };
            for k in 1..=8 {
                let t = info.t0 + (info.t1 - info.t0) * f64::from(k) / 8.0;
                int.dense(t, &mut buf);
                track(&ode, t, &buf);
            }
        }
        let meshes = sys
            .meshes
            .iter()
            .enumerate()
            .map(|(j, m)| BranchMesh {
                delta_max_m: hi[j].0,
                delta_min_m: lo[j].0,
                delta_amplitude_m: 0.5 * (hi[j].0 - lo[j].0),
                harmonics_m: Vec::new(),
                rel_min_m: lo[j].1,
                rel_max_m: hi[j].1,
                impact: Impact::classify(lo[j].1, hi[j].1, m.backlash_m),
            })
            .collect();
        (meshes, int.stats.steps)
    }
}
