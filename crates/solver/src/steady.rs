//! Steady-state response by time integration: transient, then recorded periods.
//!
//! A run starts from the loaded static equilibrium at rest at `t = 0` (or
//! from a given state, which sweeps use to carry the end state from one
//! frequency to the next), integrates transient mesh periods, then records
//! periods. Per mesh it reports the deflection's minimum, maximum, mean and
//! RMS, the mesh force and dynamic factor, the impact regime, Poincaré
//! samples once per mesh period, an optional time history and spectrum, and
//! the period of the Poincaré orbit.
//!
//! Early end of the transient. The transient is a *maximum*. After each
//! period the Poincaré point `P_n` (every mesh's deflection and rate over
//! omega, in micrometres: the whole elastic state) is compared with `P_{n-p}`
//! for `p = 1..=8`. With `d_k = |P_{n-kp} - P_{n-(k+1)p}|_inf` for
//! `k = 0..5`, the contraction per `p` periods `rho` is the worst of the
//! observed ratios `d_k / d_{k+1}` and of the slowest modal decay of the
//! linearized system, `exp(-p T min_k zeta_k omega_k)`; the transient ends
//! when the geometric bound on the remaining drift `d_0 rho / (1 - rho)` is
//! below `tol / 2`, where `tol = 1e-4 um + 1e-5 * (the deflections' range
//! over the last period)` is the settle tolerance. (The modal floor matters:
//! with the ring's undamped support the first mode of the default set has a
//! damping ratio of only 0.0024, and a mode that turns by nearly whole turns
//! between samples hides from Poincaré differences.)
//! Orbits that converge slowly (near a bifurcation) or never (quasi-periodic,
//! chaotic) run the full transient.
//!
//! Extremes are exact to the integrator's accuracy, not to a sampling grid:
//! wherever a deflection's rate changes sign inside a step, the extremum is
//! located on a cubic Hermite model and evaluated on the dense output.

use crate::dynamics::tolerances;
use crate::dynamics::MeshOde;
use crate::error::{Result, SolverError};
use crate::ode::{Dopri5, IntegratorStats, Tolerances};
use crate::shooting::ShootRun;
use std::f64::consts::PI;

mod options;
mod probe;
mod record;
mod settle;
mod spectrum;
#[cfg(test)]
mod tests;
mod verdict;

pub use options::{SteadyOptions, DEFAULT_ATOL_M, DEFAULT_RTOL};
use probe::Probe;
pub use probe::{decide, LyapunovEvidence, DECIDE_AT, LAMBDA_MIN};
use record::Recorder;
pub(crate) use settle::detect_period;
use settle::{has_settled, SpanTracker, SETTLE_DISTANCES};
pub use spectrum::{spectrum, Spectrum};
use verdict::window_verdict;
pub(crate) use verdict::{candidate_period, CHECKPOINTS, PROBE_FROM_REST};
pub use verdict::{classify_recorded, Motion, MAX_PROBES};

/// The model every steady run takes (defined in [`crate::model`]),
/// re-exported beside the run for its callers.
pub use crate::model::Model;

/// Impact regime of a steady response (Kahraman & Singh, 1990).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum Impact {
    /// The drive flanks never separate.
    None,
    /// They separate, but the back flanks never touch.
    SingleSided,
    /// The back flanks touch.
    DoubleSided,
    /// The teeth never touch at all (no load, no excitation large enough).
    NoContact,
    /// No gap to cross: the mesh has no backlash, so its force is linear in
    /// the deflection and the teeth never part (a negative deflection
    /// loads the back flanks without an impact).
    NoGap,
}

