//! Branches of periodic orbits by shooting: pseudo-arclength continuation
//! in Omega of period-n orbits, with folds and period doublings located
//! and the period-doubled branch followed (`gearshock frf --method shooting`).
//!
//! The unknowns are `Y = (z, W Omega)`: the orbit's reduced start point
//! ([`crate::shooting::Reduced`], µm) and Omega weighted by `W` (the start
//! orbit's size over the Omega range), so that a step of length `ds` moves
//! the orbit and the frequency alike. The residual is `G = P^n(z) - z`;
//! its Jacobian is `[Phi - I, dG/dOmega / W]`, the monodromy `Phi` from the
//! variational equations and `dG/dOmega` by central differences. Each step
//! predicts along the unit tangent (the null vector of the Jacobian,
//! oriented as the previous one) and corrects by Newton on `G = 0` and the
//! hyperplane through the prediction normal to the tangent; the step grows
//! by 1.5 after an easy correction and halves after a failed one.
//!
//! Bifurcations between two points: a fold where the tangent's Omega
//! component changes sign, a period doubling where the count of real
//! multipliers below -1 changes, a Neimark–Sacker point where the count of
//! complex multipliers outside the unit circle changes. Folds and period
//! doublings are located on the branch by the Illinois method on the test
//! function (the tangent's Omega component, the real multiplier nearest
//! -1 plus one) until the bracket spans less than 1e-7 in Omega. At a
//! period doubling the period-2n branch is started from the located orbit
//! along the multiplier's eigenvector (the new branch leaves the old one
//! at right angles, in z) and followed until it leaves the range or
//! doubles again.

use crate::bifurcation::Bifurcation;
use crate::error::{Result, SolverError};
use crate::hbm::{BranchPoint, LeftOut, PieceEnd, Restart};
use crate::shooting::floquet::{real_eigenvector, Multipliers};
use crate::shooting::{shoot, Reduced, ShootOptions, ShootOutcome, MAX_SHOOT_PERIOD};
use crate::steady::{steady_state, SteadyOptions};
use crate::sweep::Direction;
use crate::Model;
use nalgebra::{DMatrix, DVector};
use replay::{Halt, Replay, Step};

mod chord;
mod estimate;
mod locate;
mod pieces;
mod replay;

use chord::Jacobian;
pub use estimate::ShootEstimate;

/// Options of a shooting frequency response.
#[derive(Debug, Clone, PartialEq)]
pub struct ShootFrfSpec {
    /// Start of the Omega range.
    pub omega_from: f64,
    /// End of the Omega range.
    pub omega_to: f64,
    /// Resolution: a step moves Omega by about `range / points` where the
    /// branch is flat.
    pub points: u32,
    /// Continue up from `omega_from` or down from `omega_to`.
    pub direction: Direction,
    /// Period of the first branch (mesh periods).
    pub period: u32,
    /// Follow the period-doubled branch at each period doubling.
    pub switch_branches: bool,
    /// Newton and integrator options (the period is set per branch).
    pub shooting: ShootOptions,
}

impl ShootFrfSpec {
    /// Defaults: period 1, branch switching on, up.
    pub fn new(omega_from: f64, omega_to: f64, points: u32) -> Self {
        let mut shooting = ShootOptions::new(1);
        shooting.rtol = 1e-10;
        shooting.atol_m = 1e-13;
        // The first orbit by plain Newton, as the branch's own corrector.
        shooting.broyden = false;
        ShootFrfSpec {
            omega_from,
            omega_to,
            points,
            direction: Direction::Up,
            period: 1,
            switch_branches: true,
            shooting,
        }
    }

    /// Checks the options.
    pub fn validate(&self) -> Result<()> {
        for (name, v) in [("omega-from", self.omega_from), ("omega-to", self.omega_to)] {
            if !(v.is_finite() && (0.01..=20.0).contains(&v)) {
                return SolverError::bad_option(name, format!("{v}"), "0.01 ..= 20");
            }
        }
        if self.omega_to <= self.omega_from {
            return SolverError::bad_option(
                "omega-to",
                format!("{}", self.omega_to),
                "> omega-from",
            );
        }
        if self.points < 2 || self.points > 100_000 {
            return SolverError::bad_option("points", self.points.to_string(), "2 ..= 100000");
        }
        let mut o = self.shooting.clone();
        o.period = self.period;
        o.validate()
    }
}

