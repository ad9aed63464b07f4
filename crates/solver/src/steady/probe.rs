//! Evidence for motion that is not periodic, measured alongside the run:
//! the largest Lyapunov exponent of the Poincaré map, by Benettin's scheme
//! on a tangent vector that the run's own integrator carries beside the
//! state (the variational equations of [`crate::shooting`]'s monodromy,
//! one column), renormalized after every period in [`crate::lyapunov`]'s
//! mesh-space metric.
//!
//! When the steady run finds no periodic orbit by shooting at a checkpoint,
//! it starts recording at once with this probe beside it. After each
//! measured period the probe decides, at [`DECIDE_AT`] periods: the motion
//! is chaotic when the exponent (the mean of the per-period logarithms after
//! the first [`SKIP`], which turn the tangent into the leading direction)
//! is at least [`LAMBDA_MIN`] per period and positive at 95 % one-sided
//! confidence (Student's t over the four quarters' means of the
//! measurement, which are nearly independent where the motion mixes in a
//! few periods, as chaos does). It is not chaos (and the run goes back to
//! its transient, looking for a candidate period at once) when the
//! exponent is negative or below `LAMBDA_MIN` at the same confidence, or
//! when the last decision point passes without a verdict.
//!
//! The tangent is the limit of a neighbour trajectory as its separation
//! goes to zero: the mesh force is continuous in the deflection, so the
//! variational equations hold across the contact switches with no jump
//! (the argument of [`crate::shooting`]), and the switches are events of
//! the state, so each step sees one slope. It rides on the state's steps
//! outside their error control ([`Dopri5::attach_tail`]): the state's
//! trajectory is the same as without the probe, and the tangent costs one
//! Jacobian product per stage instead of a second trajectory with its own
//! steps (about a quarter of the chaotic states' integration before).

use crate::dynamics::MeshOde;
use crate::error::{Result, SolverError};
use crate::ode::{Dopri5, Ode};
use crate::separation::{neighbour, Rigid};
use crate::Model;

/// First measured periods left out of the mean.
pub const SKIP: usize = 2;

/// Measured periods at which the probe decides.
pub const DECIDE_AT: &[usize] = &[16, 24, 32, 48, 64];

/// The smallest exponent per period called chaotic.
pub const LAMBDA_MIN: f64 = 0.05;

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

/// The mesh ODE with one tangent vector after the state: the ODE a run
/// steps with while its probe is on.
pub(super) struct WithTangent<'a> {
    pub(super) ode: &'a mut MeshOde,
}

impl Ode for WithTangent<'_> {
    fn dim(&self) -> usize {
        4 * self.ode.dof()
    }

    fn rhs(&mut self, t: f64, y: &[f64], dy: &mut [f64]) {
        let n2 = 2 * self.ode.dof();
        let (ys, zs) = y.split_at(n2);
        let (dys, dzs) = dy.split_at_mut(n2);
        self.ode.rhs_with_tangent(t, ys, zs, dys, dzs);
    }

    fn n_events(&self) -> usize {
        self.ode.n_events()
    }

    fn events(&mut self, t: f64, y: &[f64], dy: &[f64], g: &mut [f64], dg: &mut [f64]) {
        let n2 = 2 * self.ode.dof();
        self.ode.events(t, &y[..n2], &dy[..n2], g, dg);
    }

    fn event(&mut self, i: usize, t: f64, y: &[f64]) -> f64 {
        self.ode.event(i, t, y)
    }

    fn event_dim(&self) -> usize {
        self.ode.event_dim()
    }

    fn event_components(&self, i: usize) -> Option<&[usize]> {
        self.ode.event_components(i)
    }
}

/// The tangent's size in the mesh-space metric of [`crate::lyapunov`]
/// (each mesh's deflection in µm and its rate over Omega in µm), linear
/// in the tangent because the deflections are.
fn mesh_norm_um(ode: &MeshOde, z: &[f64]) -> f64 {
    let (dq, dv) = z.split_at(ode.dof());
    let w = ode.omega_rad_s();
    (0..ode.n_meshes())
        .map(|j| {
            let a = ode.deflection(j, dq) * 1e6;
            let b = ode.deflection(j, dv) / w * 1e6;
            a * a + b * b
        })
        .sum::<f64>()
        .sqrt()
}

/// The probe's tangent bookkeeping and the logarithms so far.
#[derive(Debug, Clone)]
pub(super) struct Probe {
    rigid: Option<Rigid>,
    logs: Vec<f64>,
    /// Integrator steps taken with the tangent attached.
    steps_from: u64,
}

impl Probe {
    /// Attaches a tangent of unit mesh-space size (1 µm) to the run's
    /// integrator `int` (stepping `main`) at its current state.
    pub(super) fn start(model: &Model, main: &mut MeshOde, int: &mut Dopri5) -> Result<Self> {
        let rigid = Rigid::of(model);
        let (t, y) = (int.t(), int.y());
        let d0 = 1.0;
        let y1 = neighbour(model, main, t, y, d0, rigid.as_ref())?;
        let z: Vec<f64> = y1.iter().zip(y).map(|(b, a)| (b - a) / d0).collect();
        int.attach_tail(&mut WithTangent { ode: main }, &z);
        Ok(Probe {
            rigid,
            logs: Vec::new(),
            steps_from: int.stats.steps,
        })
    }

    /// Integrator steps taken with the tangent attached so far.
    pub(super) fn steps(&self, int: &Dopri5) -> u64 {
        int.stats.steps - self.steps_from
    }

    /// Measures the tangent's growth over the period that ends now,
    /// renormalizes it (without its rigid-body part) and decides:
    /// `Some(evidence)` once decided.
    pub(super) fn measure(
        &mut self,
        main: &mut MeshOde,
        int: &mut Dopri5,
    ) -> Result<Option<LyapunovEvidence>> {
        let d = mesh_norm_um(main, int.tail());
        if !(d.is_finite() && d > 0.0) {
            return Err(SolverError::NonFinite { t_s: int.t() });
        }
        self.logs.push(d.ln());
        let mut z: Vec<f64> = int.tail().iter().map(|v| v / d).collect();
        Rigid::project_out(self.rigid.as_ref(), &mut z);
        int.attach_tail(&mut WithTangent { ode: main }, &z);
        Ok(decide(&self.logs))
    }

    /// Detaches the tangent: the run steps its own ODE again.
    pub(super) fn stop(int: &mut Dopri5) {
        int.detach_tail();
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
    let chaotic = q > 0 && lambda >= LAMBDA_MIN && lambda > margin;
    let not_chaotic = q > 0 && (lambda < 0.0 || lambda + margin < LAMBDA_MIN);
    let last = DECIDE_AT.last().is_some_and(|&n| n == k);
    (chaotic || not_chaotic || last).then_some(LyapunovEvidence {
        per_period: lambda,
        periods: k as u32,
        chaotic,
    })
}