impl Impact {
    /// Name for output.
    pub fn name(self) -> &'static str {
        match self {
            Impact::None => "none",
            Impact::SingleSided => "single-sided",
            Impact::DoubleSided => "double-sided",
            Impact::NoContact => "no-contact",
            Impact::NoGap => "no-gap",
        }
    }

    /// Parses a name written by [`Impact::name`].
    pub fn from_name(s: &str) -> Option<Self> {
        [
            Impact::None,
            Impact::SingleSided,
            Impact::DoubleSided,
            Impact::NoContact,
            Impact::NoGap,
        ]
        .into_iter()
        .find(|i| i.name() == s)
    }

    /// The regime in words, as a reader meets it.
    pub fn words(self) -> &'static str {
        match self {
            Impact::None => "no impact",
            Impact::SingleSided => "single-sided impact",
            Impact::DoubleSided => "double-sided impact",
            Impact::NoContact => "no contact",
            Impact::NoGap => "no gap (linear contact)",
        }
    }

    /// Classifies from the extremes of the relative displacement `x = delta - e`.
    pub fn classify(rel_min: f64, rel_max: f64, backlash: f64) -> Self {
        if backlash <= 0.0 {
            Impact::NoGap
        } else if rel_min > backlash {
            Impact::None
        } else if rel_min < -backlash {
            Impact::DoubleSided
        } else if rel_max > backlash {
            Impact::SingleSided
        } else {
            Impact::NoContact
        }
    }
}

/// Per-mesh results of a steady run.
#[derive(Debug, Clone, PartialEq)]
pub struct MeshSteady {
    /// Smallest deflection delta (m): the rotations' part, without the
    /// TE (the seed's plotted quantity is x, [`Self::rel_min_m`]).
    pub delta_min_m: f64,
    /// Largest deflection delta (m), the rotations' part.
    pub delta_max_m: f64,
    /// Mean deflection delta (m), the rotations' part, from the uniform
    /// samples (NaN without samples).
    pub delta_mean_m: f64,
    /// RMS of delta about zero (m), the rotations' part, from the uniform
    /// samples (NaN without samples).
    pub delta_rms_m: f64,
    /// Smallest tooth deflection x = delta - e (m), TE included: the dead
    /// zone's argument and the seed's plotted quantity.
    pub rel_min_m: f64,
    /// Largest tooth deflection x = delta - e (m), TE included.
    pub rel_max_m: f64,
    /// Largest mesh force (N).
    pub force_max_n: f64,
    /// Smallest mesh force (N).
    pub force_min_n: f64,
    /// Static mesh force (N).
    pub static_force_n: f64,
    /// max F / F_static, if the static force is non-zero.
    pub dynamic_factor: Option<f64>,
    /// Impact regime.
    pub impact: Impact,
    /// Poincaré samples of delta (m), the rotations' part, one per
    /// recorded period.
    pub poincare_delta_m: Vec<f64>,
    /// Poincaré samples of delta' (m/s), the rotations' part.
    pub poincare_velocity_m_s: Vec<f64>,
    /// Poincaré samples of x = delta - e (m), TE included (the seed's
    /// penetration depth), one per recorded period.
    pub poincare_x_m: Vec<f64>,
    /// Poincaré samples of x' (m/s) (the seed's penetration velocity).
    pub poincare_x_velocity_m_s: Vec<f64>,
    /// Fraction of the recorded time in drive contact, apart and in back contact
    /// (from the uniform samples; zeros without samples).
    pub contact_fraction: [f64; 3],
}

/// Time history of one mesh over the recorded periods.
#[derive(Debug, Clone, PartialEq)]
pub struct MeshHistory {
    /// Mesh index.
    pub mesh: usize,
    /// delta (m) at the sample times.
    pub delta_m: Vec<f64>,
    /// delta' (m/s).
    pub velocity_m_s: Vec<f64>,
    /// x = delta - e (m).
    pub rel_m: Vec<f64>,
    /// Mesh force (N).
    pub force_n: Vec<f64>,
}

/// Work and convergence figures of a run.
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct SteadyStats {
    /// Transient periods actually integrated.
    pub transient_periods_run: u32,
    /// Whether the early-settle criterion ended the transient.
    pub settled: bool,
    /// Integrator counters.
    pub integrator: IntegratorStats,
    /// Shooting attempts made during the transient.
    pub shooting_attempts: u32,
    /// Integrator steps of those attempts, with the tangents or without.
    pub shooting_steps: u64,
    /// Integrator steps of the Lyapunov probe's neighbour trajectory.
    pub probe_steps: u64,
}

