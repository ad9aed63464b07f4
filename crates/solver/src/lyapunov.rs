//! The largest Lyapunov exponent of the stroboscopic (Poincaré) map.
//!
//! Why the map and not the flow: the forced system's flow always has a zero
//! exponent along the time direction (a perturbation that shifts the orbit
//! along itself neither grows nor decays), so the flow's largest exponent
//! can never be negative and hides the difference between a stable periodic
//! orbit and a quasi-periodic one. The map `P: y(t) -> y(t + T)` over one
//! mesh period `T` has no such direction: its largest exponent is negative
//! for a stable periodic response (it is then `ln |mu|` of the leading
//! Floquet multiplier), zero for quasi-periodic motion and positive for chaos.
//!
//! Method (Benettin's two-trajectory scheme): after a transient, a reference
//! and a neighbouring trajectory (separated by `perturbation_um` in mesh
//! space) are integrated together; after each period their separation `d`
//! is measured in mesh space (every mesh's `delta` and `delta' / omega`, in
//! micrometres: the same coordinates as the Poincaré points, blind to the
//! free rigid-body rotation, which would otherwise add a spurious neutral
//! direction), `ln(d / d0)` is accumulated and the neighbour is pulled back
//! to distance `d0` along the current separation. The exponent per period is
//! the mean of the logarithms. The dead-zone force is continuous, so the
//! flow is continuous across contact switches and no saltation correction
//! is needed; the integrator locates every switch.

use crate::dynamics::MeshOde;
use crate::error::{Result, SolverError};
use crate::ode::{Dopri5, Tolerances};
use crate::separation::{dist2, mesh_point, neighbour, Rigid};
use crate::steady::{Model, SteadyOptions, SteadyRun};
use std::f64::consts::PI;

/// Options of a Lyapunov-exponent computation.
#[derive(Debug, Clone, PartialEq)]
pub struct LyapunovOptions {
    /// Dimensionless mesh frequency.
    pub omega: f64,
    /// Transient periods before measuring (early settle applies).
    pub transient_periods: u32,
    /// Periods over which the logarithms are averaged.
    pub periods: u32,
    /// Initial separation in mesh space (um).
    pub perturbation_um: f64,
    /// Relative tolerance of the integrator.
    pub rtol: f64,
    /// Absolute tolerance as a mesh deflection (m).
    pub atol_m: f64,
}

impl LyapunovOptions {
    /// Defaults: 300 transient periods, 200 measured, separation 1e-3 um,
    /// tolerances 100 times tighter than the separation.
    pub fn new(omega: f64) -> Self {
        LyapunovOptions {
            omega,
            transient_periods: 300,
            periods: 200,
            perturbation_um: 1e-3,
            rtol: 1e-10,
            atol_m: 1e-14,
        }
    }

    /// Checks the options.
    pub fn validate(&self) -> Result<()> {
        let bad = |option: &str, value: String, allowed: &str| {
            SolverError::bad_option(option, value, allowed)
        };
        if !(self.omega.is_finite() && (0.01..=20.0).contains(&self.omega)) {
            return bad("omega", format!("{}", self.omega), "0.01 ..= 20");
        }
        if self.periods == 0 || self.periods > 100_000 {
            return bad("periods", self.periods.to_string(), "1 ..= 100000");
        }
        if self.transient_periods > 1_000_000 {
            return bad(
                "transient-periods",
                self.transient_periods.to_string(),
                "0 ..= 1000000",
            );
        }
        if !(self.perturbation_um.is_finite()
            && self.perturbation_um > 0.0
            && self.perturbation_um <= 1.0)
        {
            return bad(
                "perturbation",
                format!("{}", self.perturbation_um),
                "0 < perturbation <= 1 um",
            );
        }
        if !(self.rtol.is_finite() && (1e-13..=1e-6).contains(&self.rtol)) {
            return bad("rtol", format!("{}", self.rtol), "1e-13 ..= 1e-6");
        }
        if !(self.atol_m.is_finite() && self.atol_m > 0.0 && self.atol_m <= 1e-9) {
            return bad("atol", format!("{}", self.atol_m), "0 < atol <= 1e-9 m");
        }
        Ok(())
    }
}

/// The result.
#[derive(Debug, Clone, PartialEq)]
pub struct Lyapunov {
    /// Dimensionless mesh frequency.
    pub omega: f64,
    /// Largest exponent of the map, per mesh period (dimensionless).
    pub per_period: f64,
    /// The same per second (1/s): `per_period / T`.
    pub per_s: f64,
    /// Running estimate after each measured period (for convergence plots).
    pub running: Vec<f64>,
    /// The state at the end (a start for the next Omega of a sweep).
    pub end_state: Vec<f64>,
}