/// One point of a shooting branch.
#[derive(Debug, Clone, PartialEq)]
pub struct ShootPoint {
    /// The point in the harmonic-balance branch's form (`coefficients`
    /// holds the reduced start point `z`; `harmonics_m` is empty).
    pub point: BranchPoint,
    /// Period of the orbit (mesh periods).
    pub period: u32,
}

/// Work counters.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
pub struct ShootFrfStats {
    /// Points emitted (located bifurcations included).
    pub points: u64,
    /// Corrector iterations.
    pub newton_iterations: u64,
    /// Steps halved after a failed correction.
    pub rejected_steps: u64,
    /// Integrator steps over every evaluation.
    pub integrator_steps: u64,
    /// The work of those steps, in integration steps: a step carrying the
    /// monodromy's `n` tangent vectors counts `1 + n` (as
    /// [`ShootingContinuation::advance_within`] charges it).
    pub work_steps: u64,
    /// Evaluations of the map that failed (a predictor far out of range,
    /// a blow-up), counted as the one-shot run counts them however a run
    /// is sliced.
    pub failed_evaluations: u64,
}

/// A branch being followed.
#[derive(Debug, Clone)]
struct Cursor {
    period: u32,
    piece: u32,
    y: Vec<f64>,
    tangent: Vec<f64>,
    ds: f64,
    /// Test functions at `y`.
    pd_count: usize,
    ns_count: usize,
    stable: bool,
    /// Points on this branch so far.
    count: u32,
    /// A switched branch: it stops at its first period doubling, and where
    /// its orbit repeats after half its period (it has joined the branch it
    /// came from).
    doubles_again: bool,
    /// The Jacobian at `y`, the chord corrector's first matrix (`None` at a
    /// switched branch's start: full Newton there).
    jac: Option<Jacobian>,
    /// A piece of the first branch (the spec's period), which must cover
    /// the range; a doubled branch is not.
    main: bool,
    /// The direction a piece of the first branch set out in.
    dir: Direction,
}

/// A point solved on the branch: `Y`, residual size, monodromy, `dG/dOmega`.
#[derive(Debug, Clone)]
struct Solved {
    y: Vec<f64>,
    monodromy: DMatrix<f64>,
    g_omega: Vec<f64>,
    iterations: usize,
    /// Whether the chord corrector found it (`chord.rs`).
    chord: bool,
}

/// The shooting continuation: bounded work per [`ShootingContinuation::advance`].
#[derive(Debug, Clone)]
pub struct ShootingContinuation {
    model: Model,
    spec: ShootFrfSpec,
    weight: f64,
    ds_max: f64,
    cur: Option<Cursor>,
    /// Branches to follow after the current one.
    pending: Vec<Cursor>,
    pieces: u32,
    /// How each branch ended, and every restart and gap, in words.
    notes: Vec<String>,
    /// The Omega span of every piece of the first branch: `(piece, lo, hi)`.
    spans: Vec<(u32, f64, f64)>,
    /// Restarts of the first branch where a piece ended early.
    restarts: Vec<Restart>,
    /// Parts of the range no piece of the first branch covers.
    left_out: Vec<LeftOut>,
    /// Omega of restarts whose first orbit was not found.
    failed_starts: Vec<f64>,
    /// Counters.
    pub stats: ShootFrfStats,
    /// The integrations of the step in progress (bounded work per call).
    replay: Replay,
}

/// The right-hand side of a branch corrector's step at `y`: minus the
/// residual `g`, and minus the distance of `y` from the hyperplane through
/// `pred` normal to `t`.
fn newton_rhs(g: &[f64], t: &[f64], y: &[f64], pred: &[f64]) -> DVector<f64> {
    let n = g.len();
    let mut rhs = DVector::zeros(n + 1);
    for r in 0..n {
        rhs[r] = -g[r];
    }
    rhs[n] = -(0..=n).map(|i| t[i] * (y[i] - pred[i])).sum::<f64>();
    rhs
}

/// Largest number of points on one branch (a guard against a loop).
const MAX_BRANCH_POINTS: u32 = 5_000;

/// Farthest a corrected point may lie from the last one, in steps.
const MAX_JUMP: f64 = 2.0;