/// A steady-state response.
#[derive(Debug, Clone, PartialEq)]
pub struct SteadyState {
    /// Dimensionless frequency.
    pub omega: f64,
    /// Mesh frequency (rad/s).
    pub omega_rad_s: f64,
    /// Mesh frequency (Hz).
    pub mesh_freq_hz: f64,
    /// Mesh period (s).
    pub period_s: f64,
    /// Time at which recording started (s).
    pub record_start_s: f64,
    /// Per-mesh results, in the system's mesh order.
    pub meshes: Vec<MeshSteady>,
    /// Sample times (s) of the histories, from `record_start_s`.
    pub sample_times_s: Vec<f64>,
    /// Histories of the requested meshes.
    pub histories: Vec<MeshHistory>,
    /// Full state at the end (phase 0 of the excitation), for continuation.
    pub end_state: Vec<f64>,
    /// Period of the Poincaré orbit in mesh periods, `None` if not periodic
    /// within the recorded window.
    pub period: Option<u32>,
    /// The classification: exact orbit, periodic by integration, still
    /// settling, not periodic; `period` is its period.
    pub motion: Motion,
    /// What shooting did when it did not give the steady state (a failed or
    /// unstable attempt), in words.
    pub shooting_note: Option<String>,
    /// The largest Lyapunov exponent measured beside the run where
    /// shooting found no steady state (see `steady::probe`).
    pub lyapunov: Option<LyapunovEvidence>,
    /// Work figures.
    pub stats: SteadyStats,
}

impl SteadyState {
    /// The verdict in words: the motion's, and for motion that is not
    /// periodic the Lyapunov evidence, e.g. "not periodic after 12
    /// transient periods; largest Lyapunov exponent 0.280 per period over
    /// 24 periods: chaotic".
    pub fn verdict(&self) -> String {
        let words = self.motion.words(self.stats.transient_periods_run);
        match (&self.motion, &self.lyapunov) {
            (Motion::NotPeriodic | Motion::StillSettling { .. }, Some(ev)) => {
                format!("{words}; {}", ev.words())
            }
            _ => words,
        }
    }

    /// Whether the run found chaos: not periodic, with a positive largest
    /// Lyapunov exponent by the probe's test. A run continued from its
    /// end state starts its probe at once ([`SteadyRun::continued`]).
    pub fn found_chaos(&self) -> bool {
        matches!(self.motion, Motion::NotPeriodic) && self.lyapunov.is_some_and(|e| e.chaotic)
    }

    /// The mesh with the largest dynamic factor (the first on a tie, mesh 0
    /// when none has one): the "worst" mesh of sweeps and views.
    pub fn worst_mesh(&self) -> usize {
        self.meshes
            .iter()
            .enumerate()
            .max_by(|a, b| {
                let da = a.1.dynamic_factor.unwrap_or(0.0);
                let db = b.1.dynamic_factor.unwrap_or(0.0);
                da.total_cmp(&db)
            })
            .map_or(0, |(j, _)| j)
    }
}

/// Largest orbit period tested.
pub const MAX_PERIOD: usize = crate::shooting::MAX_SHOOT_PERIOD as usize;

/// Settle tolerance (um) for deflections spanning `span_um`.
pub fn settle_tol_um(span_um: f64) -> f64 {
    1e-4 + 1e-5 * span_um
}

/// Runs one steady-state response from `start` (or the static equilibrium).
///
/// The one-shot form of [`SteadyRun`]: the same run, without pauses.
pub fn steady_state(
    model: &Model,
    opts: &SteadyOptions,
    start: Option<&[f64]>,
) -> Result<SteadyState> {
    let mut run = SteadyRun::new(model, opts, start)?;
    loop {
        if let Some(ss) = run.advance(model, u64::MAX)? {
            return Ok(ss);
        }
    }
}

