//! Harmonic balance: periodic responses as truncated Fourier series, solved by
//! Newton's method and followed in Omega by pseudo-arclength continuation,
//! with Floquet stability and bifurcation points.
//!
//! - [`model`]: the problem in scaled modal coordinates (rigid mode removed),
//!   full or reduced by the cyclic symmetry of in-phase planets.
//! - [`harmonic`]: AFT, exact integration between the contact switches, the
//!   seed's describing function, the multiplication operator.
//! - [`assembly`]: residual and analytic Jacobian.
//! - [`stability`]: monodromy matrix and Floquet multipliers.
//!
//! Newton. The corrector solves the bordered system `[R_X R_Omega; t^T]` by
//! LU; the last factorization also gives the new tangent, and on a smooth
//! residual (not AFT's) once a step is below `1e-5` of the solution's scale
//! it is kept for the next (chord) step, which then costs a residual and a
//! solve instead of a Jacobian and an LU. The fixed-
//! Omega Newton of the first and last points halves a step that does not
//! reduce the residual (down to 1/128). The corrector has converged when
//! the last step is below `1e-9` of the solution's scale (micrometres) and
//! the residual below `1e-6` of it (at the iterate before that last tiny
//! step, which only reduces it, or else at the result), and fails with
//! [`SolverError::NotConverged`] carrying Omega and the residual otherwise —
//! never a silent last iterate.
//!
//! First point. Newton at the start frequency, continued in the number of
//! harmonics (1, 2, ..., H) from the static equilibrium; if that fails (a
//! resonance zone, contact loss), the branch is continued upward from
//! Omega = 0.05, where the response is quasi-static, to the start frequency.
//! A continuation that uses `20 points + 4000` points in all stops with
//! [`SolverError::ContinuationStalled`].
//!
//! Continuation. Pseudo-arclength in `(X / (a sqrt(n)), Omega / range)` with
//! `a` three times the current RMS coefficient (at least 1 um), so that the
//! metric measures relative changes of the orbit whatever its size. The
//! step follows the curve's geometry ([`StepControl::Geometry`]): after
//! each corrector, the predictor-corrector distance `d` and the tangent's
//! turn `alpha` give the factor `f = max(sqrt(d / 1e-3), alpha / 0.1)` by
//! which the step overshot its nominal size; `f > 2` rejects the step and
//! retries it `f` times shorter (at most 4), otherwise the next step is
//! `ds / f` (growth at most 2). A step also moves Omega by at most
//! `range / points`, so `points` is a floor on the resolution of flat
//! stretches; bends, resonances and folds get what their geometry needs.
//! A sign change of the tangent's Omega component marks a fold (the branch
//! turns back: a jump); the fold is then located on the branch by the
//! Illinois variant of regula falsi on the step length (each trial a
//! corrector) until Omega settles to `1e-10`, and inserted as a point of
//! its own. Stability changes between consecutive points are labelled by
//! the multiplier that crossed the unit circle: real +1 without a turn
//! (branch point), real -1 (period doubling), complex pair (Neimark–Sacker).
//! The control before issue 14 ([`StepControl::Iterations`]: the step
//! adapted to the corrector's iteration count, capped at `1 / points` of
//! arclength, folds labelled on the point after them) is kept for the
//! benchmark's before/after comparison.
//!
//! Restarts. A piece of the branch ends early when it turns back and
//! leaves the range at its start, diverges (its largest coefficient beyond
//! 1000 times the static equilibrium's: the periodic response has a pole,
//! e.g. at the edge of a parametric resonance of a linear mesh), stalls
//! (300 points without a new farthest Omega: a tangle of close folds), or
//! its corrector fails at the smallest step. While part of the range is
//! not covered, the continuation restarts: first from the other end in the
//! other direction, then inside the first gap (at its middle, upward, and
//! from there downward; if Newton finds no first point there, at a quarter
//! and three quarters). A restarted piece ends where the range is covered.
//! A gap whose start lies beyond the divergence bound is a pole; a gap in
//! which a restarted piece did not get across either (or three starts
//! failed) is a tangle. Both are left out and reported
//! ([`FrfContinuation::left_out`]), every restart too
//! ([`FrfContinuation::restarts`]), each with a plain note
//! ([`FrfContinuation::notes`]); every point carries its piece number, so
//! that a curve is broken between pieces. Never a silent gap.

pub mod assembly;
pub mod harmonic;
pub mod model;
pub mod stability;

use crate::error::{Result, SolverError};
use crate::steady::{Impact, Model};
use crate::sweep::Direction;
pub use assembly::{Assembly, Method};
pub use model::{HbmModel, Reduction};
use nalgebra::Complex;
use nalgebra::{DMatrix, DVector};
pub use stability::Floquet;
use stability::{eval_coef, floquet};
use std::f64::consts::PI;

/// A bifurcation detected between two branch points.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Bifurcation {
    /// The branch turns back in Omega (a jump in a sweep).
    Fold,
    /// A real multiplier crosses -1.
    PeriodDoubling,
    /// A complex pair crosses the unit circle.
    NeimarkSacker,
    /// A real multiplier crosses +1 without a turn (symmetry breaking or transcritical).
    BranchPoint,
}

impl Bifurcation {
    /// Name for output.
    pub fn name(self) -> &'static str {
        match self {
            Bifurcation::Fold => "fold",
            Bifurcation::PeriodDoubling => "period-doubling",
            Bifurcation::NeimarkSacker => "neimark-sacker",
            Bifurcation::BranchPoint => "branch-point",
        }
    }
}

/// Options of a frequency-response computation.
#[derive(Debug, Clone, PartialEq)]
pub struct FrfSpec {
    /// Start of the Omega range.
    pub omega_from: f64,
    /// End of the Omega range.
    pub omega_to: f64,
    /// Resolution: a step moves Omega by at most `range / points` (with
    /// [`StepControl::Iterations`], the largest arclength step is
    /// `1 / points` in the continuation's metric).
    pub points: u32,
    /// Continue upward from `omega_from` or downward from `omega_to`.
    pub direction: Direction,
    /// Number of harmonics H.
    pub harmonics: usize,
    /// AFT or the seed's describing function.
    pub method: Method,
    /// AFT grid size (default [`harmonic::Grid::default_size`]).
    pub grid: Option<usize>,
    /// Compute Floquet stability at every point.
    pub stability: bool,
    /// Use the cyclic-symmetry reduction when the planets allow it.
    pub symmetric: bool,
    /// How the continuation chooses its step.
    pub step_control: StepControl,
}

/// The continuation's step-length control.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum StepControl {
    /// From the curve's geometry (the predictor-corrector distance and the
    /// tangent's turn), folds located by regula falsi; the default.
    Geometry,
    /// From the corrector's iteration count with the arclength step capped
    /// at `1 / points`, folds labelled on the point after them: the control
    /// before issue 14, kept for the benchmark's before/after comparison.
    Iterations,
}

impl FrfSpec {
    /// Defaults: H = 5 with the exact method, stability on, symmetric
    /// reduction on, up.
    pub fn new(omega_from: f64, omega_to: f64, points: u32) -> Self {
        FrfSpec {
            omega_from,
            omega_to,
            points,
            direction: Direction::Up,
            harmonics: 5,
            method: Method::Exact,
            grid: None,
            stability: true,
            symmetric: true,
            step_control: StepControl::Geometry,
        }
    }