/// Computes the largest Lyapunov exponent of the stroboscopic map at
/// `opts.omega`, from `start` (or the static equilibrium).
///
/// The one-shot form of [`LyapunovRun`]: the same run, without pauses.
pub fn largest_exponent(
    model: &Model,
    opts: &LyapunovOptions,
    start: Option<&[f64]>,
) -> Result<Lyapunov> {
    let mut run = LyapunovRun::new(model, opts, start)?;
    loop {
        if let Some(l) = run.advance(model, u64::MAX)? {
            return Ok(l);
        }
    }
}

/// A Lyapunov-exponent computation that can pause and resume:
/// [`LyapunovRun::advance`] takes at most a given number of integrator
/// steps (of the transient's run and of both trajectories together) and
/// returns, keeping the integrators' states, the accumulated logarithms and
/// the period count, so a caller (the page's worker) can serve newer work
/// between slices. Any sequence of slices computes the same bits as
/// [`largest_exponent`], which is one unlimited slice.
#[derive(Debug, Clone)]
pub struct LyapunovRun {
    opts: LyapunovOptions,
    steps: u64,
    phase: Phase,
}

/// Where a [`LyapunovRun`] stands.
#[derive(Debug, Clone)]
enum Phase {
    /// The transient, by a steady-state run (it ends at a whole period).
    Transient(Box<SteadyRun>),
    /// The two trajectories, measured period by period.
    Measure(Box<Measure>),
    /// Finished or failed: nothing left to do.
    Done,
}

/// The measured phase: the reference `a`, the neighbour `b`, and the sums.
#[derive(Debug, Clone)]
struct Measure {
    ode_a: MeshOde,
    ode_b: MeshOde,
    a: Dopri5,
    b: Dopri5,
    tol: Tolerances,
    rigid: Option<Rigid>,
    omega_rad_s: f64,
    period: f64,
    d0: f64,
    budget: u64,
    bound_m: f64,
    /// The period being integrated (1-based).
    p: u32,
    /// Whether `a` has reached the end of period `p` and been checked.
    a_done: bool,
    sum: f64,
    running: Vec<f64>,
    pa: Vec<f64>,
    pb: Vec<f64>,
}

impl LyapunovRun {
    /// A run of `model` with `opts` from `start` (or the static
    /// equilibrium), before its first step; bad options are refused here.
    pub fn new(model: &Model, opts: &LyapunovOptions, start: Option<&[f64]>) -> Result<Self> {
        opts.validate()?;
        let mut so = SteadyOptions::new(opts.omega);
        so.transient_periods = opts.transient_periods;
        so.record_periods = 1;
        so.samples_per_period = 0;
        let transient = SteadyRun::new(model, &so, start)?;
        Ok(LyapunovRun {
            opts: opts.clone(),
            steps: 0,
            phase: Phase::Transient(Box::new(transient)),
        })
    }

    /// Integrator steps taken so far (the transient's and both trajectories').
    pub fn steps(&self) -> u64 {
        self.steps
    }

    /// Whether the run has returned its result or failed.
    pub fn is_done(&self) -> bool {
        matches!(self.phase, Phase::Done)
    }

    /// Continues the run for at most `max_steps` integrator steps (at least
    /// one): `Ok(Some(result))` once it is complete, `Ok(None)` if paused.
    /// `model` must be the run's own (the one given to [`LyapunovRun::new`]).
    /// After the result or an error the run is done, and further calls
    /// return `Ok(None)` without work.
    pub fn advance(&mut self, model: &Model, max_steps: u64) -> Result<Option<Lyapunov>> {
        let r = self.advance_inner(model, max_steps.max(1));
        if !matches!(r, Ok(None)) {
            self.phase = Phase::Done;
        }
        r
    }

    fn advance_inner(&mut self, model: &Model, max_steps: u64) -> Result<Option<Lyapunov>> {
        let mut left = max_steps;
        loop {
            match &mut self.phase {
                Phase::Done => return Ok(None),
                Phase::Transient(run) => {
                    if left == 0 {
                        return Ok(None);
                    }
                    let before = run.steps();
                    let out = run.advance(model, left);
                    let taken = run.steps() - before;
                    self.steps += taken;
                    left -= taken.min(left);
                    match out? {
                        None => return Ok(None),
                        Some(ss) => {
                            let m = Measure::start(model, &self.opts, &ss.end_state)?;
                            self.phase = Phase::Measure(Box::new(m));
                        }
                    }
                }
                Phase::Measure(m) => {
                    return m.advance(model, &self.opts, &mut self.steps, left);
                }
            }
        }
    }
}