/// Where a [`SteadyRun`] stands.
#[derive(Debug, Clone)]
enum Phase {
    /// Integrating transient period `p` (1-based).
    Transient { p: u32 },
    /// Integrating recorded period `r` (1-based) of the window starting at `t_rec`.
    Record {
        r: u32,
        t_rec: f64,
        rec: Box<Recorder>,
    },
    /// Shooting for a periodic orbit from the state at the end of transient
    /// period `periods_run`; `settled` if the early-settle test started it
    /// (a failure then records from the integrated state).
    Shoot {
        run: Box<ShootRun>,
        period: u32,
        settled: bool,
    },
    /// A recorded window kept while shooting tried to confirm it (see
    /// `SteadyRun::confirm_window`), to be reported as it is.
    Finish { t_rec: f64, rec: Box<Recorder> },
    /// Finished or failed: nothing left to do.
    Done,
}

/// A steady-state run that can pause and resume: [`SteadyRun::advance`]
/// takes at most a given number of integrator steps and returns, keeping the
/// integrator's state, so a caller (the page's worker) can serve newer work
/// between slices. Any sequence of slices computes the same bits as
/// [`steady_state`], which is one unlimited slice.
#[derive(Debug, Clone)]
pub struct SteadyRun {
    opts: SteadyOptions,
    ode: MeshOde,
    int: Dopri5,
    /// The integrator's tolerances (a converged orbit restarts it).
    tol: Tolerances,
    facts: RunFacts,
    settling: Settling,
    periods_run: u32,
    phase: Phase,
    shooting: ShootingLog,
    probing: Probing,
    /// A recorded window whose verdict shooting is trying to confirm:
    /// its start, its recorder and its periods (now counted in
    /// `periods_run`).
    window: Option<(f64, Box<Recorder>, u32)>,
}

/// What a run knows from its start and never changes.
#[derive(Debug, Clone)]
struct RunFacts {
    omega_rad_s: f64,
    period: f64,
    bound_m: f64,
    /// Integrator steps allowed in all.
    budget: u64,
    /// Whether the model is linear (no backlash on any mesh): its steady
    /// state is the period-1 orbit shooting finds in one Newton step, or
    /// parametric growth; never chaos, so it is never probed for it.
    linear: bool,
}

/// The evidence that the transient has died out.
#[derive(Debug, Clone)]
struct Settling {
    /// The slowest modal decay per period (see `has_settled`).
    rho_modal: f64,
    poincare_hist: Vec<Vec<f64>>,
    span: SpanTracker,
    deflections: Vec<f64>,
    /// The latest Poincaré points, for the candidate period.
    pipe_hist: Vec<Vec<f64>>,
    settled: bool,
}

/// Shooting's attempts to find the exact orbit, and its outcome.
#[derive(Debug, Clone, Default)]
struct ShootingLog {
    /// The exact orbit's verdict, once shooting has found it.
    exact: Option<Motion>,
    note: Option<String>,
    attempts: u32,
    steps: u64,
}

/// The Lyapunov probe beside a recording started without an orbit.
#[derive(Debug, Clone)]
struct Probing {
    probe: Option<Box<Probe>>,
    /// Probes started so far (at most `verdict::MAX_PROBES`).
    count: u32,
    /// The first transient period after which a probe may start: later
    /// from the static equilibrium, whose transient from rest can look
    /// chaotic for dozens of periods (`verdict::PROBE_FROM_REST`).
    from: u32,
    /// Its finished probe's evidence, and the neighbour's steps.
    lyapunov: Option<LyapunovEvidence>,
    steps: u64,
}