    /// Checks the options.
    pub fn validate(&self) -> Result<()> {
        let bad = |option: &str, value: String, allowed: &str| {
            SolverError::bad_option(option, value, allowed)
        };
        for (name, v) in [("omega-from", self.omega_from), ("omega-to", self.omega_to)] {
            if !(v.is_finite() && (0.01..=20.0).contains(&v)) {
                return bad(name, format!("{v}"), "0.01 ..= 20");
            }
        }
        if self.omega_to <= self.omega_from {
            return bad("omega-to", format!("{}", self.omega_to), "> omega-from");
        }
        if self.points < 2 || self.points > 100_000 {
            return bad("points", self.points.to_string(), "2 ..= 100000");
        }
        if self.harmonics == 0 || self.harmonics > 40 {
            return bad("harmonics", self.harmonics.to_string(), "1 ..= 40");
        }
        if self.method == Method::DescribingFunction && self.harmonics != 1 {
            return bad(
                "harmonics",
                self.harmonics.to_string(),
                "1 with the describing-function method",
            );
        }
        if let Some(n) = self.grid {
            if n <= 4 * self.harmonics || n > 1 << 16 {
                return bad("grid", n.to_string(), "4 H + 1 ..= 65536");
            }
        }
        Ok(())
    }
}

/// One mesh on a branch point, reconstructed from the harmonics.
#[derive(Debug, Clone, PartialEq)]
pub struct BranchMesh {
    /// Largest deflection delta (m).
    pub delta_max_m: f64,
    /// Smallest deflection delta (m).
    pub delta_min_m: f64,
    /// Half the peak-to-peak deflection (m).
    pub delta_amplitude_m: f64,
    /// Mean (index 0) and amplitude of harmonics 1..=H of delta (m).
    pub harmonics_m: Vec<f64>,
    /// Smallest relative displacement delta - e (m).
    pub rel_min_m: f64,
    /// Largest relative displacement delta - e (m).
    pub rel_max_m: f64,
    /// Contact regime of the reconstructed orbit.
    pub impact: Impact,
}

/// One point of a branch.
#[derive(Debug, Clone, PartialEq)]
pub struct BranchPoint {
    /// Dimensionless frequency.
    pub omega: f64,
    /// Every physical mesh, in the system's order.
    pub meshes: Vec<BranchMesh>,
    /// Stability (None if not computed or the eigenvalues failed).
    pub stable: Option<bool>,
    /// Floquet multipliers (empty if not computed).
    pub multipliers: Vec<Complex<f64>>,
    /// A bifurcation detected between the previous point and this one.
    pub bifurcation: Option<Bifurcation>,
    /// Newton iterations spent on this point.
    pub newton_iterations: usize,
    /// The solution's coefficients (scaled units; for continuation and checks).
    pub coefficients: Vec<f64>,
    /// The piece of the branch this point belongs to: 0, then one more at
    /// every automatic restart (a curve through the points is broken
    /// between pieces).
    pub piece: u32,
}

/// Why a piece of the branch ended.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum PieceEnd {
    /// It left the range through the far end.
    Reached,
    /// It turned back at a fold and left the range through the end it
    /// started from.
    TurnedBack,
    /// The response grew without bound: the periodic solution passes through
    /// infinity (a multiplier of the orbit's linearization at +1, such as the
    /// edge of a parametric resonance of the linear mesh).
    Diverged,
    /// It made no progress in Omega over many points (a tangle of close folds).
    Stalled,
    /// The corrector failed at the smallest step.
    Failed,
}

impl PieceEnd {
    /// Name for output.
    pub fn name(self) -> &'static str {
        match self {
            PieceEnd::Reached => "reached-end",
            PieceEnd::TurnedBack => "turned-back",
            PieceEnd::Diverged => "diverged",
            PieceEnd::Stalled => "stalled",
            PieceEnd::Failed => "corrector-failed",
        }
    }
}

/// An automatic restart of the continuation: where and why the previous
/// piece ended and where the next one started.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Restart {
    /// Index of the new piece (1, 2, ...).
    pub piece: u32,
    /// Why the previous piece ended.
    pub reason: PieceEnd,
    /// Omega where the previous piece ended.
    pub stopped_at: f64,
    /// Omega where the new piece started.
    pub start_omega: f64,
    /// Direction of the new piece.
    pub direction: Direction,
}

impl Restart {
    /// A plain sentence for the user.
    pub fn note(&self) -> String {
        let why = match self.reason {
            PieceEnd::Reached => "ended".to_string(),
            PieceEnd::TurnedBack => format!(
                "turned back at a fold and left the range at Omega {:.4}",
                self.stopped_at
            ),
            PieceEnd::Diverged => format!(
                "grew without bound near Omega {:.4} (the periodic response has a pole there)",
                self.stopped_at
            ),
            PieceEnd::Stalled => format!(
                "wound through many close folds near Omega {:.4} without progress",
                self.stopped_at
            ),
            PieceEnd::Failed => format!("could not be corrected at Omega {:.4}", self.stopped_at),
        };
        let dir = match self.direction {
            Direction::Up => "upward",
            Direction::Down => "downward",
        };
        format!(
            "The branch {why}; it was restarted at Omega {:.4}, {dir} (piece {} of the curve).",
            self.start_omega,
            self.piece + 1
        )
    }
}

/// Work counters of a continuation.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
pub struct FrfStats {
    /// Points on the branch.
    pub points: u64,
    /// Newton iterations.
    pub newton_iterations: u64,
    /// Rejected continuation steps.
    pub rejected_steps: u64,
    /// Residual and Jacobian evaluations.
    pub jacobians: u64,
}

/// A continuation in progress; [`FrfContinuation::advance`] computes a bounded
/// number of points per call.
#[derive(Debug, Clone)]
pub struct FrfContinuation {
    asm: Assembly,
    spec: FrfSpec,
    y: Vec<f64>,
    tangent: Vec<f64>,
    ds: f64,
    ds_max: f64,
    scale: f64,
    started: bool,
    finished: bool,
    prev_stable: Option<bool>,
    prev_multipliers: Vec<Complex<f64>>,
    since_fold: u32,
    max_points: u64,
    /// Work so far.
    pub stats: FrfStats,
    x0: Vec<f64>,
    transform: Option<DMatrix<f64>>,
    mesh_to_channel: Vec<usize>,
    /// A fine grid on which reconstructed orbits are sampled for their extremes.
    recon: harmonic::Grid,
    left_at_start: bool,
    /// Direction and start of the current piece.
    dir: Direction,
    start_omega: f64,
    /// Points computed but not yet returned.
    queue: Vec<BranchPoint>,
    /// A fold whose location failed: labelled on the next point.
    pending_fold: bool,
    /// The current piece's index.
    piece: u32,
    /// The Omega span `(lo, hi)` of every piece so far.
    spans: Vec<(f64, f64)>,
    /// Automatic restarts so far.
    restarts: Vec<Restart>,
    /// Whether a piece that ends early is followed by a restart.
    restarts_allowed: bool,
    /// Points of the current piece since it last advanced its frontier.
    since_progress: u64,
    /// The current piece's frontier: the farthest Omega in its direction.
    frontier: f64,
    /// An amplitude beyond which the piece has diverged.
    divergence: f64,
    /// Parts of the range that no piece covers, and why.
    left_out: Vec<LeftOut>,
    /// Omega of restarts whose first point Newton did not find.
    failed_starts: Vec<f64>,
    /// A failure to report once the points before it are returned.
    pending_error: Option<SolverError>,
}

