//! Damped Newton on `P^n(z) - z = 0` with a backtracking line search and
//! Broyden updates of the Newton matrix.
//!
//! The first iterate evaluates `P^n` and its monodromy `Phi` together
//! ([`super::variational`]); the Newton step solves `J dz = -F` with
//! `J = Phi - I`. A trial point `z + alpha dz` is accepted when its
//! residual meets the tolerance or has fallen by the Armijo factor
//! `1 - 1e-4 alpha` in the 2-norm; otherwise `alpha` is halved (a trial
//! whose integration fails, say by leaving the bounded range, counts as not
//! accepted), down to 1/64.
//!
//! Trials integrate the orbit alone: after an accepted step `s` with the
//! residual's change `y`, the Newton matrix takes Broyden's rank-one update
//! `J += (y - J s) s^T / (s^T s)` instead of a new monodromy, so an
//! iteration costs one plain integration of `n` periods instead of one with
//! the `2m` tangent vectors alongside (about ten times the work). Where the
//! line search fails or the matrix is singular with an updated `J`, the
//! monodromy is integrated afresh at the current iterate and the step
//! retried; with a fresh one the attempt is given up. Once the residual
//! meets the tolerance, the monodromy is integrated at the converged orbit
//! itself, so its Floquet multipliers (and the orbit's stability) are
//! exact, not the update's estimate. [`ShootOptions::broyden`] off, every
//! iterate integrates the tangents (plain Newton).
//!
//! A converged period-n orbit may repeat sooner: a period-1 orbit is a
//! fixed point of `P^3` too, and the pipeline shoots for the period its
//! loose test read off a transient. Before its monodromy is taken, the
//! orbit is checked after each proper divisor `d` of `n` (one plain
//! integration of `d` periods each); where it repeats, the orbit is of
//! period `d` and its monodromy is integrated over `d` periods. Otherwise
//! its multipliers would be the `n/d`-th powers of its own: a period-1
//! orbit with largest multiplier 0.964 reported as 0.895 (`0.964^3`), and a
//! multiplier near -1 (a period doubling) read as one near +1 (a fold).
//!
//! The monodromy that only steers Newton may be integrated at looser
//! tolerances ([`ShootOptions::jacobian_tol`]): the residual, and so the
//! orbit, is always evaluated at the attempt's own.
//!
//! Convergence: the residual's size in mesh space (every mesh's deflection
//! and rate over omega, µm) at most `tol_abs_um + tol_rel` times the
//! orbit's own size there. For a linear system (no backlash) `P^n` is
//! affine, its monodromy is exact to the integrator's accuracy, and the
//! first step lands on the orbit.
//!
//! [`ShootRun`] is resumable at the integrator's step: a caller gives it at
//! most `k` steps per call and any slicing computes the same bits.

use super::floquet::Multipliers;
use super::variational::{MapRun, MapValue};
use super::Reduced;
use crate::dynamics::MeshOde;
use crate::error::{Result, SolverError};
use crate::ode::Tolerances;
use crate::Model;
use nalgebra::{DMatrix, DVector};

/// Options of a shooting attempt.
#[derive(Debug, Clone, PartialEq)]
pub struct ShootOptions {
    /// The orbit's period in mesh periods, n.
    pub period: u32,
    /// Newton iterations allowed.
    pub max_iterations: u32,
    /// Relative tolerance of the integrator.
    pub rtol: f64,
    /// Absolute tolerance of the integrator, as a mesh deflection (m).
    pub atol_m: f64,
    /// Residual tolerance relative to the orbit's size in mesh space.
    pub tol_rel: f64,
    /// Absolute residual tolerance (µm).
    pub tol_abs_um: f64,
    /// Step budget per mesh period of one evaluation.
    pub max_steps_per_period: u64,
    /// Broyden updates of the Newton matrix between steps (see the module
    /// doc); off, the monodromy is integrated at every iterate.
    pub broyden: bool,
    /// The integrator's relative tolerance and absolute one (m) for the
    /// monodromy that only steers Newton (`None`: `rtol` and `atol_m`).
    /// The converged orbit's monodromy always uses `rtol` and `atol_m`.
    pub jacobian_tol: Option<(f64, f64)>,
    /// The tangent vectors' absolute tolerance as a fraction of the
    /// orbit's (0 < scale <= 1). The tangents start at 1 µm of mesh
    /// deflection, a hundredth of a loaded mesh's, so at 1 they are
    /// integrated about a hundred times less accurately, relative to their
    /// size, than the orbit: enough for the multipliers near the unit
    /// circle (which decide stability), not for the small ones. At 1e-2
    /// the small ones follow too (Liouville's formula holds to 1e-8 at
    /// rtol 1e-12), for about 1.7 times the monodromy's steps.
    pub tangent_atol_scale: f64,
}

