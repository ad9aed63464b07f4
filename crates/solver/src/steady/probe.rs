//! Evidence for motion that is not periodic, measured alongside the run:
//! the largest Lyapunov exponent of the Poincaré map by Benettin's
//! two-trajectory scheme (as [`crate::lyapunov`], whose neighbour and
//! mesh-space metric it shares), a neighbour integrated beside the run's own
//! trajectory and pulled back to `d0` after every period.
//!
//! When the steady run finds no periodic orbit by shooting at a checkpoint,
//! it starts recording at once with this probe beside it. After each
//! measured period the probe decides, at [`DECIDE_AT`] periods: the motion
//! is chaotic when the exponent (the mean of the per-period logarithms after
//! the first [`SKIP`], which turn the separation into the leading
//! direction) is at least [`LAMBDA_MIN`] per period and positive at 95 %
//! one-sided confidence (Student's t over the four quarters' means of the
//! measurement, which are nearly independent where the motion mixes in a
//! few periods, as chaos does), and the growth is sustained: the exponent
//! over the window's second half at least [`SUSTAINED`] of the first
//! half's, which tells exponential separation from separation growing
//! like a power of time (the finite-time exponent of `d ~ k^p` is
//! `p ln k / k`, positive over any finite window but fading). It is not chaos (and the run goes back to
//! its transient, looking for a candidate period at once) when the
//! exponent is negative or below `LAMBDA_MIN` at the same confidence, or when the last
//! decision point passes without a verdict.
//!
//! The separation `d0` is 0.01 µm: a hundred times the integrator's
//! absolute tolerance on a deflection (0.1 nm), so that its error is a
//! small part of each logarithm, and far below the backlash and the
//! transmission error, so that the separation grows as a tangent vector
//! does over one period.

use crate::dynamics::MeshOde;
use crate::error::{Result, SolverError};
use crate::ode::{Dopri5, Tolerances};
use crate::separation::{dist2, mesh_point, neighbour, Rigid};
use crate::Model;

/// Separation of the neighbour in mesh space (µm).
pub(crate) const PROBE_SEPARATION_UM: f64 = 0.1;

/// How much looser the neighbour's tolerances are than the run's.
pub(crate) const NEIGHBOUR_LOOSER: f64 = 10.0;

/// First measured periods left out of the mean.
pub(crate) const SKIP: usize = 2;

/// Measured periods at which the probe decides.
pub const DECIDE_AT: &[usize] = &[16, 24, 32, 48, 64];

/// The smallest exponent per period called chaotic.
pub const LAMBDA_MIN: f64 = 0.05;

/// The smallest ratio of the second half's exponent to the first half's
/// for growth to count as exponential (see [`decide`]).
pub(crate) const SUSTAINED: f64 = 0.5;

/// What the probe found.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct LyapunovEvidence {
    /// Largest exponent of the Poincaré map per mesh period.
    pub per_period: f64,
    /// Periods it was measured over.
    pub periods: u32,
    /// Whether it is positive by the probe's test (see the module's doc).
    pub chaotic: bool,
}

impl LyapunovEvidence {
    /// The evidence in words, e.g. "largest Lyapunov exponent 0.280 per
    /// period over 24 periods: chaotic".
    pub fn words(&self) -> String {
        let kind = if self.chaotic {
            "chaotic"
        } else if self.per_period >= LAMBDA_MIN {
            "undecided (the separation grew, but not at a steady exponential rate)"
        } else if self.per_period > -LAMBDA_MIN {
            "quasi-periodic or near a bifurcation"
        } else {
            "contracting"
        };
        format!(
            "largest Lyapunov exponent {:.3} per period over {} periods: {kind}",
            self.per_period, self.periods
        )
    }
}

/// The neighbour trajectory and the logarithms so far.
#[derive(Debug, Clone)]
pub(super) struct Probe {
    ode: MeshOde,
    int: Dopri5,
    tol: Tolerances,
    rigid: Option<Rigid>,
    logs: Vec<f64>,
    pa: Vec<f64>,
    pb: Vec<f64>,
}