impl SteadyRun {
    /// A run of `model` with `opts` from `start` (or the static
    /// equilibrium), before its first step; bad options are refused here.
    pub fn new(model: &Model, opts: &SteadyOptions, start: Option<&[f64]>) -> Result<Self> {
        opts.validate()?;
        let sys = &model.system;
        let omega_rad_s = opts.omega * sys.omega_ref_rad_s;
        let period = 2.0 * PI / omega_rad_s;
        let mut ode = MeshOde::new(sys, omega_rad_s);
        let y0 = match start {
            Some(y) if y.len() == 2 * sys.dof() && y.iter().all(|v| v.is_finite()) => y.to_vec(),
            _ => model.static_state(),
        };
        let tol = tolerances(sys, opts.omega, opts.rtol, opts.atol_m, period, 1e-13);
        let int = Dopri5::new(&mut ode, 0.0, &y0, period / 200.0, tol.clone());
        let n_mesh = sys.meshes.len();
        let budget = opts
            .max_steps_per_period
            .saturating_mul(u64::from(opts.transient_periods) + u64::from(opts.record_periods) + 1);
        Ok(SteadyRun {
            opts: opts.clone(),
            ode,
            int,
            tol,
            facts: RunFacts {
                omega_rad_s,
                period,
                bound_m: model.divergence_bound_m(),
                budget,
                linear: model.is_linear(),
            },
            settling: Settling {
                rho_modal: (-model.modes.slowest_decay_rate(sys.omega_ref_rad_s) * period).exp(),
                poincare_hist: Vec::new(),
                span: SpanTracker::new(n_mesh),
                deflections: vec![0.0; n_mesh],
                pipe_hist: Vec::new(),
                settled: false,
            },
            periods_run: 0,
            phase: Phase::Transient { p: 1 },
            shooting: ShootingLog::default(),
            probing: Probing {
                probe: None,
                count: 0,
                from: if start.is_some() { 0 } else { PROBE_FROM_REST },
                lyapunov: None,
                steps: 0,
            },
            window: None,
        })
    }

    /// A run continued from `from`: the end state of a previous run (the
    /// previous point of a sweep or of a map's row, a small step away in
    /// Omega) and whether that run found chaos
    /// ([`SteadyState::found_chaos`]); `None` starts from the static
    /// equilibrium, as [`SteadyRun::new`]. After chaos the Lyapunov probe
    /// and the recording start at once, before the first transient period:
    /// the state lies on or next to a chaotic attractor, so the first
    /// checkpoint's transient would only delay the probe, which must run
    /// anyway. Should the motion here not be chaotic, the probe says so and
    /// the run goes back to its transient and its candidate period as after
    /// any probe (the probed periods then count as transient). Without
    /// shooting, or with a transient budget of 0, the hint changes nothing.
    pub fn continued(
        model: &Model,
        opts: &SteadyOptions,
        from: Option<(&[f64], bool)>,
    ) -> Result<Self> {
        let mut run = SteadyRun::new(model, opts, from.map(|(y, _)| y))?;
        let after_chaos = from.is_some_and(|(_, chaos)| chaos);
        if after_chaos && opts.shooting && opts.transient_periods > 0 && !run.facts.linear {
            run.start_probe(model)?;
        }
        Ok(run)
    }

    /// Integrator steps taken so far (shooting's included).
    pub fn steps(&self) -> u64 {
        self.int.stats.steps
            + self.shooting.steps
            + self.probing.steps
            + self.probing.probe.as_ref().map_or(0, |p| p.steps())
    }

    /// Whether the run has returned its result or failed.
    pub fn is_done(&self) -> bool {
        matches!(self.phase, Phase::Done)
    }

    /// Continues the run for at most `max_steps` integrator steps (at least
    /// one): `Ok(Some(state))` once it is complete, `Ok(None)` if paused.
    /// `model` must be the run's own (the one given to [`SteadyRun::new`]).
    /// After the result or an error the run is done, and further calls
    /// return `Ok(None)` without work.
    pub fn advance(&mut self, model: &Model, max_steps: u64) -> Result<Option<SteadyState>> {
        let r = self.advance_inner(model, max_steps.max(1));
        if !matches!(r, Ok(None)) {
            self.phase = Phase::Done;
        }
        r
    }