/// The Euclidean distance between two points of the unknowns.
fn distance(a: &[f64], b: &[f64]) -> f64 {
    a.iter()
        .zip(b)
        .map(|(x, y)| (x - y) * (x - y))
        .sum::<f64>()
        .sqrt()
}

impl ShootingContinuation {
    /// Finds the first orbit at the range's start and its tangent.
    pub fn new(model: &Model, spec: ShootFrfSpec) -> Result<Self> {
        spec.validate()?;
        let omega0 = match spec.direction {
            Direction::Up => spec.omega_from,
            Direction::Down => spec.omega_to,
        };
        let mut opts = spec.shooting.clone();
        opts.period = spec.period;
        // The first orbit's Newton integrates the monodromy at every
        // iterate (no Broyden): its steps count as carrying the tangents.
        let tangent_cost = 1 + Reduced::new(model, omega0).dim() as u64;
        let steps_of = |o: &ShootOutcome| match o {
            ShootOutcome::Converged(o) => o.steps,
            ShootOutcome::Failed(f) => f.steps,
        };
        let mut out = shoot(model, omega0, &model.static_state(), &opts)?;
        let mut first_work = steps_of(&out) * tangent_cost;
        if !matches!(out, ShootOutcome::Converged(_)) {
            // From the static state Newton may be too far: settle a while first.
            let mut so = SteadyOptions::new(omega0);
            so.record_periods = 1;
            so.samples_per_period = 0;
            let ss = steady_state(model, &so, None)?;
            out = shoot(model, omega0, &ss.end_state, &opts)?;
            first_work += ss.stats.integrator.steps + steps_of(&out) * tangent_cost;
        }
        let orbit = match out {
            ShootOutcome::Converged(o) => o,
            ShootOutcome::Failed(f) => {
                return Err(SolverError::NotConverged {
                    omega: omega0,
                    residual: f.residual_um,
                    iterations: f.iterations as usize,
                })
            }
        };
        let range = spec.omega_to - spec.omega_from;
        let size = orbit.z.iter().map(|v| v * v).sum::<f64>().sqrt().max(1.0);
        let weight = size / range;
        let ds_max = 1.5 * weight * range / f64::from(spec.points);
        let mut y = orbit.z.clone();
        y.push(omega0 * weight);
        let sign = if spec.direction == Direction::Up {
            1.0
        } else {
            -1.0
        };
        let mut t0 = vec![0.0; y.len()];
        t0[y.len() - 1] = sign;
        let mut me = ShootingContinuation {
            model: model.clone(),
            spec,
            weight,
            ds_max,
            cur: None,
            pending: Vec::new(),
            pieces: 0,
            notes: Vec::new(),
            spans: Vec::new(),
            restarts: Vec::new(),
            left_out: Vec::new(),
            failed_starts: Vec::new(),
            stats: ShootFrfStats {
                work_steps: first_work,
                ..ShootFrfStats::default()
            },
            replay: Replay::default(),
        };
        let (_, solved) = me.unbounded(|me| me.evaluate(&y, me.spec.period))?;
        let tangent = me.tangent(&solved, &t0).ok_or(SolverError::Singular {
            what: "the continuation's tangent at the first orbit".into(),
        })?;
        let m = Multipliers::of(&solved.monodromy);
        me.cur = Some(Cursor {
            period: me.spec.period,
            piece: 0,
            y,
            tangent,
            ds: 0.25 * ds_max,
            pd_count: m.as_ref().map_or(0, pd_count),
            ns_count: m.as_ref().map_or(0, ns_count),
            stable: m.as_ref().is_some_and(Multipliers::is_stable),
            count: 0,
            doubles_again: false,
            jac: Some(Jacobian::of(&solved)),
            main: true,
            dir: me.spec.direction,
        });
        Ok(me)
    }

    /// The spec.
    pub fn spec(&self) -> &ShootFrfSpec {
        &self.spec
    }

    /// Notes on how branches ended, where the first branch was restarted
    /// and what it left out.
    pub fn notes(&self) -> &[String] {
        &self.notes
    }

    /// Whether every branch has ended.
    pub fn is_finished(&self) -> bool {
        self.cur.is_none() && self.pending.is_empty()
    }