/// A part of the Omega range left out of the branch, reported.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct LeftOut {
    /// Lower Omega.
    pub from: f64,
    /// Upper Omega.
    pub to: f64,
    /// Why.
    pub reason: LeftOutReason,
}

/// Why a part of the range has no branch points.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum LeftOutReason {
    /// The response grows without bound from both sides (a pole of the
    /// periodic solution), and a start inside is beyond the divergence bound.
    Unbounded,
    /// Pieces from both sides wound through many close folds there and a
    /// start inside did not get across either.
    Tangle,
}

impl LeftOut {
    /// A plain sentence for the user.
    pub fn note(&self) -> String {
        match self.reason {
            LeftOutReason::Unbounded => format!(
                "Between Omega {:.5} and {:.5} the periodic response is unbounded \
                 (it grows without bound from both sides): no point is drawn there.",
                self.from, self.to
            ),
            LeftOutReason::Tangle => format!(
                "Between Omega {:.5} and {:.5} the branch winds through many close folds \
                 (a strongly impacting response, which a few harmonics resolve poorly) and \
                 was not followed across: no point is drawn there; time integration shows \
                 the motion.",
                self.from, self.to
            ),
        }
    }

    /// Name of the reason for output.
    pub fn reason_name(&self) -> &'static str {
        match self.reason {
            LeftOutReason::Unbounded => "unbounded",
            LeftOutReason::Tangle => "tangle",
        }
    }
}

const NEWTON_MAX: usize = 12;
/// Nominal predictor-corrector distance in the arclength metric.
const D_NOM: f64 = 1e-3;
/// Nominal turn of the tangent per step (radians).
const ALPHA_NOM: f64 = 0.1;
/// Largest step in the arclength metric.
const DS_CAP: f64 = 0.25;
/// Regula falsi steps locating a fold, and their tolerance on Omega.
const FOLD_ITERATIONS: usize = 12;
const FOLD_TOL: f64 = 1e-10;
/// Points without progress in Omega after which a piece has stalled.
const STALL_WINDOW: u64 = 300;
/// Where in a gap (as a fraction of it) restarts try to start, in turn,
/// while Newton fails to find a first point.
const GAP_STARTS: [f64; 3] = [0.5, 0.25, 0.75];
/// Restarts of a branch that ends early.
const MAX_RESTARTS: usize = 6;
/// A piece has diverged when its largest coefficient exceeds this multiple
/// of the static equilibrium's (at least 1 um).
const DIVERGENCE_FACTOR: f64 = 1e3;
/// Where the fallback start begins its upward continuation.
const START_OMEGA: f64 = 0.05;
const NEWTON_TOL: f64 = 1e-9;
/// A residual this small (relative to the solution's scale) is converged
/// even if the kinked force makes the last step stall above `NEWTON_TOL`.
const RESIDUAL_FLOOR: f64 = 1e-7;
/// Below this relative Newton step the corrector keeps its factorization.
const CHORD_STEP: f64 = 1e-5;

impl FrfContinuation {
    /// Prepares the frequency response of a gear model.
    pub fn new(model: &Model, spec: FrfSpec) -> Result<Self> {
        spec.validate()?;
        let hbm = HbmModel::from_system(&model.system, spec.symmetric)?;
        // Start from the static equilibrium, projected on the HBM coordinates.
        let t = hbm.transform.clone().ok_or_else(|| SolverError::Singular {
            what: "harmonic-balance model without a coordinate map".into(),
        })?;
        let q = DVector::from_column_slice(&model.statics.q);
        let x_static = (t.transpose() * &model.system.mass * q) * 1e6;
        let mut x0 = vec![0.0; hbm.m * harmonic::n_coef(spec.harmonics)];
        x0[..hbm.m].copy_from_slice(x_static.as_slice());
        let mut mesh_to_channel = vec![0; model.system.meshes.len()];
        for (c, ch) in hbm.channels.iter().enumerate() {
            for &j in &ch.meshes {
                mesh_to_channel[j] = c;
            }
        }
        Self::with_model(hbm, spec, x0, Some(t), mesh_to_channel)
    }

    /// Prepares the frequency response of any harmonic-balance problem
    /// (test models), starting from zero.
    pub fn for_model(hbm: HbmModel, spec: FrfSpec) -> Result<Self> {
        spec.validate()?;
        let x0 = vec![0.0; hbm.m * harmonic::n_coef(spec.harmonics)];
        let map = (0..hbm.n_meshes).collect();
        Self::with_model(hbm, spec, x0, None, map)
    }

    fn with_model(
        hbm: HbmModel,
        spec: FrfSpec,
        x0: Vec<f64>,
        transform: Option<DMatrix<f64>>,
        mesh_to_channel: Vec<usize>,
    ) -> Result<Self> {
        let h = if spec.method == Method::DescribingFunction {
            1
        } else {
            spec.harmonics
        };
        let grid = spec.grid.unwrap_or_else(|| harmonic::Grid::default_size(h));
        let asm = Assembly::new(hbm, h, spec.method, grid);
        // Arclength is measured with Omega in units of the range.
        let ds_max = 1.0 / f64::from(spec.points);
        let divergence = DIVERGENCE_FACTOR * inf_norm(&x0).max(1.0);
        Ok(FrfContinuation {
            divergence,
            max_points: 20 * u64::from(spec.points) + 4000,
            asm,
            y: Vec::new(),
            tangent: Vec::new(),
            ds: ds_max,
            ds_max,
            scale: 1.0,
            started: false,
            finished: false,
            prev_stable: None,
            prev_multipliers: Vec::new(),
            since_fold: u32::MAX,
            stats: FrfStats::default(),
            x0,
            transform,
            mesh_to_channel,
            recon: harmonic::Grid::new(h, recon_samples(h)),
            left_at_start: false,
            dir: spec.direction,
            start_omega: match spec.direction {
                Direction::Up => spec.omega_from,
                Direction::Down => spec.omega_to,
            },
            queue: Vec::new(),
            pending_fold: false,
            piece: 0,
            spans: Vec::new(),
            restarts: Vec::new(),
            restarts_allowed: true,
            since_progress: 0,
            frontier: f64::NAN,
            left_out: Vec::new(),
            failed_starts: Vec::new(),
            pending_error: None,
            spec,
        })
    }

    /// The evaluator (model, grid, harmonics).
    pub fn assembly(&self) -> &Assembly {
        &self.asm
    }

    /// The specification.
    pub fn spec(&self) -> &FrfSpec {
        &self.spec
    }

    /// Whether the branch has left the Omega range (or failed).
    pub fn is_finished(&self) -> bool {
        self.finished && self.queue.is_empty() && self.pending_error.is_none()
    }

    /// Whether the finished branch turned back at a fold and left the range
    /// through the end it started from, and the rest of the range was not
    /// reached by a restart either (continue from the other end, in the
    /// other direction, to see it).
    pub fn left_at_start(&self) -> bool {
        self.left_at_start
    }

    /// The automatic restarts: where a piece of the branch ended early, why,
    /// and where the next one started.
    pub fn restarts(&self) -> &[Restart] {
        &self.restarts
    }