/// Largest orbit period shooting accepts (the same as the period detection's).
pub(crate) const MAX_SHOOT_PERIOD: u32 = 32;

impl ShootOptions {
    /// Defaults for a period-`period` orbit: 16 iterations, integrator at
    /// rtol 1e-11 and 1e-14 m, residual below 1e-8 of the orbit's size plus
    /// 1e-7 µm (the integration's own noise in the map is about 1e-9 of the
    /// orbit's size at these tolerances, measured on the linear compound set).
    pub fn new(period: u32) -> Self {
        ShootOptions {
            period,
            max_iterations: 16,
            rtol: 1e-11,
            atol_m: 1e-14,
            tol_rel: 1e-8,
            tol_abs_um: 1e-7,
            max_steps_per_period: 200_000,
            broyden: true,
            jacobian_tol: None,
            tangent_atol_scale: 1.0,
        }
    }

    /// Checks the options' ranges.
    pub fn validate(&self) -> Result<()> {
        if self.period == 0 || self.period > MAX_SHOOT_PERIOD {
            return SolverError::bad_option(
                "period",
                self.period.to_string(),
                &format!("1 ..= {MAX_SHOOT_PERIOD}"),
            );
        }
        if self.max_iterations == 0 || self.max_iterations > 200 {
            return SolverError::bad_option(
                "max-iterations",
                self.max_iterations.to_string(),
                "1 ..= 200",
            );
        }
        if !(self.rtol.is_finite() && (1e-13..=1e-5).contains(&self.rtol)) {
            return SolverError::bad_option("rtol", format!("{}", self.rtol), "1e-13 ..= 1e-5");
        }
        if !(self.atol_m.is_finite() && self.atol_m > 0.0 && self.atol_m <= 1e-8) {
            return SolverError::bad_option(
                "atol",
                format!("{}", self.atol_m),
                "0 < atol <= 1e-8 m",
            );
        }
        if let Some((rtol, atol_m)) = self.jacobian_tol {
            if !(rtol.is_finite() && (1e-13..=1e-3).contains(&rtol)) {
                return SolverError::bad_option(
                    "jacobian rtol",
                    format!("{rtol}"),
                    "1e-13 ..= 1e-3",
                );
            }
            if !(atol_m.is_finite() && atol_m > 0.0 && atol_m <= 1e-6) {
                return SolverError::bad_option(
                    "jacobian atol",
                    format!("{atol_m}"),
                    "0 < atol <= 1e-6 m",
                );
            }
        }
        let scale = self.tangent_atol_scale;
        if !(scale.is_finite() && scale > 0.0 && scale <= 1.0) {
            return SolverError::bad_option(
                "tangent atol scale",
                format!("{scale}"),
                "0 < scale <= 1",
            );
        }
        Ok(())
    }
}

/// A converged periodic orbit.
#[derive(Debug, Clone, PartialEq)]
pub struct Orbit {
    /// Dimensionless frequency.
    pub omega: f64,
    /// Period in mesh periods.
    pub period: u32,
    /// The orbit's point at phase 0 in reduced coordinates.
    pub z: Vec<f64>,
    /// The same as a full state `(q, q')`, with the start's rigid-body part.
    pub start_state: Vec<f64>,
    /// The monodromy `dP^n/dz` at the orbit.
    pub monodromy: DMatrix<f64>,
    /// Its Floquet multipliers (`None` if the eigenvalues failed).
    pub multipliers: Option<Multipliers>,
    /// The final residual's size in mesh space (µm).
    pub residual_um: f64,
    /// Newton steps taken.
    pub iterations: u32,
    /// Integrator steps over all evaluations.
    pub steps: u64,
}

