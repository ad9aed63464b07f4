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
use crate::ode::Dopri5;
use crate::steady::{steady_state, Model, SteadyOptions};
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

/// Mesh-space coordinates (um) of a state: every mesh's delta and delta'/omega.
fn mesh_point(ode: &MeshOde, t: f64, y: &[f64], omega_rad_s: f64, out: &mut Vec<f64>) {
    out.clear();
    for j in 0..ode.n_meshes() {
        let mi = ode.mesh_instant(j, t, y);
        out.push(mi.delta * 1e6);
        out.push(mi.delta_dot / omega_rad_s * 1e6);
    }
}

fn dist2(a: &[f64], b: &[f64]) -> f64 {
    a.iter()
        .zip(b)
        .map(|(x, y)| (x - y) * (x - y))
        .sum::<f64>()
        .sqrt()
}

/// Computes the largest Lyapunov exponent of the stroboscopic map at
/// `opts.omega`, from `start` (or the static equilibrium).
pub fn largest_exponent(
    model: &Model,
    opts: &LyapunovOptions,
    start: Option<&[f64]>,
) -> Result<Lyapunov> {
    opts.validate()?;
    let sys = &model.system;
    let omega_rad_s = opts.omega * sys.omega_ref_rad_s;
    let period = 2.0 * PI / omega_rad_s;
    // The transient, by the steady-state run (it ends at a whole period).
    let mut so = SteadyOptions::new(opts.omega);
    so.transient_periods = opts.transient_periods;
    so.record_periods = 1;
    so.samples_per_period = 0;
    let ss = steady_state(model, &so, start)?;
    let y0 = ss.end_state;

    let tol = crate::steady::tolerances(sys, opts.omega, opts.rtol, opts.atol_m, period, 1e-14);
    let lengths = sys.dof_length_m();
    let n = y0.len();
    let dof = sys.dof();

    // The neighbour: displaced along a fixed mixed direction (every
    // coordinate, positions and rates), scaled to d0 in mesh space.
    let mut ode_a = MeshOde::new(sys, omega_rad_s);
    let mut ode_b = MeshOde::new(sys, omega_rad_s);
    let mut pa = Vec::new();
    let mut pb = Vec::new();
    mesh_point(&ode_a, 0.0, &y0, omega_rad_s, &mut pa);
    let mut y1 = y0.clone();
    for (i, v) in y1.iter_mut().enumerate() {
        let scale = if i < dof {
            lengths[i]
        } else {
            lengths[i - dof] * omega_rad_s
        };
        *v += scale * 1e-6 * (1.0 + 0.37 * i as f64).sin();
    }
    mesh_point(&ode_b, 0.0, &y1, omega_rad_s, &mut pb);
    let d_init = dist2(&pa, &pb);
    if !(d_init > 0.0 && d_init.is_finite()) {
        return Err(SolverError::Singular {
            what: "Lyapunov: the initial perturbation has no mesh-space component".into(),
        });
    }
    let d0 = opts.perturbation_um;
    for i in 0..n {
        y1[i] = y0[i] + (y1[i] - y0[i]) * d0 / d_init;
    }

    // The free rigid-body rotation: a separation along it is invisible in
    // mesh space and never decays, and the pull-back would inflate it
    // without bound; it is removed (M-orthogonally) at every pull-back.
    let rigid: Option<Vec<f64>> = model
        .modes
        .modes
        .iter()
        .find(|m| m.kind == crate::modal::ModeKind::RigidBody)
        .map(|m| m.shape.clone());
    let project_out_rigid = |dy: &mut [f64]| {
        if let Some(phi) = &rigid {
            let m_phi: Vec<f64> = (0..dof)
                .map(|i| (0..dof).map(|k| sys.mass[(i, k)] * phi[k]).sum())
                .collect();
            let norm: f64 = (0..dof).map(|i| phi[i] * m_phi[i]).sum();
            if norm > 0.0 {
                for half in [0, dof] {
                    let c: f64 = (0..dof).map(|i| m_phi[i] * dy[half + i]).sum::<f64>() / norm;
                    for i in 0..dof {
                        dy[half + i] -= c * phi[i];
                    }
                }
            }
        }
    };
    {
        let mut dy: Vec<f64> = (0..n).map(|i| y1[i] - y0[i]).collect();
        project_out_rigid(&mut dy);
        for i in 0..n {
            y1[i] = y0[i] + dy[i];
        }
    }

    let budget = 200_000u64 * (u64::from(opts.periods) + 1);
    let mut a = Dopri5::new(&mut ode_a, 0.0, &y0, period / 200.0, tol.clone());
    let mut b = Dopri5::new(&mut ode_b, 0.0, &y1, period / 200.0, tol.clone());
    let bound_m = model.divergence_bound_m();
    let mut sum = 0.0;
    let mut running = Vec::with_capacity(opts.periods as usize);
    for p in 1..=opts.periods {
        let t_end = f64::from(p) * period;
        while a.t() < t_end {
            a.step(&mut ode_a, t_end)
                .map_err(|e| model.explain_failure(&ode_a, &a, e))?;
        }
        model.check_bounded(&ode_a, t_end, a.y(), bound_m)?;
        while b.t() < t_end {
            b.step(&mut ode_b, t_end)
                .map_err(|e| model.explain_failure(&ode_b, &b, e))?;
        }
        if a.stats.steps > budget || b.stats.steps > budget {
            return Err(SolverError::TooManySteps {
                max_steps: budget,
                t_s: t_end,
            });
        }
        mesh_point(&ode_a, t_end, a.y(), omega_rad_s, &mut pa);
        mesh_point(&ode_b, t_end, b.y(), omega_rad_s, &mut pb);
        let d = dist2(&pa, &pb);
        if !(d.is_finite() && d > 0.0) {
            return Err(SolverError::NonFinite { t_s: t_end });
        }
        sum += (d / d0).ln();
        running.push(sum / f64::from(p));
        // Pull the neighbour back to d0 along the separation and restart
        // its integrator there.
        let ya = a.y().to_vec();
        let mut dy: Vec<f64> = (0..n).map(|i| (b.y()[i] - ya[i]) * d0 / d).collect();
        project_out_rigid(&mut dy);
        let yb: Vec<f64> = (0..n).map(|i| ya[i] + dy[i]).collect();
        b = Dopri5::new(&mut ode_b, t_end, &yb, b.h(), tol.clone());
    }
    let per_period = sum / f64::from(opts.periods);
    Ok(Lyapunov {
        omega: opts.omega,
        per_period,
        per_s: per_period / period,
        running,
        end_state: a.y().to_vec(),
    })
}