    fn advance_inner(&mut self, model: &Model, max_steps: u64) -> Result<Option<SteadyState>> {
        let dof = model.system.dof();
        let mut steps = 0u64;
        loop {
            match &mut self.phase {
                Phase::Done => return Ok(None),
                Phase::Finish { .. } => {
                    let Phase::Finish { t_rec, rec } =
                        std::mem::replace(&mut self.phase, Phase::Done)
                    else {
                        return Ok(None);
                    };
                    return Ok(Some(self.finish(model, t_rec, *rec)));
                }
                Phase::Transient { p } if *p > self.opts.transient_periods => {
                    self.start_recording(model);
                }
                Phase::Transient { p } => {
                    let p_now = *p;
                    let t_end = f64::from(p_now) * self.facts.period;
                    while self.int.t() < t_end {
                        if steps >= max_steps {
                            return Ok(None);
                        }
                        self.int
                            .step(&mut self.ode, t_end)
                            .map_err(|e| model.explain_failure(&self.ode, &self.int, e))?;
                        steps += 1;
                        guard(&self.int, self.facts.budget)?;
                        if self.opts.early_settle || self.opts.shooting {
                            self.ode
                                .deflections(&self.int.y()[..dof], &mut self.settling.deflections);
                            self.settling.span.add(&self.settling.deflections);
                        }
                    }
                    self.periods_run = p_now;
                    model.check_bounded(
                        &self.ode,
                        self.int.t(),
                        self.int.y(),
                        self.facts.bound_m,
                    )?;
                    self.phase = Phase::Transient { p: p_now + 1 };
                    let span_um = self.settling.span.span_um();
                    let point = poincare_point(
                        &self.ode,
                        self.int.t(),
                        self.int.y(),
                        self.facts.omega_rad_s,
                    );
                    if self.opts.shooting {
                        self.settling.pipe_hist.push(point.clone());
                        if self.settling.pipe_hist.len() > 2 * MAX_PERIOD + 1 {
                            self.settling.pipe_hist.remove(0);
                        }
                    }
                    if self.opts.early_settle {
                        let hist = &mut self.settling.poincare_hist;
                        hist.push(point);
                        if hist.len() > SETTLE_DISTANCES * 8 + 1 {
                            hist.remove(0);
                        }
                        let tol = settle_tol_um(span_um);
                        if p_now >= 5 && has_settled(hist, tol, self.settling.rho_modal) {
                            self.settling.settled = true;
                            let candidate = if self.facts.linear {
                                Some(1)
                            } else {
                                candidate_period(&self.settling.pipe_hist, 10.0 * tol)
                            };
                            match candidate {
                                Some(n) if self.opts.shooting => {
                                    self.start_shooting(model, n, span_um, true)?;
                                }
                                _ => self.start_recording(model),
                            }
                            continue;
                        }
                    }
                    if self.opts.shooting && CHECKPOINTS.contains(&p_now) {
                        if let Some(n) = self.checkpoint_candidate(span_um) {
                            self.settling.span.reset_keep_last();
                            self.start_shooting(model, n, span_um, false)?;
                            continue;
                        }
                        if self.may_probe() {
                            self.settling.span.reset_keep_last();
                            self.start_probe(model)?;
                            continue;
                        }
                    }
                    self.settling.span.reset_keep_last();
                }
                Phase::Shoot {
                    run,
                    period,
                    settled,
                } => {
                    let (n, settled) = (*period, *settled);
                    if steps >= max_steps {
                        return Ok(None);
                    }
                    let before = run.steps();
                    let out = run.advance(max_steps - steps.min(max_steps));
                    let taken = run.steps() - before;
                    steps += taken;
                    self.shooting.steps += taken;
                    let Some(out) = out? else {
                        return Ok(None);
                    };
                    self.after_shooting(model, out, n, settled)?;
                    if steps >= max_steps && !matches!(self.phase, Phase::Done) {
                        return Ok(None);
                    }
                }
                Phase::Record { r, t_rec, rec } => {
                    let t_end = *t_rec + f64::from(*r) * self.facts.period;
                    while self.int.t() < t_end {
                        if steps >= max_steps {
                            return Ok(None);
                        }
                        let info = self
                            .int
                            .step(&mut self.ode, t_end)
                            .map_err(|e| model.explain_failure(&self.ode, &self.int, e))?;
                        steps += 1;
                        guard(&self.int, self.facts.budget)?;
                        rec.on_step(&self.ode, &self.int, info);
                    }
                    if let Some(pr) = &mut self.probing.probe {
                        loop {
                            if steps >= max_steps {
                                return Ok(None);
                            }
                            if !pr.step_towards(model, t_end)? {
                                break;
                            }
                            steps += 1;
                        }
                    }
                    model.check_bounded(
                        &self.ode,
                        self.int.t(),
                        self.int.y(),
                        self.facts.bound_m,
                    )?;
                    rec.on_period(
                        &self.ode,
                        self.int.t(),
                        self.int.y(),
                        self.facts.omega_rad_s,
                    );
                    let r_now = *r;
                    let target = self.record_target();
                    if self.probing.probe.is_some() && self.probe_period(model, r_now, target)? {
                        continue;
                    }
                    let Phase::Record { r, t_rec, .. } = &mut self.phase else {
                        continue;
                    };
                    if *r < target {
                        *r += 1;
                    } else {
                        let t_rec = *t_rec;
                        let Phase::Record { rec, .. } =
                            std::mem::replace(&mut self.phase, Phase::Done)
                        else {
                            return Ok(None);
                        };
                        let mut rec = *rec;
                        if let Some(n) = self.shooting.exact.as_ref().and_then(Motion::period) {
                            rec.repeat_poincare(n as usize, self.opts.record_periods as usize);
                        } else if let Some(n) = self.period_to_confirm(&rec) {
                            self.confirm_window(model, t_rec, rec, n, target);
                            continue;
                        }
                        return Ok(Some(self.finish(model, t_rec, rec)));
                    }
                }
            }
        }
    }