impl Orbit {
    /// The largest multiplier's modulus (infinity if the eigenvalues failed).
    pub fn max_multiplier_modulus(&self) -> f64 {
        self.multipliers
            .as_ref()
            .map_or(f64::INFINITY, Multipliers::max_modulus)
    }

    /// Stable: every multiplier inside the unit circle.
    pub fn is_stable(&self) -> bool {
        self.multipliers
            .as_ref()
            .is_some_and(Multipliers::is_stable)
    }
}

/// A shooting attempt that did not converge, and why.
#[derive(Debug, Clone, PartialEq)]
pub struct ShootFailure {
    /// Period tried.
    pub period: u32,
    /// Newton steps taken.
    pub iterations: u32,
    /// The last accepted residual's size in mesh space (µm; infinity if none).
    pub residual_um: f64,
    /// The reason in words.
    pub reason: String,
    /// Integrator steps over all evaluations.
    pub steps: u64,
}

/// The end of a shooting attempt.
#[derive(Debug, Clone, PartialEq)]
pub enum ShootOutcome {
    /// Newton converged.
    Converged(Box<Orbit>),
    /// It did not; the orbit is not known.
    Failed(ShootFailure),
}

/// Which evaluation is in progress.
#[derive(Debug, Clone, Copy, PartialEq)]
enum Stage {
    /// The residual at the current iterate (with the monodromy where it
    /// can share the integration).
    Base,
    /// The monodromy at the current iterate, for the Newton matrix.
    Jacobian,
    /// The residual at `z + alpha dz`.
    Trial { alpha: f64 },
    /// At the converged orbit, whether it repeats after `d` mesh periods,
    /// a proper divisor of the period shot for.
    Divisor { d: u32 },
    /// The monodromy at the converged orbit.
    Final,
}

/// The residual's ratio over an accepted step above which the Newton
/// matrix is integrated afresh rather than updated.
const SLOW_STEP: f64 = 0.5;

/// How far (in residual tolerances) the converged orbit may miss its
/// start after a proper divisor `d` of the period shot for and still count
/// as repeating after `d` periods. A period-n orbit that is not of period d
/// misses by its own size, far more; one that is, by about the Newton
/// error, which the n-period residual bounds only up to `|1 - mu|` factors.
const DIVISOR_SLACK: f64 = 10.0;

/// Smallest line-search factor tried.
const ALPHA_MIN: f64 = 1.0 / 64.0;

/// A shooting attempt that can pause and resume (see the module doc).
#[derive(Debug, Clone)]
pub(crate) struct ShootRun {
    opts: ShootOptions,
    omega: f64,
    red: Reduced,
    ode: MeshOde,
    tol: Tolerances,
    /// The tolerances of [`Stage::Jacobian`].
    jac_tol: Tolerances,
    bound_m: f64,
    rigid: (f64, f64),
    z: Vec<f64>,
    /// Residual at `z`, once evaluated.
    f: Vec<f64>,
    /// The Newton matrix `J` (`Phi - I`, or its Broyden update) and whether
    /// it was integrated at `z` itself.
    jac: DMatrix<f64>,
    jac_fresh: bool,
    res_um: f64,
    dz: Vec<f64>,
    iterations: u32,
    steps: u64,
    stage: Stage,
    eval: Option<Box<MapRun>>,
    done: bool,
}