    /// Plain sentences saying what the continuation did beyond following
    /// one branch from end to end (empty when it did just that).
    pub fn notes(&self) -> Vec<String> {
        let mut notes: Vec<String> = self.restarts.iter().map(Restart::note).collect();
        notes.extend(self.left_out.iter().map(LeftOut::note));
        notes
    }

    /// The Omega intervals no piece covers, and why: a pole of the periodic
    /// response, or a tangle of folds that no piece got across.
    pub fn left_out(&self) -> &[LeftOut] {
        &self.left_out
    }

    /// Fraction of the Omega range covered so far, for progress bars.
    pub fn progress(&self) -> f64 {
        if self.finished {
            return 1.0;
        }
        let range = self.spec.omega_to - self.spec.omega_from;
        let covered: f64 = self.coverage_gaps().iter().map(|(a, b)| b - a).sum::<f64>();
        ((range - covered) / range).clamp(0.0, 1.0)
    }

    /// The parts of the Omega range that no piece has covered yet, except
    /// the poles (where pieces on both sides diverged).
    fn coverage_gaps(&self) -> Vec<(f64, f64)> {
        let mut spans = self.spans.clone();
        spans.extend(self.left_out.iter().map(|l| (l.from, l.to)));
        Self::gaps_of(&self.spec, spans)
    }

    /// The parts of the range that `spans` leave out.
    fn gaps_of(spec: &FrfSpec, mut spans: Vec<(f64, f64)>) -> Vec<(f64, f64)> {
        spans.sort_by(|a, b| a.0.total_cmp(&b.0));
        let tol = 1e-9 * (spec.omega_to - spec.omega_from);
        let mut gaps = Vec::new();
        let mut reached = spec.omega_from;
        for (lo, hi) in spans {
            if lo > reached + tol {
                gaps.push((reached, lo.min(spec.omega_to)));
            }
            reached = reached.max(hi);
        }
        if reached < spec.omega_to - tol {
            gaps.push((reached, spec.omega_to));
        }
        gaps
    }

    /// Physical generalized coordinates `q(theta)` are `transform x 1e-6`.
    pub fn transform(&self) -> Option<&DMatrix<f64>> {
        self.transform.as_ref()
    }

    /// Computes up to `k` further points. On a solver failure the branch ends
    /// and the error is returned, after any points computed before it (the
    /// points already returned stay valid).
    ///
    /// A piece of the branch that ends before the far end of the range
    /// (turned back, diverged, stalled in a tangle of folds, or a failed
    /// corrector) is followed by an automatic restart while part of the
    /// range is not covered: first from the other end in the other
    /// direction, then from the middle of the first gap, upward; see
    /// [`FrfContinuation::restarts`]. A restarted piece ends where the range
    /// is covered.
    pub fn advance(&mut self, k: usize) -> Result<Vec<BranchPoint>> {
        if self.queue.is_empty() {
            if let Some(e) = self.pending_error.take() {
                return Err(e);
            }
        }
        while self.queue.len() < k && !self.finished {
            let before = self.queue.len();
            let outcome = if !self.started {
                self.start()
            } else if self.stats.points >= self.max_points {
                let omega = self.y.last().copied().unwrap_or(f64::NAN);
                self.finished = true;
                Err(SolverError::ContinuationStalled {
                    omega,
                    points: self.stats.points,
                })
            } else {
                match self.step() {
                    // A corrector that fails at the smallest step ends the
                    // piece; a restart may cover the rest.
                    Err(e) if self.restarts_allowed && self.restarts.len() < MAX_RESTARTS => {
                        let omega = self.y[self.n_x()];
                        self.end_piece(PieceEnd::Failed, omega).map_err(|_| e)
                    }
                    other => other,
                }
            };
            self.stats.points += (self.queue.len() - before) as u64;
            if let Err(e) = outcome {
                self.finished = true;
                if self.queue.is_empty() {
                    return Err(e);
                }
                // The points before the failure stay valid: they are
                // returned first, the error by the call after them.
                self.pending_error = Some(e);
                break;
            }
        }
        // At most `k` now; a located fold and the point after it can come
        // in one step, and the second then waits for the next call.
        let n = self.queue.len().min(k);
        Ok(self.queue.drain(..n).collect())
    }

    fn n_x(&self) -> usize {
        self.asm.n_x()
    }

    /// Records a new point of the current piece in its span and frontier,
    /// queues it, and ends the piece when it has diverged, stalled or
    /// (for a restarted piece) covered the rest of the range.
    fn emit(&mut self, p: BranchPoint) -> Result<()> {
        let omega = p.omega;
        let piece = self.piece as usize;
        if self.spans.len() <= piece {
            self.spans.push((omega, omega));
        }
        let span = &mut self.spans[piece];
        span.0 = span.0.min(omega).max(self.spec.omega_from);
        span.1 = span.1.max(omega).min(self.spec.omega_to);
        let ahead = match self.dir {
            Direction::Up => omega > self.frontier,
            Direction::Down => omega < self.frontier,
        };
        if ahead || self.frontier.is_nan() {
            self.frontier = omega;
            self.since_progress = 0;
        } else {
            self.since_progress += 1;
        }
        let amplitude = inf_norm(&p.coefficients);
        self.queue.push(p);
        if self.finished || !self.started {
            return Ok(());
        }
        if amplitude > self.divergence {
            return self.end_piece(PieceEnd::Diverged, omega);
        }
        if self.since_progress > self.stall_window() {
            return self.end_piece(PieceEnd::Stalled, omega);
        }
        if self.piece > 0 && self.coverage_gaps().is_empty() {
            self.finished = true;
        }
        Ok(())
    }

    /// Points without progress in Omega after which a piece has stalled.
    fn stall_window(&self) -> u64 {
        STALL_WINDOW
    }

    /// The last point of a piece (reached an end of the range, or turned back).
    fn finish_piece(
        &mut self,
        iterations: usize,
        label: Option<Bifurcation>,
        how: PieceEnd,
    ) -> Result<()> {
        let p = self.point(iterations, label);
        let omega = p.omega;
        self.started = false;
        self.emit(p)?;
        self.end_piece(how, omega)
    }