impl Measure {
    /// The measured phase from the transient's end state `y0` (at a whole
    /// period, taken as time 0): the neighbour displaced along a fixed mixed
    /// direction (every coordinate, positions and rates), scaled to the
    /// separation in mesh space, without a rigid-body component.
    fn start(model: &Model, opts: &LyapunovOptions, y0: &[f64]) -> Result<Self> {
        let sys = &model.system;
        let omega_rad_s = opts.omega * sys.omega_ref_rad_s;
        let period = 2.0 * PI / omega_rad_s;
        let tol =
            crate::dynamics::tolerances(sys, opts.omega, opts.rtol, opts.atol_m, period, 1e-14);
        let mut ode_a = MeshOde::new(sys, omega_rad_s);
        let mut ode_b = MeshOde::new(sys, omega_rad_s);
        let mut pa = Vec::new();
        let mut pb = Vec::new();
        let d0 = opts.perturbation_um;
        let rigid = Rigid::of(model);
        let y1 = neighbour(model, &ode_a, 0.0, y0, d0, rigid.as_ref())?;
        mesh_point(&ode_a, 0.0, y0, omega_rad_s, &mut pa);
        mesh_point(&ode_b, 0.0, &y1, omega_rad_s, &mut pb);
        let a = Dopri5::new(&mut ode_a, 0.0, y0, period / 200.0, tol.clone());
        let b = Dopri5::new(&mut ode_b, 0.0, &y1, period / 200.0, tol.clone());
        Ok(Measure {
            ode_a,
            ode_b,
            a,
            b,
            tol,
            rigid,
            omega_rad_s,
            period,
            d0,
            budget: 200_000u64 * (u64::from(opts.periods) + 1),
            bound_m: model.divergence_bound_m(),
            p: 1,
            a_done: false,
            sum: 0.0,
            running: Vec::with_capacity(opts.periods as usize),
            pa,
            pb,
        })
    }

    /// Continues for at most `left` integrator steps, counted in `steps`.
    fn advance(
        &mut self,
        model: &Model,
        opts: &LyapunovOptions,
        steps: &mut u64,
        mut left: u64,
    ) -> Result<Option<Lyapunov>> {
        let n = self.a.y().len();
        while self.p <= opts.periods {
            let t_end = f64::from(self.p) * self.period;
            if !self.a_done {
                while self.a.t() < t_end {
                    if left == 0 {
                        return Ok(None);
                    }
                    self.a
                        .step(&mut self.ode_a, t_end)
                        .map_err(|e| model.explain_failure(&self.ode_a, &self.a, e))?;
                    left -= 1;
                    *steps += 1;
                }
                model.check_bounded(&self.ode_a, t_end, self.a.y(), self.bound_m)?;
                self.a_done = true;
            }
            while self.b.t() < t_end {
                if left == 0 {
                    return Ok(None);
                }
                self.b
                    .step(&mut self.ode_b, t_end)
                    .map_err(|e| model.explain_failure(&self.ode_b, &self.b, e))?;
                left -= 1;
                *steps += 1;
            }
            if self.a.stats.steps > self.budget || self.b.stats.steps > self.budget {
                return Err(SolverError::TooManySteps {
                    max_steps: self.budget,
                    t_s: t_end,
                });
            }
            let w = self.omega_rad_s;
            mesh_point(&self.ode_a, t_end, self.a.y(), w, &mut self.pa);
            mesh_point(&self.ode_b, t_end, self.b.y(), w, &mut self.pb);
            let d = dist2(&self.pa, &self.pb);
            if !(d.is_finite() && d > 0.0) {
                return Err(SolverError::NonFinite { t_s: t_end });
            }
            self.sum += (d / self.d0).ln();
            self.running.push(self.sum / f64::from(self.p));
            // Pull the neighbour back to d0 along the separation and
            // restart its integrator there.
            let ya = self.a.y();
            let yb = self.b.y();
            let mut dy: Vec<f64> = (0..n).map(|i| (yb[i] - ya[i]) * self.d0 / d).collect();
            Rigid::project_out(self.rigid.as_ref(), &mut dy);
            let yb: Vec<f64> = (0..n).map(|i| ya[i] + dy[i]).collect();
            let h = self.b.h();
            self.b = Dopri5::new(&mut self.ode_b, t_end, &yb, h, self.tol.clone());
            self.p += 1;
            self.a_done = false;
        }
        let per_period = self.sum / f64::from(opts.periods);
        Ok(Some(Lyapunov {
            omega: opts.omega,
            per_period,
            per_s: per_period / self.period,
            running: std::mem::take(&mut self.running),
            end_state: self.a.y().to_vec(),
        }))
    }
}