impl ShootRun {
    /// An attempt at dimensionless frequency `omega` from full state `start`
    /// (taken at phase 0).
    pub fn new(model: &Model, omega: f64, start: &[f64], opts: &ShootOptions) -> Result<Self> {
        opts.validate()?;
        let sys = &model.system;
        if start.len() != 2 * sys.dof() || start.iter().any(|v| !v.is_finite()) {
            return SolverError::bad_option(
                "start",
                format!("{} values", start.len()),
                &format!("{} finite values", 2 * sys.dof()),
            );
        }
        let red = Reduced::new(model, omega);
        let ode = MeshOde::new(sys, red.omega_rad_s);
        let tol =
            crate::dynamics::tolerances(sys, omega, opts.rtol, opts.atol_m, red.period_s, 1e-14);
        let jac_tol = match opts.jacobian_tol {
            Some((rtol, atol_m)) => {
                crate::dynamics::tolerances(sys, omega, rtol, atol_m, red.period_s, 1e-14)
            }
            None => tol.clone(),
        };
        let (z, rigid) = red.from_state(start);
        Ok(ShootRun {
            opts: opts.clone(),
            omega,
            ode,
            tol,
            jac_tol,
            bound_m: model.divergence_bound_m(),
            rigid,
            f: Vec::new(),
            jac: DMatrix::zeros(0, 0),
            jac_fresh: false,
            res_um: f64::INFINITY,
            dz: Vec::new(),
            iterations: 0,
            steps: 0,
            stage: Stage::Base,
            eval: None,
            done: false,
            z,
            red,
        })
    }

    /// Integrator steps so far.
    pub fn steps(&self) -> u64 {
        self.steps
    }

    /// Continues for at most `max_steps` integrator steps (at least one):
    /// `Ok(Some(outcome))` at the end, `Ok(None)` if paused; afterwards
    /// `Ok(None)` without work.
    pub fn advance(&mut self, max_steps: u64) -> Result<Option<ShootOutcome>> {
        if self.done {
            return Ok(None);
        }
        let out = self.advance_inner(max_steps.max(1));
        if !matches!(out, Ok(None)) {
            self.done = true;
        }
        out
    }

    fn point(&self, alpha: f64) -> Vec<f64> {
        if alpha == 0.0 {
            return self.z.clone();
        }
        self.z
            .iter()
            .zip(&self.dz)
            .map(|(z, d)| z + alpha * d)
            .collect()
    }

    fn fail(&self, reason: String) -> ShootOutcome {
        ShootOutcome::Failed(ShootFailure {
            period: self.opts.period,
            iterations: self.iterations,
            residual_um: self.res_um,
            reason,
            steps: self.steps,
        })
    }

    fn tolerance_um(&self, z: &[f64]) -> f64 {
        self.opts.tol_abs_um + self.opts.tol_rel * self.red.mesh_norm_um(z)
    }

    /// Whether the base evaluation carries the tangents: when the Newton
    /// matrix is integrated at the attempt's own tolerances anyway.
    fn base_has_tangents(&self) -> bool {
        self.opts.jacobian_tol.is_none()
    }