    /// Ends the current piece; restarts while the range is not covered.
    fn end_piece(&mut self, how: PieceEnd, stopped_at: f64) -> Result<()> {
        self.started = false;
        let tol = 1e-9 * (self.spec.omega_to - self.spec.omega_from);
        // A gap in which (or at whose edge) a restart already began, and
        // that pieces from both sides could not cross: left out, reported.
        loop {
            let gaps = self.coverage_gaps();
            let tried = gaps.iter().copied().find(|g| {
                let down_pending = self.restarts.last().is_some_and(|r| {
                    r.piece >= 2
                        && r.direction == Direction::Up
                        && (g.1 - r.start_omega).abs() <= tol
                });
                let inside = |w: f64| g.0 - tol <= w && w <= g.1 + tol;
                let failed = self.failed_starts.iter().filter(|&&w| inside(w)).count();
                !down_pending
                    && (failed >= GAP_STARTS.len()
                        || self
                            .restarts
                            .iter()
                            .any(|r| r.piece >= 2 && inside(r.start_omega)))
            });
            match tried {
                Some(g) => self.left_out.push(LeftOut {
                    from: g.0,
                    to: g.1,
                    reason: LeftOutReason::Tangle,
                }),
                None => break,
            }
        }
        let gaps = self.coverage_gaps();
        if gaps.is_empty() {
            self.finished = true;
            return Ok(());
        }
        if !self.restarts_allowed || self.restarts.len() >= MAX_RESTARTS {
            self.finished = true;
            return match how {
                PieceEnd::TurnedBack | PieceEnd::Reached => {
                    self.left_at_start = how == PieceEnd::TurnedBack;
                    Ok(())
                }
                PieceEnd::Diverged | PieceEnd::Stalled | PieceEnd::Failed => {
                    Err(SolverError::ContinuationStalled {
                        omega: stopped_at,
                        points: self.stats.points + self.queue.len() as u64,
                    })
                }
            };
        }
        // First from the other end, backward; then from the middle of the
        // first gap, upward, and from the same start downward if the gap
        // below it remains.
        let down_again = self.restarts.last().and_then(|r| {
            let below = gaps.iter().any(|g| (g.1 - r.start_omega).abs() <= tol);
            (r.piece >= 2 && r.direction == Direction::Up && below).then_some(r.start_omega)
        });
        let (start_omega, dir) = if self.restarts.is_empty() {
            match self.spec.direction {
                Direction::Up => (self.spec.omega_to, Direction::Down),
                Direction::Down => (self.spec.omega_from, Direction::Up),
            }
        } else if let Some(omega) = down_again {
            (omega, Direction::Down)
        } else {
            let (a, b) = gaps[0];
            let failed = self
                .failed_starts
                .iter()
                .filter(|&&w| a - tol <= w && w <= b + tol)
                .count();
            let frac = GAP_STARTS[failed.min(GAP_STARTS.len() - 1)];
            (a + frac * (b - a), Direction::Up)
        };
        self.piece += 1;
        self.restarts.push(Restart {
            piece: self.piece,
            reason: how,
            stopped_at,
            start_omega,
            direction: dir,
        });
        self.dir = dir;
        self.start_omega = start_omega;
        self.prev_stable = None;
        self.prev_multipliers.clear();
        self.since_fold = u32::MAX;
        self.pending_fold = false;
        self.ds = self.ds_max;
        self.frontier = f64::NAN;
        self.since_progress = 0;
        Ok(())
    }

    /// The first point of a piece: Newton at fixed Omega, continued in the
    /// number of harmonics (1, 2, ..., H, each solution padded with zeros as
    /// the next guess) because a many-harmonic Newton from the static guess
    /// can wander into the dead zone and stall.
    fn start(&mut self) -> Result<()> {
        let omega = self.start_omega;
        let nx = self.n_x();
        let found = match self.start_in_h(omega) {
            Ok(found) => Ok(found),
            // The fallback (a continuation from below) only for the first
            // piece: a restart that cannot start directly tries the next.
            Err(direct) if self.piece == 0 => self.start_from_below(omega).map_err(|_| direct),
            Err(direct) => Err(direct),
        };
        let (x, iterations) = match found {
            Ok(found) => found,
            Err(e) if self.piece > 0 => {
                // No piece: the restart is withdrawn and the next one tried
                // (elsewhere in the same gap, or the next gap).
                self.failed_starts.push(omega);
                return match self.restarts.pop() {
                    Some(r) => {
                        self.piece -= 1;
                        self.end_piece(r.reason, r.stopped_at)
                    }
                    None => {
                        self.finished = true;
                        Err(e)
                    }
                };
            }
            Err(e) => {
                self.finished = true;
                return Err(e);
            }
        };
        let mut r = vec![0.0; nx];
        let mut jac = DMatrix::zeros(nx, nx + 1);
        if self.piece > 0 && inf_norm(&x) > self.divergence {
            // A start beyond the divergence bound lies in a gap where the
            // response is unbounded: a pole, which the pieces on both sides
            // approached. It is left out, and the next gap is tried.
            if let (Some(r), Some(&gap)) = (
                self.restarts.pop(),
                self.coverage_gaps()
                    .iter()
                    .find(|g| g.0 <= omega && omega <= g.1),
            ) {
                self.piece -= 1;
                self.left_out.push(LeftOut {
                    from: gap.0,
                    to: gap.1,
                    reason: LeftOutReason::Unbounded,
                });
                return self.end_piece(r.reason, r.stopped_at);
            }
        }
        self.scale = (3.0 * rms(&x[self.asm.model.m..])).max(1.0);
        self.y = x;
        self.y.push(omega);
        // First tangent: [R_X R_Omega] t = 0 with t_Omega = +-1.
        self.asm
            .evaluate(&self.y[..nx], omega, &mut r, Some(&mut jac));
        let lu = jac.columns(0, nx).into_owned().lu();
        let rhs = DVector::from_iterator(nx, (0..nx).map(|i| -jac[(i, nx)]));
        let tx = lu.solve(&rhs).ok_or_else(|| SolverError::Singular {
            what: format!("harmonic-balance Jacobian at Omega = {omega}"),
        })?;
        let sign = if self.dir == Direction::Up { 1.0 } else { -1.0 };
        self.tangent = tx.iter().map(|v| v * sign).collect();
        self.tangent.push(sign);
        self.normalize_tangent();
        self.started = true;
        let p = self.point(iterations, None);
        self.emit(p)
    }

    /// Newton at `omega` continued in the number of harmonics.
    fn start_in_h(&mut self, omega: f64) -> Result<(Vec<f64>, usize)> {
        let m = self.asm.model.m;
        let mut x: Vec<f64> = self.x0[..m].to_vec();
        let mut iterations = 0;
        for hh in 1..=self.asm.h {
            x.resize(m * harmonic::n_coef(hh), 0.0);
            if hh == self.asm.h {
                iterations += newton_fixed(&mut self.asm, &mut x, omega, &mut self.stats)?;
            } else {
                let grid = harmonic::Grid::default_size(hh).max(self.asm.grid.n.min(1 << 12));
                let mut coarse = Assembly::new(self.asm.model.clone(), hh, self.asm.method, grid);
                iterations += newton_fixed(&mut coarse, &mut x, omega, &mut self.stats)?;
            }
        }
        Ok((x, iterations))
    }

    /// Fallback start when Newton at `omega` fails from the static guess
    /// (resonance zones, contact loss): continue upward from `START_OMEGA`,
    /// where the response is quasi-static and Newton is reliable, to `omega`
    /// and polish there. The branch reached is the one an upward sweep
    /// follows. A one-time cost of up to one full continuation.
    fn start_from_below(&mut self, omega: f64) -> Result<(Vec<f64>, usize)> {
        if omega <= START_OMEGA * 1.5 {
            return Err(SolverError::NotConverged {
                omega,
                residual: f64::NAN,
                iterations: 0,
            });
        }
        let mut spec = self.spec.clone();
        spec.omega_from = START_OMEGA;
        spec.omega_to = omega;
        spec.direction = Direction::Up;
        spec.stability = false;
        spec.points = spec.points.max(200);
        let mut inner = FrfContinuation::with_model(
            self.asm.model.clone(),
            spec,
            self.x0.clone(),
            None,
            self.mesh_to_channel.clone(),
        )?;
        inner.restarts_allowed = false;
        let mut last = None;
        while !inner.is_finished() {
            if let Some(p) = inner.advance(64)?.pop() {
                last = Some(p);
            }
        }
        self.stats.newton_iterations += inner.stats.newton_iterations;
        self.stats.jacobians += inner.stats.jacobians;
        let mut x = last
            .filter(|p| (p.omega - omega).abs() < 0.05 * omega)
            .map(|p| p.coefficients)
            .ok_or(SolverError::NotConverged {
                omega,
                residual: f64::NAN,
                iterations: 0,
            })?;
        let iterations = newton_fixed(&mut self.asm, &mut x, omega, &mut self.stats)?;
        Ok((x, iterations))
    }

