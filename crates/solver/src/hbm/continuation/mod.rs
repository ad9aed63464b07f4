//! Pseudo-arclength continuation of harmonic-balance solutions in Omega:
//! the frequency response as a branch of points, with folds, stability
//! changes, restarts and the parts of the range left out.
//!
//! - [`branch`]: what a continuation is asked for and what it returns.
//! - [`start`]: the first point of a piece (Newton at fixed Omega).
//! - [`step`]: predictor, corrector, step control and fold location.
//! - [`point`]: a solution turned into a branch point (extremes, stability).
//!
//! Newton. The corrector solves the bordered system `[R_X R_Omega; t^T]` by
//! LU; the last factorization also gives the new tangent, and on a smooth
//! residual (not AFT's) once a step is below `1e-5` of the solution's scale
//! it is kept for the next (chord) step, which then costs a residual and a
//! solve instead of a Jacobian and an LU. It starts on the parabola through
//! the last two points (tangent at the last), about ten times closer to the
//! branch than the tangent's predictor where the branch bends smoothly, so
//! that most points need one factorization; the hyperplane it solves on and
//! the step control's distance stay the tangent predictor's. The fixed-
//! Omega Newton of the first and last points halves a step that does not
//! reduce the residual (down to 1/128). The corrector has converged when
//! the error left after the last step is below `1e-9` of the solution's
//! scale (micrometres): the step itself is, or the contraction `theta` of
//! the last two steps bounds what is left by `theta / (1 - theta)` times
//! the step (Deuflhard's estimate); and the residual is below `1e-6` of it
//! (at the iterate before that last step, which only reduces it, or else
//! at the result). It fails with [`SolverError::NotConverged`] carrying
//! Omega and the residual otherwise — never a silent last iterate.
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
//! The simpler control ([`StepControl::Iterations`]: the step adapted to
//! the corrector's iteration count, capped at `1 / points` of arclength,
//! folds labelled on the point after them) needs about three times the
//! points for the same folds; `gearshock bench` compares the two.
//!
//! Restarts. A piece of the branch ends early when it turns back and
//! leaves the range at its start, diverges (its largest coefficient beyond
//! 1000 times the static equilibrium's: the periodic response has a pole,
//! e.g. at the edge of a parametric resonance of a linear mesh), stalls
//! (300 points without a new farthest Omega: a tangle of close folds), or
//! its corrector fails at the smallest step. While part of the range is
//! not covered, the continuation restarts: first from the other end in the
//! other direction, then inside the first gap (at its middle, upward, and
//! from there downward; if Newton finds no first point there, at a quarter,
//! three quarters, an eighth and three eighths of it). A restarted piece
//! ends where the range is covered. A gap whose start lies beyond the
//! divergence bound is a pole; a gap in which a restarted piece did not get
//! across either (or five starts failed) is a tangle. Both are left out and reported
//! ([`FrfContinuation::left_out`]), every restart too
//! ([`FrfContinuation::restarts`]), each with a plain note
//! ([`FrfContinuation::notes`]); every point carries its piece number, so
//! that a curve is broken between pieces. Never a silent gap.

use super::assembly::{Assembly, Method};
use super::harmonic;
use super::model::HbmModel;
use super::stability::{eval_coef, floquet};
use crate::error::{Result, SolverError};
use crate::model::Model;
use crate::steady::Impact;
use crate::sweep::Direction;
use nalgebra::{Complex, DMatrix, DVector};
use std::f64::consts::PI;

pub mod branch;
mod point;
mod sampled;
mod start;
use start::newton_fixed;
mod step;

pub use branch::{
    Bifurcation, BranchMesh, BranchPoint, FrfSpec, FrfStats, LeftOut, LeftOutReason, PieceEnd,
    Restart, StepControl, SAMPLED_STABILITY_STRIDE,
};

/// A continuation in progress; [`FrfContinuation::advance`] computes a bounded
/// number of points per call.
#[derive(Debug, Clone)]
pub struct FrfContinuation {
    asm: Assembly,
    spec: FrfSpec,
    cursor: Cursor,
    stability: StabilityTrack,
    piece: Piece,
    coverage: Coverage,
    recon: Reconstruction,
    started: bool,
    finished: bool,
    max_points: u64,
    /// Work so far.
    pub stats: FrfStats,
    /// Points computed but not yet returned.
    queue: Vec<BranchPoint>,
    /// A failure to report once the points before it are returned.
    pending_error: Option<SolverError>,
    /// The corrector's spent Jacobians and factors, their storage reused
    /// by the next correction (two `n x n` matrices a point).
    matrix_pool: Vec<DMatrix<f64>>,
}