    /// The first point (to emit before continuing).
    pub fn first_point(&mut self) -> Result<ShootPoint> {
        let Some(c) = self.cur.clone() else {
            return Err(SolverError::Singular {
                what: "no branch".into(),
            });
        };
        self.unbounded(|me| {
            let (_, solved) = me.evaluate(&c.y, c.period)?;
            me.emit(&solved, c.period, c.piece, None)
        })
    }

    /// Runs `f` with no work bound (it cannot pause).
    fn unbounded<T>(&mut self, f: impl FnOnce(&mut Self) -> Step<T>) -> Result<T> {
        self.replay.begin(u64::MAX);
        let out = f(self);
        self.replay.finish();
        match out {
            Ok(v) => Ok(v),
            Err(Halt::Fail(e)) => Err(e),
            Err(Halt::Pause) => Err(SolverError::Singular {
                what: "an unbounded evaluation paused".into(),
            }),
        }
    }

    /// Computes at most `k` further points (located bifurcations count).
    pub fn advance(&mut self, k: usize) -> Result<Vec<ShootPoint>> {
        self.advance_within(k, u64::MAX)
    }

    /// Computes at most `k` further points with at most about `work`
    /// integrator steps of new integration (a step carrying the monodromy's
    /// tangents counts one per vector, plus one): when the work runs out in
    /// the middle of a branch step, the points finished so far are
    /// returned and the next call takes the step up again where it paused
    /// (`replay.rs`), so that slices of any size give the same points as
    /// one call. [`Self::is_finished`] says when every branch has ended.
    pub fn advance_within(&mut self, k: usize, work: u64) -> Result<Vec<ShootPoint>> {
        let mut out = Vec::new();
        self.replay.begin(work);
        while out.len() < k {
            if self.cur.is_none() {
                match self.pending.pop() {
                    Some(c) => self.cur = Some(c),
                    None => break,
                }
            }
            let saved = (
                self.cur.clone(),
                self.pending.clone(),
                self.pieces,
                self.notes.len(),
                self.stats,
                self.coverage(),
            );
            let mut step_out = Vec::new();
            match self.step(&mut step_out) {
                Ok(()) => {
                    self.replay.finish();
                    out.extend(step_out);
                }
                Err(Halt::Pause) => {
                    let (cur, pending, pieces, notes, stats, coverage) = saved;
                    self.cur = cur;
                    self.pending = pending;
                    self.pieces = pieces;
                    self.notes.truncate(notes);
                    self.stats = stats;
                    self.restore(coverage);
                    break;
                }
                Err(Halt::Fail(e)) => {
                    self.replay.finish();
                    return Err(e);
                }
            }
        }
        Ok(out)
    }

    fn omega_of(&self, y: &[f64]) -> f64 {
        y[y.len() - 1] / self.weight
    }

    fn in_range(&self, omega: f64) -> bool {
        (self.spec.omega_from..=self.spec.omega_to).contains(&omega)
    }