    /// Weights of the arclength metric: Omega in units of the range, the
    /// coefficients in units of `scale` (RMS over coefficients).
    fn metric(&self, i: usize) -> f64 {
        if i == self.n_x() {
            let range = self.spec.omega_to - self.spec.omega_from;
            1.0 / (range * range)
        } else {
            1.0 / (self.scale * self.scale * self.n_x() as f64)
        }
    }

    /// Grows the amplitude scale of the metric with the largest response seen
    /// (three times its RMS harmonic coefficient, at least 1 um), so that a
    /// resonance peak costs a bounded number of steps whatever its height.
    fn update_scale(&mut self) {
        let m = self.asm.model.m;
        let nx = self.n_x();
        let amp = 3.0 * rms(&self.y[m..nx]);
        if self.spec.step_control == StepControl::Geometry {
            self.scale = amp.max(1.0);
            self.normalize_tangent();
        } else if amp > self.scale {
            self.scale = amp;
            self.normalize_tangent();
        }
    }

    fn normalize_tangent(&mut self) {
        let norm: f64 = (0..self.tangent.len())
            .map(|i| self.metric(i) * self.tangent[i] * self.tangent[i])
            .sum::<f64>()
            .sqrt();
        for t in &mut self.tangent {
            *t /= norm;
        }
    }

    /// One predictor-corrector step; `None` when the branch has left the range.
    ///
    /// The step length follows the curve's geometry: after a converged
    /// corrector, the distance from the predictor to the solution (`d`, in
    /// the arclength metric) and the angle between the old and new tangents
    /// (`alpha`) give the factor `f = max(sqrt(d / D_NOM), alpha / ALPHA_NOM)`
    /// by which the step overshot its nominal size (the distance grows as the
    /// square of the step, the angle linearly). `f > 2` rejects the step
    /// and retries with `ds / f`; otherwise the next step is `ds / f`,
    /// growing by at most 2. The step is also capped so that Omega moves by
    /// at most `range / points`.
    fn step(&mut self) -> Result<()> {
        let nx = self.n_x();
        let n = nx + 1;
        let omega_now = self.y[nx];
        let ds_min = 1e-5 * self.ds_max;
        loop {
            let t_om = self.tangent[nx];
            let end = match self.dir {
                Direction::Up => self.spec.omega_to,
                Direction::Down => self.spec.omega_from,
            };
            // At most `range / points` in Omega per step.
            let range = self.spec.omega_to - self.spec.omega_from;
            let mut ds = match self.spec.step_control {
                StepControl::Geometry => {
                    let omega_cap = range / f64::from(self.spec.points) / t_om.abs().max(1e-300);
                    self.ds.min(omega_cap).min(DS_CAP).max(ds_min)
                }
                StepControl::Iterations => self.ds,
            };
            // Land on the end of the range instead of overshooting it.
            let mut landing = false;
            if t_om != 0.0 {
                let to_end = (end - omega_now) / t_om;
                if to_end > 0.0 && to_end <= ds {
                    ds = to_end;
                    landing = true;
                }
            }
            let pred: Vec<f64> = (0..n).map(|i| self.y[i] + ds * self.tangent[i]).collect();
            if landing {
                // The last point sits exactly on the end of the range: a
                // natural-parameter Newton at Omega = end from the predictor.
                let mut x = pred[..nx].to_vec();
                let mut stats = self.stats;
                if let Ok(iterations) = newton_fixed(&mut self.asm, &mut x, end, &mut stats) {
                    self.stats = stats;
                    self.y[..nx].copy_from_slice(&x);
                    self.y[nx] = end;
                    return self.finish_piece(iterations, None, PieceEnd::Reached);
                }
            }
            match self.correct(&pred) {
                Ok((y_new, t_new, iterations)) => {
                    let cos: f64 = (0..n)
                        .map(|i| self.metric(i) * t_new[i] * self.tangent[i])
                        .sum();
                    let alpha = cos.clamp(-1.0, 1.0).acos();
                    let dist = (0..n)
                        .map(|i| self.metric(i) * (y_new[i] - pred[i]).powi(2))
                        .sum::<f64>()
                        .sqrt();
                    let geometry = self.spec.step_control == StepControl::Geometry;
                    if geometry {
                        let f = (dist / D_NOM).sqrt().max(alpha / ALPHA_NOM).max(0.5);
                        if f > 2.0 && ds > ds_min {
                            self.stats.rejected_steps += 1;
                            self.ds = (ds / f.min(4.0)).max(ds_min);
                            continue;
                        }
                        self.ds = (ds / f).clamp(ds_min, DS_CAP);
                    } else {
                        // Before issue 14: the turn limits the step, the
                        // corrector's iterations adapt it.
                        if cos < 0.9 && ds > ds_min {
                            self.stats.rejected_steps += 1;
                            self.ds = ds * 0.5;
                            continue;
                        }
                        self.ds = if iterations <= 2 {
                            (ds * 1.4).min(self.ds_max)
                        } else if iterations >= 5 {
                            ds * 0.6
                        } else {
                            ds
                        }
                        .max(ds_min);
                    }
                    if t_new[nx].signum() != self.tangent[nx].signum() && !geometry {
                        self.pending_fold = true;
                    } else if t_new[nx].signum() != self.tangent[nx].signum() {
                        // A fold between the two points: locate it, and
                        // put it on the branch before the new point.
                        if let Some((y_fold, t_fold, it)) = self.locate_fold(ds, t_new[nx]) {
                            let (y_keep, t_keep) = (
                                std::mem::replace(&mut self.y, y_fold),
                                std::mem::replace(&mut self.tangent, t_fold),
                            );
                            let fold_point = self.point(it, Some(Bifurcation::Fold));
                            self.y = y_keep;
                            self.tangent = t_keep;
                            self.emit(fold_point)?;
                            if !self.started || self.finished {
                                return Ok(());
                            }
                        } else {
                            self.pending_fold = true;
                        }
                    }
                    self.y = y_new;
                    self.tangent = t_new;
                    self.update_scale();
                    let omega = self.y[nx];
                    let label = std::mem::take(&mut self.pending_fold).then_some(Bifurcation::Fold);
                    if omega > self.spec.omega_to + 1e-12 || omega < self.spec.omega_from - 1e-12 {
                        // Left through the end it started from: the branch
                        // turned back at a fold and the rest of the range
                        // was not reached.
                        let at_start = match self.dir {
                            Direction::Up => omega < self.spec.omega_from + 1e-9,
                            Direction::Down => omega > self.spec.omega_to - 1e-9,
                        };
                        let how = if at_start {
                            PieceEnd::TurnedBack
                        } else {
                            PieceEnd::Reached
                        };
                        return self.finish_piece(iterations, label, how);
                    }
                    let p = self.point(iterations, label);
                    return self.emit(p);
                }
                Err(e) => {
                    self.stats.rejected_steps += 1;
                    if ds <= ds_min {
                        return Err(e);
                    }
                    self.ds = (ds * 0.5).max(ds_min);
                }
            }
        }
    }