/// Where the continuation stands: the last point `y` (harmonic
/// coefficients and Omega), its unit tangent and the step sizes.
#[derive(Debug, Clone)]
struct Cursor {
    y: Vec<f64>,
    tangent: Vec<f64>,
    /// The point before `y` on the same piece (none at a piece's start):
    /// with `y` and its tangent it gives the corrector's starting guess.
    prev_y: Option<Vec<f64>>,
    ds: f64,
    ds_max: f64,
    scale: f64,
}

/// The stability of the points behind the cursor, for locating changes.
#[derive(Debug, Clone)]
struct StabilityTrack {
    prev_stable: Option<bool>,
    prev_multipliers: Vec<Complex<f64>>,
    since_fold: u32,
    /// The points at the queue's end whose stability is not decided yet:
    /// their distance (in points) from the last fold.
    unresolved: Vec<u32>,
    /// A fold whose location failed: labelled on the next point.
    pending_fold: bool,
}

/// The current piece of the curve (a restart begins a new one).
#[derive(Debug, Clone)]
struct Piece {
    /// The piece's index.
    index: u32,
    /// Its direction and start.
    dir: Direction,
    start_omega: f64,
    /// Points since it last advanced its frontier.
    since_progress: u64,
    /// The farthest Omega in its direction.
    frontier: f64,
    /// An amplitude beyond which the piece has diverged.
    divergence: f64,
}

/// What the pieces cover of the Omega range, and what they leave out.
#[derive(Debug, Clone)]
struct Coverage {
    /// The Omega span `(lo, hi)` of every piece so far.
    spans: Vec<(f64, f64)>,
    /// Automatic restarts so far.
    restarts: Vec<Restart>,
    /// Whether a piece that ends early is followed by a restart.
    restarts_allowed: bool,
    /// Parts of the range that no piece covers, and why.
    left_out: Vec<LeftOut>,
    /// Omega of restarts whose first point Newton did not find.
    failed_starts: Vec<f64>,
    left_at_start: bool,
}

/// How the harmonic coefficients map back to the gear set's meshes.
#[derive(Debug, Clone)]
struct Reconstruction {
    /// The start (the static equilibrium in the HBM coordinates).
    x0: Vec<f64>,
    transform: Option<DMatrix<f64>>,
    mesh_to_channel: Vec<usize>,
    /// A fine grid on which reconstructed orbits are sampled for their extremes.
    grid: harmonic::Grid,
}

const NEWTON_MAX: usize = 12;
/// Nominal predictor-corrector distance in the arclength metric.
const D_NOM: f64 = 1e-3;
/// Nominal turn of the tangent per step (radians).
const ALPHA_NOM: f64 = 0.1;