    fn advance_inner(&mut self, max_steps: u64) -> Result<Option<ShootOutcome>> {
        let mut taken = 0u64;
        loop {
            let (alpha, tangents, tol) = match self.stage {
                Stage::Base => (0.0, self.base_has_tangents(), &self.tol),
                Stage::Jacobian => (0.0, true, &self.jac_tol),
                Stage::Trial { alpha } => (alpha, !self.opts.broyden, &self.tol),
                Stage::Divisor { .. } => (0.0, false, &self.tol),
                Stage::Final => (0.0, true, &self.tol),
            };
            let zt = self.point(alpha);
            // The monodromy that only steers Newton at its own tolerances
            // needs no accurate small multipliers.
            let scale = match (self.stage, self.opts.jacobian_tol) {
                (Stage::Jacobian, Some(_)) => 1.0,
                _ => self.opts.tangent_atol_scale,
            };
            if self.eval.is_none() {
                let periods = match self.stage {
                    Stage::Divisor { d } => d,
                    _ => self.opts.period,
                };
                let budget = self
                    .opts
                    .max_steps_per_period
                    .saturating_mul(u64::from(periods));
                self.eval = Some(Box::new(MapRun::new(
                    &self.red,
                    &self.ode,
                    tol,
                    &zt,
                    self.rigid,
                    periods,
                    tangents,
                    scale,
                    self.bound_m,
                    budget,
                )));
            }
            let Some(eval) = self.eval.as_mut() else {
                continue;
            };
            let before = taken;
            let out = eval.advance(&self.red, max_steps - taken.min(max_steps), &mut taken);
            self.steps += taken - before;
            let value = match out {
                Ok(None) => return Ok(None),
                Ok(Some(v)) => Ok(v),
                Err(e) => Err(e),
            };
            self.eval = None;
            let next = match self.stage {
                Stage::Base => match value {
                    Ok(v) => self.accept(zt, v),
                    Err(e) => Some(self.fail(format!(
                        "the first evaluation of the period-{} map failed: {e}",
                        self.opts.period
                    ))),
                },
                Stage::Jacobian => match value {
                    Ok(v) => {
                        self.set_monodromy(v.monodromy);
                        self.newton_direction()
                    }
                    Err(e) => Some(self.fail(format!(
                        "the monodromy of the period-{} map failed: {e}",
                        self.opts.period
                    ))),
                },
                Stage::Divisor { d } => {
                    let repeats = value.is_ok_and(|v| {
                        let f: Vec<f64> = v.z.iter().zip(&zt).map(|(p, z)| p - z).collect();
                        self.red.mesh_norm_um(&f) <= DIVISOR_SLACK * self.tolerance_um(&zt)
                    });
                    if repeats {
                        // The orbit's own period is d: its multipliers are
                        // those of the d-period map, integrated afresh.
                        self.opts.period = d;
                        self.stage = Stage::Final;
                        None
                    } else {
                        self.after_divisor(d)
                    }
                }
                Stage::Final => match value {
                    Ok(v) => Some(self.converged(v.monodromy)),
                    Err(e) => Some(self.fail(format!(
                        "the monodromy at the converged period-{} orbit failed: {e}",
                        self.opts.period
                    ))),
                },
                Stage::Trial { alpha } => {
                    let accepted = match value {
                        Ok(v) => {
                            let f: Vec<f64> = v.z.iter().zip(&zt).map(|(p, z)| p - z).collect();
                            let res = self.red.mesh_norm_um(&f);
                            let n2 = |x: &[f64]| x.iter().map(|v| v * v).sum::<f64>().sqrt();
                            let ok = res <= self.tolerance_um(&zt)
                                || n2(&f) <= (1.0 - 1e-4 * alpha) * n2(&self.f);
                            ok.then_some(v)
                        }
                        Err(_) => None,
                    };
                    match accepted {
                        Some(v) => {
                            self.iterations += 1;
                            self.accept(zt, v)
                        }
                        None if alpha * 0.5 >= ALPHA_MIN => {
                            self.stage = Stage::Trial { alpha: alpha * 0.5 };
                            None
                        }
                        None if !self.jac_fresh => {
                            // The updated matrix may be what misled the step.
                            self.stage = Stage::Jacobian;
                            None
                        }
                        None => Some(self.fail(format!(
                            "the line search found no decrease of the residual ({:.3e} µm) along the Newton step",
                            self.res_um
                        ))),
                    }
                }
            };
            if let Some(outcome) = next {
                return Ok(Some(outcome));
            }
            if taken >= max_steps {
                return Ok(None);
            }
        }
    }

    /// At the converged orbit, after the proper divisors of the period up
    /// to `tried` were found not to repeat it: the next divisor to try, or
    /// the orbit with the monodromy integrated for its period.
    fn after_divisor(&mut self, tried: u32) -> Option<ShootOutcome> {
        let n = self.opts.period;
        if let Some(d) = (tried + 1..n).find(|d| n.is_multiple_of(*d)) {
            self.stage = Stage::Divisor { d };
            return None;
        }
        if self.jac_fresh && self.opts.jacobian_tol.is_none() {
            // The monodromy was integrated here, at the orbit's tolerances.
            let m = self.red.dim();
            let mono = &self.jac + DMatrix::identity(m, m);
            return Some(self.converged(Some(mono)));
        }
        self.stage = Stage::Final;
        None
    }