    /// Locates a fold between the current point (`self.y`, tangent
    /// `self.tangent`) and the solution a step `ds` further: the zero of the
    /// tangent's Omega component along the branch, by the Illinois variant
    /// of regula falsi on the step length, each trial a corrector on the
    /// hyperplane normal to the current tangent. Returns the fold's solution,
    /// tangent and the corrector's iterations; `None` if a corrector failed
    /// (the fold is then labelled on the point after it).
    fn locate_fold(&mut self, ds: f64, f_end: f64) -> Option<(Vec<f64>, Vec<f64>, usize)> {
        let nx = self.n_x();
        let n = nx + 1;
        let (mut a, mut fa) = (0.0, self.tangent[nx]);
        let (mut b, mut fb) = (ds, f_end);
        if fa.signum() == fb.signum() {
            return None;
        }
        let mut best = None;
        let mut omega_prev = f64::NAN;
        for _ in 0..FOLD_ITERATIONS {
            let s = (a * fb - b * fa) / (fb - fa);
            let pred: Vec<f64> = (0..n).map(|i| self.y[i] + s * self.tangent[i]).collect();
            let (y, t, it) = self.correct(&pred).ok()?;
            let fs = t[nx];
            let omega = y[nx];
            let converged = (omega - omega_prev).abs() <= FOLD_TOL * (1.0 + omega.abs());
            omega_prev = omega;
            best = Some((y, t, it));
            if converged || fs == 0.0 {
                break;
            }
            if fs.signum() != fb.signum() {
                (a, fa) = (b, fb);
            } else {
                fa *= 0.5;
            }
            (b, fb) = (s, fs);
        }
        best
    }

    /// Newton on the bordered system from the predictor `pred`; returns the
    /// solution, its tangent and the iterations.
    fn correct(&mut self, pred: &[f64]) -> Result<(Vec<f64>, Vec<f64>, usize)> {
        let nx = self.n_x();
        let n = nx + 1;
        let mut y = pred.to_vec();
        let mut r = vec![0.0; nx];
        let mut jac = DMatrix::zeros(n, n);
        let mut jx = DMatrix::zeros(nx, n);
        let weighted_t: Vec<f64> = (0..n).map(|i| self.metric(i) * self.tangent[i]).collect();
        let mut res_prev = f64::INFINITY;
        // The last factorization and the size of the step it produced: once
        // a step is below `CHORD_STEP`, the Jacobian moves by less than that
        // and the factorization is kept (a chord step, whose error is the
        // product of the two small steps), and it also gives the tangent.
        let mut lu: Option<nalgebra::LU<f64, nalgebra::Dyn, nalgebra::Dyn>> = None;
        let mut step_prev = f64::INFINITY;
        for iteration in 1..=NEWTON_MAX {
            // AFT's residual has small kinks where a contact switch crosses
            // a grid point, on which chord steps can stall: it keeps Newton.
            let chord = lu.is_some() && step_prev <= CHORD_STEP && self.asm.method != Method::Aft;
            if chord {
                self.asm.evaluate(&y[..nx], y[nx], &mut r, None);
            } else {
                self.asm.evaluate(&y[..nx], y[nx], &mut r, Some(&mut jx));
            }
            self.stats.jacobians += 1;
            self.stats.newton_iterations += 1;
            let mut g = DVector::zeros(n);
            for i in 0..nx {
                g[i] = r[i];
            }
            g[nx] = (0..n).map(|i| weighted_t[i] * (y[i] - pred[i])).sum();
            let res = inf_norm(&r);
            if !res.is_finite() {
                break;
            }
            // On a kinked residual Newton can stall, bouncing between two
            // linearizations: a residual at round-off level that no longer
            // falls (where smooth Newton would square it) is a solution as
            // it stands.
            let scale_now = 1.0 + inf_norm(&y[..nx]);
            let at_floor =
                iteration > 2 && res <= RESIDUAL_FLOOR * scale_now && res > 0.1 * res_prev;
            res_prev = res;
            if !chord {
                jac.rows_mut(0, nx).copy_from(&jx);
                for i in 0..n {
                    jac[(nx, i)] = weighted_t[i];
                }
                lu = Some(jac.clone().lu());
            }
            let Some(factors) = lu.as_ref() else { break };
            let mut step = 0.0;
            if !at_floor {
                let Some(dy) = factors.solve(&g) else { break };
                for i in 0..n {
                    y[i] -= dy[i];
                }
                let scale = 1.0 + inf_norm(&y[..nx]);
                step = inf_norm(&dy.as_slice()[..nx]).max(dy[nx].abs() * scale) / scale;
            }
            step_prev = step;
            if at_floor || step <= NEWTON_TOL {
                let scale = 1.0 + inf_norm(&y[..nx]);
                // The residual before this last (tiny) step is already
                // within the bound: the step only reduces it, and a second
                // evaluation is saved. Otherwise check at the result.
                if !at_floor && res > 1e-6 * scale {
                    self.asm.evaluate(&y[..nx], y[nx], &mut r, None);
                    self.stats.jacobians += 1;
                    if inf_norm(&r) > 1e-6 * scale {
                        break;
                    }
                }
                // Converged: the tangent solves [R_X R_Omega; t^T] t_new = [0; 1],
                // with the last factorization (a Jacobian within a chord
                // step of the solution).
                let mut e = DVector::zeros(n);
                e[nx] = 1.0;
                let t = factors.solve(&e).ok_or_else(|| SolverError::Singular {
                    what: format!("bordered Jacobian at Omega = {}", y[nx]),
                })?;
                let mut t: Vec<f64> = t.iter().copied().collect();
                let norm: f64 = (0..n)
                    .map(|i| self.metric(i) * t[i] * t[i])
                    .sum::<f64>()
                    .sqrt();
                let dot: f64 = (0..n)
                    .map(|i| self.metric(i) * t[i] * self.tangent[i])
                    .sum();
                let sign = if dot < 0.0 { -1.0 } else { 1.0 };
                for v in &mut t {
                    *v *= sign / norm;
                }
                // A step accepted at the residual floor was as easy as a
                // two-iteration one: let the step size grow.
                let effort = if at_floor {
                    iteration.min(2)
                } else {
                    iteration
                };
                return Ok((y, t, effort));
            }
        }
        self.asm.evaluate(&y[..nx], y[nx], &mut r, None);
        Err(SolverError::NotConverged {
            omega: y[nx],
            residual: inf_norm(&r),
            iterations: NEWTON_MAX,
        })
    }

