//! What a continuation is asked for (`FrfSpec`) and what it returns: branch
//! points with their meshes, how each piece ended, the restarts, the work
//! done and the parts of the range left out.

use super::super::assembly::Method;
use crate::error::{Result, SolverError};
use crate::steady::Impact;
use crate::sweep::Direction;
use nalgebra::Complex;

pub use crate::bifurcation::Bifurcation;

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
    /// Compute Floquet stability (every point gets its flag).
    pub stability: bool,
    /// Monodromy on every `stability_stride`-th point only (and the last
    /// of a piece); between two with the same stability the points take
    /// it, a change is located by bisection on the points between. 1: the
    /// monodromy at every point.
    pub stability_stride: u32,
    /// Use the cyclic-symmetry reduction when the planets allow it.
    pub symmetric: bool,
    /// How the continuation chooses its step.
    pub step_control: StepControl,
}

/// The default [`FrfSpec::stability_stride`]: every point, so that every
/// point's flag is its own monodromy's. The sampled route
/// ([`SAMPLED_STABILITY_STRIDE`], `gearshock frf --stability-stride`)
/// gives the benchmark branch (Omega 0.1..0.5, H = 7, 732 points) the same
/// flags and labels with a third of the monodromies, but over Omega
/// 0.1..2 it misses a Neimark-Sacker window two points wide at Omega
/// 0.240 (both samples stable and clear of the unit circle): not a
/// default.
pub(crate) const DEFAULT_STABILITY_STRIDE: u32 = 1;

/// The stride of the sampled stability route that `gearshock bench`
/// measures beside every point.
pub const SAMPLED_STABILITY_STRIDE: u32 = 4;

/// The continuation's step-length control.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum StepControl {
    /// From the curve's geometry (the predictor-corrector distance and the
    /// tangent's turn), folds located by regula falsi; the default.
    Geometry,
    /// From the corrector's iteration count with the arclength step capped
    /// at `1 / points`, folds labelled on the point after them: the simpler
    /// control that `gearshock bench` measures the geometry control against.
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
            stability_stride: DEFAULT_STABILITY_STRIDE,
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
        if self.stability_stride == 0 || self.stability_stride > 64 {
            return bad(
                "stability-stride",
                self.stability_stride.to_string(),
                "1 ..= 64",
            );
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
    /// The corrector failed at the smallest step (or, on a shooting
    /// branch, its tangent was singular).
    Failed,
    /// A shooting branch reached its point limit (a guard against a loop).
    PointLimit,
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
            PieceEnd::PointLimit => "point-limit",
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
            PieceEnd::PointLimit => {
                format!("reached its point limit at Omega {:.4}", self.stopped_at)
            }
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
    /// Monodromy matrices computed (Floquet stability).
    pub monodromies: u64,
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
    /// No piece of a shooting branch got across, and three starts inside
    /// found no first orbit.
    NotFollowed,
    /// A shooting branch's restarts ran out before a piece got there.
    RestartsUsed,
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
            LeftOutReason::NotFollowed => format!(
                "Between Omega {:.5} and {:.5} no piece of the branch got across and no \
                 first orbit was found inside: no point is drawn there; time integration \
                 shows the motion.",
                self.from, self.to
            ),
            LeftOutReason::RestartsUsed => format!(
                "Between Omega {:.5} and {:.5} the branch was not followed: its restarts \
                 ran out before a piece got there; no point is drawn there.",
                self.from, self.to
            ),
        }
    }

    /// Name of the reason for output.
    pub fn reason_name(&self) -> &'static str {
        match self.reason {
            LeftOutReason::Unbounded => "unbounded",
            LeftOutReason::Tangle => "tangle",
            LeftOutReason::NotFollowed => "not-followed",
            LeftOutReason::RestartsUsed => "restarts-used",
        }
    }
}