/// The factor by which a continuation step overshot its nominal size,
/// from the distance `dist` between the predictor and the corrected point
/// (in the arclength metric) and the tangent's turn `alpha` (radians):
/// `max(sqrt(dist / D_NOM), alpha / ALPHA_NOM)`, at least 0.5 (the
/// distance grows as the square of the step, the turn linearly). Above 2
/// the step is retried at `ds / f`; otherwise the next is `ds / f`. The
/// harmonic balance's branch and the boundary trace step by it alike.
pub(crate) fn overshoot(dist: f64, alpha: f64) -> f64 {
    (dist / D_NOM).sqrt().max(alpha / ALPHA_NOM).max(0.5)
}
/// Largest step in the arclength metric.
const DS_CAP: f64 = 0.25;
/// Regula falsi steps locating a fold, and their tolerance on Omega.
const FOLD_ITERATIONS: usize = 12;
const FOLD_TOL: f64 = 1e-10;
/// Points without progress in Omega after which a piece has stalled.
const STALL_WINDOW: u64 = 300;
/// Where in a gap (as a fraction of it) restarts try to start, in turn,
/// while Newton fails to find a first point.
const GAP_STARTS: [f64; 5] = [0.5, 0.25, 0.75, 0.125, 0.375];
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
        Assembly::check_harmonics(&hbm, spec.harmonics, spec.method)?;
        let grid = spec.grid.unwrap_or_else(|| harmonic::Grid::default_size(h));
        let asm = Assembly::new(hbm, h, spec.method, grid);
        // Arclength is measured with Omega in units of the range.
        let ds_max = 1.0 / f64::from(spec.points);
        let divergence = DIVERGENCE_FACTOR * inf_norm(&x0).max(1.0);
        Ok(FrfContinuation {
            max_points: 20 * u64::from(spec.points) + 4000,
            asm,
            cursor: Cursor {
                y: Vec::new(),
                tangent: Vec::new(),
                prev_y: None,
                ds: ds_max,
                ds_max,
                scale: 1.0,
            },
            stability: StabilityTrack {
                prev_stable: None,
                prev_multipliers: Vec::new(),
                since_fold: u32::MAX,
                unresolved: Vec::new(),
                pending_fold: false,
            },
            piece: Piece {
                index: 0,
                dir: spec.direction,
                start_omega: match spec.direction {
                    Direction::Up => spec.omega_from,
                    Direction::Down => spec.omega_to,
                },
                since_progress: 0,
                frontier: f64::NAN,
                divergence,
            },
            coverage: Coverage {
                spans: Vec::new(),
                restarts: Vec::new(),
                restarts_allowed: true,
                left_out: Vec::new(),
                failed_starts: Vec::new(),
                left_at_start: false,
            },
            recon: Reconstruction {
                x0,
                transform,
                mesh_to_channel,
                grid: harmonic::Grid::new(h, recon_samples(h)),
            },
            started: false,
            finished: false,
            stats: FrfStats::default(),
            queue: Vec::new(),
            pending_error: None,
            matrix_pool: Vec::new(),
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
        self.coverage.left_at_start
    }

    /// The automatic restarts: where a piece of the branch ended early, why,
    /// and where the next one started.
    pub fn restarts(&self) -> &[Restart] {
        &self.coverage.restarts
    }

    /// Plain sentences saying what the continuation did beyond following
    /// one branch from end to end (empty when it did just that).
    pub fn notes(&self) -> Vec<String> {
        let mut notes: Vec<String> = self.coverage.restarts.iter().map(Restart::note).collect();
        notes.extend(self.coverage.left_out.iter().map(LeftOut::note));
        notes
    }

    /// The Omega intervals no piece covers, and why: a pole of the periodic
    /// response, or a tangle of folds that no piece got across.
    pub fn left_out(&self) -> &[LeftOut] {
        &self.coverage.left_out
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
        let mut spans = self.coverage.spans.clone();
        spans.extend(self.coverage.left_out.iter().map(|l| (l.from, l.to)));
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
        self.recon.transform.as_ref()
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
        while self.queue.len() - self.stability.unresolved.len() < k && !self.finished {
            let before = self.queue.len();
            let outcome = if !self.started {
                self.start()
            } else if self.stats.points >= self.max_points {
                let omega = self.cursor.y.last().copied().unwrap_or(f64::NAN);
                self.finished = true;
                Err(SolverError::ContinuationStalled {
                    omega,
                    points: self.stats.points,
                })
            } else {
                match self.step() {
                    // A corrector that fails at the smallest step ends the
                    // piece; a restart may cover the rest.
                    Err(e)
                        if self.coverage.restarts_allowed
                            && self.coverage.restarts.len() < MAX_RESTARTS =>
                    {
                        let omega = self.cursor.y[self.n_x()];
                        self.end_piece(PieceEnd::Failed, omega).map_err(|_| e)
                    }
                    other => other,
                }
            };
            self.stats.points += (self.queue.len() - before) as u64;
            if self.stability_due() {
                self.resolve_stability();
            }
            if let Err(e) = outcome {
                self.finished = true;
                self.resolve_stability();
                if self.queue.is_empty() {
                    return Err(e);
                }
                // The points before the failure stay valid: they are
                // returned first, the error by the call after them.
                self.pending_error = Some(e);
                break;
            }
        }
        if self.finished {
            self.resolve_stability();
        }
        // At most `k` now; a located fold and the point after it can come
        // in one step, and the second then waits for the next call.
        let n = (self.queue.len() - self.stability.unresolved.len()).min(k);
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
        let piece = self.piece.index as usize;
        if self.coverage.spans.len() <= piece {
            self.coverage.spans.push((omega, omega));
        }
        let span = &mut self.coverage.spans[piece];
        span.0 = span.0.min(omega).max(self.spec.omega_from);
        span.1 = span.1.max(omega).min(self.spec.omega_to);
        let ahead = match self.piece.dir {
            Direction::Up => omega > self.piece.frontier,
            Direction::Down => omega < self.piece.frontier,
        };
        if ahead || self.piece.frontier.is_nan() {
            self.piece.frontier = omega;
            self.piece.since_progress = 0;
        } else {
            self.piece.since_progress += 1;
        }
        let amplitude = inf_norm(&p.coefficients);
        self.queue.push(p);
        if self.finished || !self.started {
            return Ok(());
        }
        if amplitude > self.piece.divergence {
            return self.end_piece(PieceEnd::Diverged, omega);
        }
        if self.piece.since_progress > self.stall_window() {
            return self.end_piece(PieceEnd::Stalled, omega);
        }
        if self.piece.index > 0 && self.coverage_gaps().is_empty() {
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
        self.resolve_stability();
        self.started = false;
        let tol = 1e-9 * (self.spec.omega_to - self.spec.omega_from);
        // A gap in which (or at whose edge) a restart already began, and
        // that pieces from both sides could not cross: left out, reported.
        loop {
            let gaps = self.coverage_gaps();
            let tried = gaps.iter().copied().find(|g| {
                let down_pending = self.coverage.restarts.last().is_some_and(|r| {
                    r.piece >= 2
                        && r.direction == Direction::Up
                        && (g.1 - r.start_omega).abs() <= tol
                });
                let inside = |w: f64| g.0 - tol <= w && w <= g.1 + tol;
                let failed = self
                    .coverage
                    .failed_starts
                    .iter()
                    .filter(|&&w| inside(w))
                    .count();
                !down_pending
                    && (failed >= GAP_STARTS.len()
                        || self
                            .coverage
                            .restarts
                            .iter()
                            .any(|r| r.piece >= 2 && inside(r.start_omega)))
            });
            match tried {
                Some(g) => self.coverage.left_out.push(LeftOut {
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
        if !self.coverage.restarts_allowed || self.coverage.restarts.len() >= MAX_RESTARTS {
            self.finished = true;
            return match how {
                PieceEnd::TurnedBack | PieceEnd::Reached => {
                    self.coverage.left_at_start = how == PieceEnd::TurnedBack;
                    Ok(())
                }
                PieceEnd::Diverged
                | PieceEnd::Stalled
                | PieceEnd::Failed
                | PieceEnd::PointLimit => Err(SolverError::ContinuationStalled {
                    omega: stopped_at,
                    points: self.stats.points + self.queue.len() as u64,
                }),
            };
        }
        // First from the other end, backward; then from the middle of the
        // first gap, upward, and from the same start downward if the gap
        // below it remains.
        let down_again = self.coverage.restarts.last().and_then(|r| {
            let below = gaps.iter().any(|g| (g.1 - r.start_omega).abs() <= tol);
            (r.piece >= 2 && r.direction == Direction::Up && below).then_some(r.start_omega)
        });
        let (start_omega, dir) = if self.coverage.restarts.is_empty() {
            match self.spec.direction {
                Direction::Up => (self.spec.omega_to, Direction::Down),
                Direction::Down => (self.spec.omega_from, Direction::Up),
            }
        } else if let Some(omega) = down_again {
            (omega, Direction::Down)
        } else {
            let (a, b) = gaps[0];
            let failed = self
                .coverage
                .failed_starts
                .iter()
                .filter(|&&w| a - tol <= w && w <= b + tol)
                .count();
            let frac = GAP_STARTS[failed.min(GAP_STARTS.len() - 1)];
            (a + frac * (b - a), Direction::Up)
        };
        self.piece.index += 1;
        self.coverage.restarts.push(Restart {
            piece: self.piece.index,
            reason: how,
            stopped_at,
            start_omega,
            direction: dir,
        });
        self.piece.dir = dir;
        self.piece.start_omega = start_omega;
        self.stability.prev_stable = None;
        self.stability.prev_multipliers.clear();
        self.stability.since_fold = u32::MAX;
        self.stability.pending_fold = false;
        self.cursor.ds = self.cursor.ds_max;
        self.cursor.prev_y = None;
        self.piece.frontier = f64::NAN;
        self.piece.since_progress = 0;
        Ok(())
    }
}

/// Samples per period used to find the extremes of a reconstructed orbit.
fn recon_samples(h: usize) -> usize {
    256.max(16 * harmonic::n_coef(h))
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