impl Probe {
    /// A neighbour of the state `y` at time `t` of the run.
    pub(super) fn new(
        model: &Model,
        main: &MeshOde,
        t: f64,
        y: &[f64],
        tol: &Tolerances,
    ) -> Result<Self> {
        let rigid = Rigid::of(model);
        let y1 = neighbour(model, main, t, y, PROBE_SEPARATION_UM, rigid.as_ref())?;
        let mut ode = main.clone();
        let period = 2.0 * std::f64::consts::PI / main.omega_rad_s();
        let mut tol = tol.clone();
        tol.rtol *= NEIGHBOUR_LOOSER;
        for a in &mut tol.atol {
            *a *= NEIGHBOUR_LOOSER;
        }
        let int = Dopri5::new(&mut ode, t, &y1, period / 200.0, tol.clone());
        Ok(Probe {
            ode,
            int,
            tol,
            rigid,
            logs: Vec::new(),
            pa: Vec::new(),
            pb: Vec::new(),
        })
    }

    /// Integrator steps of the neighbour so far.
    pub(super) fn steps(&self) -> u64 {
        self.int.stats.steps
    }

    /// Takes one step of the neighbour towards `t_end`; `false` once there.
    pub(super) fn step_towards(&mut self, model: &Model, t_end: f64) -> Result<bool> {
        if self.int.t() >= t_end {
            return Ok(false);
        }
        self.int
            .step(&mut self.ode, t_end)
            .map_err(|e| model.explain_failure(&self.ode, &self.int, e))?;
        Ok(true)
    }

    /// Measures the separation from the run's state `y` at the period's end
    /// `t` (where the neighbour is too), pulls the neighbour back and
    /// decides: `Some(evidence)` once decided.
    pub(super) fn measure(
        &mut self,
        main: &MeshOde,
        t: f64,
        y: &[f64],
    ) -> Result<Option<LyapunovEvidence>> {
        let w = main.omega_rad_s();
        mesh_point(main, t, y, w, &mut self.pa);
        mesh_point(&self.ode, t, self.int.y(), w, &mut self.pb);
        let d = dist2(&self.pa, &self.pb);
        if !(d.is_finite() && d > 0.0) {
            return Err(SolverError::NonFinite { t_s: t });
        }
        self.logs.push((d / PROBE_SEPARATION_UM).ln());
        let yb = self.int.y();
        let mut dy: Vec<f64> = y
            .iter()
            .zip(yb)
            .map(|(a, b)| (b - a) * PROBE_SEPARATION_UM / d)
            .collect();
        Rigid::project_out(self.rigid.as_ref(), &mut dy);
        let yb: Vec<f64> = y.iter().zip(&dy).map(|(a, b)| a + b).collect();
        let (h, stats) = (self.int.h(), self.int.stats);
        self.int = Dopri5::new(&mut self.ode, t, &yb, h, self.tol.clone());
        self.int.stats = stats;
        Ok(decide(&self.logs))
    }
}

/// The probe's decision on the logarithms so far (see the module's doc).
pub fn decide(logs: &[f64]) -> Option<LyapunovEvidence> {
    let k = logs.len();
    if !DECIDE_AT.contains(&k) {
        return None;
    }
    let l = &logs[SKIP.min(k)..];
    let mean = |xs: &[f64]| xs.iter().sum::<f64>() / xs.len().max(1) as f64;
    let lambda = mean(l);
    let q = l.len() / 4;
    let quarters: Vec<f64> = (0..4)
        .map(|i| mean(&l[i * l.len() / 4..(i + 1) * l.len() / 4]))
        .collect();
    let qm = mean(&quarters);
    let sd = (quarters.iter().map(|b| (b - qm) * (b - qm)).sum::<f64>() / 3.0).sqrt();
    // One-sided 95 % on the quarters' means: Student's t with 3 degrees
    // of freedom (2.353) times their standard error (sd / 2).
    let margin = 2.353 * sd / 2.0;
    // Sustained growth: the second half's exponent is not much below the
    // first's. A separation growing like a power of time (shear on a torus,
    // a non-normal but bounded linear map) has a finite-time exponent that
    // fades as `p ln k / k`: its second half's is at most 0.38 of its
    // first's (at 16 periods, less later), where chaos keeps its rate.
    let half = l.len() / 2;
    let (first, second) = (mean(&l[..half]), mean(&l[half..]));
    let sustained = second >= LAMBDA_MIN && second >= SUSTAINED * first;
    let chaotic = q > 0 && lambda >= LAMBDA_MIN && lambda > margin && sustained;
    let not_chaotic = q > 0 && (lambda < 0.0 || lambda + margin < LAMBDA_MIN);
    let last = DECIDE_AT.last().is_some_and(|&n| n == k);
    (chaotic || not_chaotic || last).then_some(LyapunovEvidence {
        per_period: lambda,
        periods: k as u32,
        chaotic,
    })
}