    /// One step of the current branch.
    fn step(&mut self, out: &mut Vec<ShootPoint>) -> Step<()> {
        let Some(mut c) = self.cur.take() else {
            return Ok(());
        };
        let ds_min = self.ds_max * 1e-5;
        let solved = loop {
            let pred: Vec<f64> =
                c.y.iter()
                    .zip(&c.tangent)
                    .map(|(y, t)| y + c.ds * t)
                    .collect();
            // A corrected point farther from the last than `MAX_JUMP`
            // steps has jumped to another part of the branch (a period-2
            // piece went from Omega 0.5764 to 0.7520 in one step): the
            // step is retried shorter, as where the corrector fails.
            if let Some(s) = self.correct(&pred, &c.tangent, c.period, c.jac.as_ref())? {
                if distance(&s.y, &c.y) <= MAX_JUMP * c.ds {
                    break s;
                }
            }
            self.stats.rejected_steps += 1;
            c.ds *= 0.5;
            if c.ds < ds_min {
                let omega = self.omega_of(&c.y);
                self.notes.push(format!(
                    "the period-{} branch stalled at Omega {omega:.6}: the corrector failed at ever smaller steps",
                    c.period,
                ));
                return self.end_piece(&c, PieceEnd::Failed, omega, out);
            }
        };
        let omega = self.omega_of(&solved.y);
        let Some(tangent) = self.tangent(&solved, &c.tangent) else {
            self.notes.push(format!(
                "the period-{} branch ended at Omega {omega:.6}: singular tangent",
                c.period
            ));
            return self.end_piece(&c, PieceEnd::Failed, omega, out);
        };
        let m = Multipliers::of(&solved.monodromy);
        let (pd, ns) = (
            m.as_ref().map_or(0, pd_count),
            m.as_ref().map_or(0, ns_count),
        );
        // A switched branch leaves at right angles (its first tangent has
        // no Omega part): no fold is read from its first points.
        let fold = c.tangent[c.y.len() - 1] * tangent[c.y.len() - 1] < 0.0
            && !(c.doubles_again && c.count < 2);
        // Where a switched branch turns back with its two halves close, it
        // is passing the period doubling that ends it (the other end of a
        // bubble), not a fold of period-2n orbits.
        let joined = c.doubles_again
            && ((c.count >= 2 && self.repeats_at_half(&solved.y, c.period, 1e-3)?)
                || (fold && self.repeats_at_half(&solved.y, c.period, 1e-2)?));
        if joined {
            self.notes.push(format!(
                "the period-{} branch joined the period-{} branch at Omega {omega:.6}",
                c.period,
                c.period / 2
            ));
            return Ok(());
        }
        // Locate what lies between the points, in arclength order.
        if fold && self.in_range(omega) {
            if let Some(at) = self.locate(&c, &solved)? {
                // A doubled branch turns back where it rejoins the branch it
                // left: there its orbit repeats after half its period, and
                // the turn is that branch's period doubling, not a fold.
                if c.doubles_again && self.repeats_at_half(&at.y, c.period, 1e-2)? {
                    out.push(self.emit(
                        &at,
                        c.period,
                        c.piece,
                        Some(Bifurcation::PeriodDoubling),
                    )?);
                    self.notes.push(format!(
                        "the period-{} branch rejoined the period-{} branch at its period doubling at Omega {:.6}",
                        c.period,
                        c.period / 2,
                        self.omega_of(&at.y)
                    ));
                    return Ok(());
                }
                out.push(self.emit(&at, c.period, c.piece, Some(Bifurcation::Fold))?);
            }
        }
        if pd != c.pd_count && self.in_range(omega) {
            if let Some((p, at_pd)) = self.locate_pd(&c, &solved)? {
                let (y_pd, mono) = (at_pd.y, at_pd.monodromy);
                out.push(p);
                if c.doubles_again {
                    self.notes.push(format!(
                        "the period-{} branch doubles again at Omega {:.6}; followed no further",
                        c.period,
                        self.omega_of(&y_pd)
                    ));
                    return Ok(());
                }
                let old = match self.evaluate(&y_pd, c.period) {
                    Ok((_, s)) => self.tangent(&s, &c.tangent),
                    Err(Halt::Pause) => return Err(Halt::Pause),
                    Err(Halt::Fail(_)) => None,
                };
                self.switch(&c, &y_pd, &mono, old.as_deref());
            }
        }
        let label = (ns != c.ns_count).then_some(Bifurcation::NeimarkSacker);
        if !self.in_range(omega) {
            return self.leave_range(&c, &solved, out);
        }
        out.push(self.emit(&solved, c.period, c.piece, label)?);
        c.count += 1;
        let easy = if solved.chord { chord::CHORD_EASY } else { 3 };
        if solved.iterations <= easy {
            c.ds = (c.ds * 1.5).min(self.ds_max);
        }
        c.jac = Some(Jacobian::of(&solved));
        c.y = solved.y;
        c.tangent = tangent;
        c.pd_count = pd;
        c.ns_count = ns;
        c.stable = m.as_ref().is_some_and(Multipliers::is_stable);
        if c.count >= MAX_BRANCH_POINTS {
            let omega = self.omega_of(&c.y);
            self.notes.push(format!(
                "the period-{} branch reached {MAX_BRANCH_POINTS} points at Omega {omega:.6}",
                c.period
            ));
            return self.end_piece(&c, PieceEnd::PointLimit, omega, out);
        }
        // A restarted piece ends where it meets the branch already followed.
        if c.main && c.piece > 0 && self.coverage_gaps().is_empty() {
            self.notes.push(format!(
                "the period-{} branch's piece {} met the part already followed at Omega {:.6}",
                c.period,
                c.piece,
                self.omega_of(&c.y)
            ));
            return Ok(());
        }
        self.cur = Some(c);
        Ok(())
    }