    /// Takes the monodromy integrated at `z` as the Newton matrix.
    fn set_monodromy(&mut self, monodromy: Option<DMatrix<f64>>) {
        let m = self.red.dim();
        let mono = monodromy.unwrap_or_else(|| DMatrix::zeros(m, m));
        self.jac = mono - DMatrix::identity(m, m);
        self.jac_fresh = true;
    }

    /// The converged orbit at `z`, with the monodromy integrated there.
    fn converged(&self, monodromy: Option<DMatrix<f64>>) -> ShootOutcome {
        let m = self.red.dim();
        let monodromy = monodromy.unwrap_or_else(|| DMatrix::zeros(m, m));
        ShootOutcome::Converged(Box::new(Orbit {
            omega: self.omega,
            period: self.opts.period,
            z: self.z.clone(),
            start_state: self.red.to_state(&self.z, self.rigid),
            multipliers: Multipliers::of(&monodromy),
            monodromy,
            residual_um: self.res_um,
            iterations: self.iterations,
            steps: self.steps,
        }))
    }

    /// Takes `zt` with its map value as the new iterate: converged, or the
    /// next Newton direction (or a failure).
    fn accept(&mut self, zt: Vec<f64>, v: MapValue) -> Option<ShootOutcome> {
        let f: Vec<f64> = v.z.iter().zip(&zt).map(|(p, z)| p - z).collect();
        let first = self.f.is_empty();
        let n2 = |x: &[f64]| x.iter().map(|v| v * v).sum::<f64>().sqrt();
        // A step that did not halve the residual: the updated matrix is
        // not steering well, and the next one is integrated afresh.
        let slow = !first && n2(&f) > SLOW_STEP * n2(&self.f);
        if v.monodromy.is_some() {
            self.set_monodromy(v.monodromy);
        } else if !first {
            // Broyden's update from the step just taken.
            let s = DVector::from_iterator(zt.len(), zt.iter().zip(&self.z).map(|(a, b)| a - b));
            let y = DVector::from_iterator(f.len(), f.iter().zip(&self.f).map(|(a, b)| a - b));
            let ss = s.dot(&s);
            if ss > 0.0 {
                let r = y - &self.jac * &s;
                self.jac += r * s.transpose() / ss;
            }
            self.jac_fresh = false;
        }
        self.res_um = self.red.mesh_norm_um(&f);
        self.z = zt;
        self.f = f;
        if self.res_um <= self.tolerance_um(&self.z) {
            return self.after_divisor(0);
        }
        if self.iterations >= self.opts.max_iterations {
            return Some(self.fail(format!(
                "Newton did not converge in {} iterations (residual {:.3e} µm)",
                self.iterations, self.res_um
            )));
        }
        if (first || slow) && !self.jac_fresh {
            self.stage = Stage::Jacobian;
            return None;
        }
        self.newton_direction()
    }

    /// The Newton step from `z` with the current matrix, or a refresh of a
    /// singular updated matrix, or a failure on a singular fresh one.
    fn newton_direction(&mut self) -> Option<ShootOutcome> {
        let rhs = -DVector::from_column_slice(&self.f);
        match crate::dense::Lu::new(self.jac.clone()).solve(&rhs) {
            Some(dz) if dz.iter().all(|x| x.is_finite()) => {
                self.dz = dz.iter().copied().collect();
                self.stage = Stage::Trial { alpha: 1.0 };
                None
            }
            _ if !self.jac_fresh => {
                self.stage = Stage::Jacobian;
                None
            }
            _ => Some(
                self.fail(
                    "the Newton matrix is singular (a multiplier at 1: a fold or a branch point)"
                        .to_string(),
                ),
            ),
        }
    }
}

/// Shoots for a period-`opts.period` orbit at `omega` from `start`: the
/// one-shot form of [`ShootRun`].
pub fn shoot(
    model: &Model,
    omega: f64,
    start: &[f64],
    opts: &ShootOptions,
) -> Result<ShootOutcome> {
    let mut run = ShootRun::new(model, omega, start, opts)?;
    loop {
        if let Some(out) = run.advance(u64::MAX)? {
            return Ok(out);
        }
    }
}