    /// Builds the output for the current solution.
    fn point(&mut self, newton_iterations: usize, fold: Option<Bifurcation>) -> BranchPoint {
        let nx = self.n_x();
        let omega = self.y[nx];
        let x = self.y[..nx].to_vec();
        let meshes = self.meshes_of(&x);
        let (stable, multipliers) = if self.spec.stability {
            match floquet(&self.asm, &x, omega) {
                Some(f) => {
                    let n_planet = f.planet_multipliers.len();
                    let mut all: Vec<Complex<f64>> = f.multipliers.clone();
                    all.extend(f.planet_multipliers.iter().copied());
                    let _ = n_planet;
                    (Some(f.spectral_radius() <= 1.0 + 1e-6), all)
                }
                None => (None, Vec::new()),
            }
        } else {
            (None, Vec::new())
        };
        let mut bifurcation = fold;
        if fold.is_some() {
            self.since_fold = 0;
        } else {
            self.since_fold = self.since_fold.saturating_add(1);
        }
        if bifurcation.is_none() {
            if let (Some(a), Some(b)) = (self.prev_stable, stable) {
                if a != b {
                    let kind = classify_crossing(&self.prev_multipliers, &multipliers);
                    // A real multiplier through +1 next to a turn is the fold
                    // itself (the monodromy of the truncated orbit and the
                    // truncated balance place it a point apart).
                    if !(kind == Bifurcation::BranchPoint && self.since_fold <= 5) {
                        bifurcation = Some(kind);
                    }
                }
            }
        }
        self.prev_stable = stable;
        self.prev_multipliers = multipliers.clone();
        BranchPoint {
            omega,
            meshes,
            stable,
            multipliers,
            bifurcation,
            newton_iterations,
            coefficients: x,
            piece: self.piece,
        }
    }

    /// Reconstructs every physical mesh's orbit from the coefficients.
    pub fn meshes_of(&self, x: &[f64]) -> Vec<BranchMesh> {
        let h = self.asm.h;
        let nc = harmonic::n_coef(h);
        let m = self.asm.model.m;
        let per_channel: Vec<BranchMesh> = self
            .asm
            .model
            .channels
            .iter()
            .map(|ch| {
                let coef: Vec<f64> = (0..nc)
                    .map(|c| (0..m).map(|i| ch.d[i] * x[c * m + i]).sum())
                    .collect();
                // delta - e has the same series with the TE's mean and first
                // harmonic subtracted.
                let mut rel_coef = coef.clone();
                let te = harmonic::te_real_coefficients(&ch.law);
                for (r, t) in rel_coef.iter_mut().zip(te) {
                    *r -= t;
                }
                let (dmin, dmax) = extremes(&self.recon, &coef, h);
                let (xmin, xmax) = extremes(&self.recon, &rel_coef, h);
                let mut harmonics_m = vec![coef[0] * 1e-6];
                for k in 1..=h {
                    harmonics_m.push(coef[2 * k - 1].hypot(coef[2 * k]) * 1e-6);
                }
                let b = ch.law.backlash_um();
                BranchMesh {
                    delta_max_m: dmax * 1e-6,
                    delta_min_m: dmin * 1e-6,
                    delta_amplitude_m: 0.5 * (dmax - dmin) * 1e-6,
                    harmonics_m,
                    rel_min_m: xmin * 1e-6,
                    rel_max_m: xmax * 1e-6,
                    impact: Impact::classify(xmin, xmax, b),
                }
            })
            .collect();
        self.mesh_to_channel
            .iter()
            .map(|&c| per_channel[c].clone())
            .collect()
    }
}

/// Samples per period used to find the extremes of a reconstructed orbit.
fn recon_samples(h: usize) -> usize {
    256.max(16 * harmonic::n_coef(h))
}

/// Damped Newton at fixed Omega: the step is halved (down to 1/128) while
/// it does not reduce the residual. Converged when the step is below
/// `NEWTON_TOL` of the solution's scale and the residual below `1e-6` of it.
fn newton_fixed(
    asm: &mut Assembly,
    x: &mut [f64],
    omega: f64,
    stats: &mut FrfStats,
) -> Result<usize> {
    let nx = asm.n_x();
    let mut r = vec![0.0; nx];
    let mut jac = DMatrix::zeros(nx, nx + 1);
    let mut trial = x.to_vec();
    let mut r_trial = vec![0.0; nx];
    let mut iterations = 0;
    loop {
        asm.evaluate(x, omega, &mut r, Some(&mut jac));
        stats.jacobians += 1;
        let res = inf_norm(&r);
        let not_converged = |residual: f64, iterations: usize| SolverError::NotConverged {
            omega,
            residual,
            iterations,
        };
        if !res.is_finite() {
            return Err(not_converged(res, iterations));
        }
        let lu = jac.columns(0, nx).into_owned().lu();
        let dx = lu
            .solve(&DVector::from_column_slice(&r))
            .ok_or_else(|| not_converged(res, iterations))?;
        let mut lambda = 1.0;
        for _ in 0..8 {
            for i in 0..nx {
                trial[i] = x[i] - lambda * dx[i];
            }
            asm.evaluate(&trial, omega, &mut r_trial, None);
            if inf_norm(&r_trial) <= res || lambda < 1e-2 {
                break;
            }
            lambda *= 0.5;
        }
        x.copy_from_slice(&trial);
        iterations += 1;
        stats.newton_iterations += 1;
        let scale = 1.0 + inf_norm(x);
        let step = inf_norm(dx.as_slice()) * lambda;
        let res_new = inf_norm(&r_trial);
        if (step <= NEWTON_TOL * scale && res_new <= 1e-6 * scale)
            || (res_new <= RESIDUAL_FLOOR * scale && step <= 1e-6 * scale)
        {
            return Ok(iterations);
        }
        if iterations >= 4 * NEWTON_MAX {
            return Err(not_converged(inf_norm(&r_trial), iterations));
        }
    }
}

/// Labels a stability change from the multipliers on either side.
fn classify_crossing(before: &[Complex<f64>], after: &[Complex<f64>]) -> Bifurcation {
    // The multiplier outside the unit circle on the unstable side.
    let outside = |set: &[Complex<f64>]| -> Option<Complex<f64>> {
        set.iter()
            .copied()
            .filter(|z| z.norm() > 1.0)
            .max_by(|a, b| a.norm().total_cmp(&b.norm()))
    };
    let z = outside(after).or_else(|| outside(before));
    match z {
        Some(z) if z.im.abs() > 1e-6 * z.norm() => Bifurcation::NeimarkSacker,
        Some(z) if z.re < 0.0 => Bifurcation::PeriodDoubling,
        _ => Bifurcation::BranchPoint,
    }
}

/// Min and max of a Fourier series: samples on `grid`, then a parabola
/// through the best sample and its neighbours.
fn extremes(grid: &harmonic::Grid, coef: &[f64], h: usize) -> (f64, f64) {
    let n = grid.n;
    let dt = 2.0 * PI / n as f64;
    let mut vals = vec![0.0; n];
    grid.synthesize(coef, &mut vals);
    let refine = |i: usize| -> f64 {
        let (a, b, c) = (vals[(i + n - 1) % n], vals[i], vals[(i + 1) % n]);
        let den = a - 2.0 * b + c;
        if den == 0.0 {
            return b;
        }
        let off = (0.5 * (a - c) / den).clamp(-1.0, 1.0);
        eval_coef(coef, h, (i as f64 + off) * dt)
    };
    let imax = (0..n)
        .max_by(|&a, &b| vals[a].total_cmp(&vals[b]))
        .unwrap_or(0);
    let imin = (0..n)
        .min_by(|&a, &b| vals[a].total_cmp(&vals[b]))
        .unwrap_or(0);
    (refine(imin).min(vals[imin]), refine(imax).max(vals[imax]))
}

fn inf_norm(v: &[f64]) -> f64 {
    v.iter().fold(0.0, |m, x| m.max(x.abs()))
}

fn rms(v: &[f64]) -> f64 {
    if v.is_empty() {
        return 0.0;
    }
    (v.iter().map(|x| x * x).sum::<f64>() / v.len() as f64).sqrt()
}