    /// Queues the period-2n branch from the period doubling at `y_pd`.
    /// The new branch's first tangent is the eigenvector made orthogonal to
    /// the old branch's tangent `old`, so that the corrector's hyperplane
    /// does not cut the old branch near the bifurcation.
    fn switch(&mut self, c: &Cursor, y_pd: &[f64], mono: &DMatrix<f64>, old: Option<&[f64]>) {
        if !self.spec.switch_branches || 2 * c.period > MAX_SHOOT_PERIOD {
            return;
        }
        let Some(e) = real_eigenvector(mono, -1.0) else {
            return;
        };
        let mut t: Vec<f64> = e.iter().copied().collect();
        t.push(0.0);
        if let Some(old) = old {
            let d: f64 = t.iter().zip(old).map(|(a, b)| a * b).sum();
            t.iter_mut().zip(old).for_each(|(a, b)| *a -= d * b);
            let norm = t.iter().map(|v| v * v).sum::<f64>().sqrt();
            if norm > 1e-6 {
                t.iter_mut().for_each(|v| *v /= norm);
            }
        }
        self.pieces += 1;
        self.pending.push(Cursor {
            period: 2 * c.period,
            piece: self.pieces,
            y: y_pd.to_vec(),
            tangent: t,
            ds: 0.25 * self.ds_max,
            pd_count: 0,
            ns_count: 0,
            stable: false,
            count: 0,
            doubles_again: true,
            jac: None,
            main: false,
            dir: self.spec.direction,
        });
    }

    /// The residual `G` at `y`, and the point with its monodromy and
    /// `dG/dOmega` (central differences).
    fn evaluate(&mut self, y: &[f64], period: u32) -> Step<(Vec<f64>, Solved)> {
        let n = y.len() - 1;
        let omega = self.omega_of(y);
        let (g, mono) = self.map(&y[..n], omega, period, true)?;
        let h = 1e-5 * omega;
        let (gp, _) = self.map(&y[..n], omega + h, period, false)?;
        let (gm, _) = self.map(&y[..n], omega - h, period, false)?;
        let g_omega = gp
            .iter()
            .zip(&gm)
            .map(|(a, b)| (a - b) / (2.0 * h))
            .collect();
        let solved = Solved {
            y: y.to_vec(),
            monodromy: mono.unwrap_or_else(|| DMatrix::zeros(n, n)),
            g_omega,
            iterations: 0,
            chord: false,
        };
        Ok((g, solved))
    }

    /// Whether the period-`period` orbit at `y` repeats after half its
    /// period within `rel` (1e-3) of its size in mesh space: the period-doubled
    /// orbit's two halves split like the square root of the distance in
    /// Omega from a period doubling, so this is within about 1e-6 of the
    /// period doubling where the branch rejoins the one it left.
    fn repeats_at_half(&mut self, y: &[f64], period: u32, rel: f64) -> Step<bool> {
        let n = y.len() - 1;
        let omega = self.omega_of(y);
        let g = match self.map(&y[..n], omega, period / 2, false) {
            Ok((g, _)) => g,
            Err(Halt::Pause) => return Err(Halt::Pause),
            Err(Halt::Fail(_)) => return Ok(false),
        };
        let red = Reduced::new(&self.model, omega);
        Ok(red.mesh_norm_um(&g) <= rel * red.mesh_norm_um(&y[..n]))
    }

    fn residual_tol(&self, z: &[f64], omega: f64) -> f64 {
        let red = Reduced::new(&self.model, omega);
        self.spec.shooting.tol_abs_um + self.spec.shooting.tol_rel * red.mesh_norm_um(z)
    }