    /// Ends the transient: the recorded window starts at the last whole period.
    fn start_recording(&mut self, model: &Model) {
        let t_rec = f64::from(self.periods_run) * self.facts.period;
        let rec = Recorder::new(
            model,
            &self.ode,
            &self.opts,
            t_rec,
            self.facts.period,
            self.int.y(),
        );
        self.phase = Phase::Record {
            r: 1,
            t_rec,
            rec: Box::new(rec),
        };
    }

    fn finish(&self, model: &Model, t_rec: f64, rec: Recorder) -> SteadyState {
        let end_state = self.int.y().to_vec();
        let (period_detected, recorded) = window_verdict(&rec);
        let (meshes, histories, times) = rec.finish(model);
        let motion = match &self.shooting.exact {
            // The recorded points may show a shorter period that divides
            // the one shot for (the orbit repeats sooner).
            Some(Motion::PeriodicExact {
                period,
                max_multiplier_modulus,
                newton_iterations,
            }) => Motion::PeriodicExact {
                period: period_detected
                    .filter(|d| period % d == 0)
                    .unwrap_or(*period),
                max_multiplier_modulus: *max_multiplier_modulus,
                newton_iterations: *newton_iterations,
            },
            _ => recorded,
        };
        SteadyState {
            omega: self.opts.omega,
            omega_rad_s: self.facts.omega_rad_s,
            mesh_freq_hz: self.facts.omega_rad_s / (2.0 * PI),
            period_s: self.facts.period,
            record_start_s: t_rec,
            meshes,
            sample_times_s: times,
            histories,
            end_state,
            period: motion.period(),
            motion,
            shooting_note: self.shooting.note.clone(),
            lyapunov: self.probing.lyapunov,
            stats: SteadyStats {
                transient_periods_run: self.periods_run,
                settled: self.settling.settled,
                integrator: self.int.stats,
                shooting_attempts: self.shooting.attempts,
                shooting_steps: self.shooting.steps,
                probe_steps: self.probing.steps,
            },
        }
    }
}

fn guard(int: &Dopri5, budget: u64) -> Result<()> {
    if int.stats.steps > budget {
        return Err(SolverError::TooManySteps {
            max_steps: budget,
            t_s: int.t(),
        });
    }
    Ok(())
}

/// The Poincaré point in mesh space: each mesh's delta and delta'/omega in um.
fn poincare_point(ode: &MeshOde, t: f64, y: &[f64], omega_rad_s: f64) -> Vec<f64> {
    let mut p = Vec::with_capacity(2 * ode.n_meshes());
    for j in 0..ode.n_meshes() {
        let mi = ode.mesh_instant(j, t, y);
        p.push(mi.delta * 1e6);
        p.push(mi.delta_dot / omega_rad_s * 1e6);
    }
    p
}