    /// Newton on `G(Y) = 0`, `t . (Y - pred) = 0`; `None` if it fails. With
    /// `jac` (the last solved point's), the chord corrector first
    /// (`chord.rs`); full Newton where it gives up or without one.
    fn correct(
        &mut self,
        pred: &[f64],
        t: &[f64],
        period: u32,
        jac: Option<&Jacobian>,
    ) -> Step<Option<Solved>> {
        if let Some(jac) = jac {
            if let Some(solved) = self.correct_chord(pred, t, period, jac)? {
                return Ok(Some(solved));
            }
        }
        let n = pred.len() - 1;
        let mut y = pred.to_vec();
        for it in 0..8 {
            let omega = self.omega_of(&y);
            if !(0.01..=20.0).contains(&omega) {
                return Ok(None);
            }
            let (g, solved) = match self.evaluate(&y, period) {
                Ok(v) => v,
                Err(Halt::Pause) => return Err(Halt::Pause),
                Err(Halt::Fail(_)) => return Ok(None),
            };
            self.stats.newton_iterations += 1;
            let red = Reduced::new(&self.model, omega);
            if red.mesh_norm_um(&g) <= self.residual_tol(&y[..n], omega) {
                return Ok(Some(Solved {
                    iterations: it,
                    ..solved
                }));
            }
            let a = self.bordered(&solved.monodromy, &solved.g_omega, t);
            let Some(dy) = crate::dense::Lu::new(a).solve(&newton_rhs(&g, t, &y, pred)) else {
                return Ok(None);
            };
            if dy.iter().any(|v| !v.is_finite()) {
                return Ok(None);
            }
            for (yi, d) in y.iter_mut().zip(dy.iter()) {
                *yi += d;
            }
        }
        Ok(None)
    }

    /// The bordered matrix `[[Phi - I, dG/dOmega / W], [row]]` of the
    /// branch's Newton steps and tangents (`n + 1` square for a monodromy
    /// of size `n`; a missing derivative entry counts 0).
    fn bordered(&self, monodromy: &DMatrix<f64>, g_omega: &[f64], row: &[f64]) -> DMatrix<f64> {
        let n = monodromy.nrows();
        let mut a = DMatrix::zeros(n + 1, n + 1);
        for r in 0..n {
            for col in 0..n {
                a[(r, col)] = monodromy[(r, col)] - if r == col { 1.0 } else { 0.0 };
            }
            a[(r, n)] = g_omega.get(r).copied().unwrap_or(0.0) / self.weight;
        }
        for col in 0..=n {
            a[(n, col)] = row.get(col).copied().unwrap_or(0.0);
        }
        a
    }

    /// The unit tangent at a solved point, oriented as `prev`.
    fn tangent(&self, s: &Solved, prev: &[f64]) -> Option<Vec<f64>> {
        let n = s.y.len() - 1;
        let a = self.bordered(&s.monodromy, &s.g_omega, prev);
        let mut rhs = DVector::zeros(n + 1);
        rhs[n] = 1.0;
        let t = crate::dense::Lu::new(a).solve(&rhs)?;
        let norm = t.norm();
        if !(norm.is_finite() && norm > 0.0) {
            return None;
        }
        let mut t: Vec<f64> = t.iter().map(|v| v / norm).collect();
        let dot: f64 = t.iter().zip(prev).map(|(a, b)| a * b).sum();
        if dot < 0.0 {
            t.iter_mut().for_each(|v| *v = -*v);
        }
        Some(t)
    }

    /// The output point of a solved `Y`: mesh extremes over the orbit from
    /// one more integration (dense output at eight points per step).
    fn emit(
        &mut self,
        s: &Solved,
        period: u32,
        piece: u32,
        label: Option<Bifurcation>,
    ) -> Step<ShootPoint> {
        let n = s.y.len() - 1;
        let omega = self.omega_of(&s.y);
        let meshes = self.extremes(&s.y[..n], omega, period)?;
        self.cover(piece, omega);
        let m = Multipliers::of(&s.monodromy);
        self.stats.points += 1;
        Ok(ShootPoint {
            point: BranchPoint {
                omega,
                meshes,
                stable: m.as_ref().map(Multipliers::is_stable),
                multipliers: m.map(|m| m.values).unwrap_or_default(),
                bifurcation: label,
                newton_iterations: s.iterations,
                coefficients: s.y[..n].to_vec(),
                piece,
            },
            period,
        })
    }
}

/// Real multipliers below -1.
fn pd_count(m: &Multipliers) -> usize {
    m.values
        .iter()
        .filter(|v| v.im.abs() <= 1e-9 * v.norm() && v.re < -1.0)
        .count()
}

/// Complex multipliers outside the unit circle.
fn ns_count(m: &Multipliers) -> usize {
    m.values
        .iter()
        .filter(|v| v.im.abs() > 1e-9 * v.norm() && v.norm() > 1.0)
        .count()
}
