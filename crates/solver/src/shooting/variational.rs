//! The Poincaré map `P^n` and its monodromy, by integrating the
//! variational equations alongside the orbit.
//!
//! The extended state is `(y, Y)`: the orbit `y = (q, q')` and one tangent
//! vector per reduced coordinate, each started at that coordinate's basis
//! vector ([`Reduced::tangent_start`]) and carried by `Y' = A(t, y) Y` with
//! the right-hand side's Jacobian `A` ([`MeshOde::tangent`]). The same
//! DOPRI5 integrator steps both, and the contact switches are events of
//! the orbit part exactly as in a plain run, so every kink of the force law
//! falls on a step boundary and the tangents see a fixed slope inside each
//! step. The mesh force is continuous in the deflection (the dead zone is
//! continuous and the damper has no switch), so the vector field is
//! continuous across a switch, the saltation matrix is the identity, and
//! the monodromy is the product of the pieces' solutions: no jump
//! correction is needed.
//!
//! The tangents start with a mesh-space size of 1 µm, and their absolute
//! tolerances are the orbit's times a scale the caller chooses
//! (`ShootOptions::tangent_atol_scale`).

use super::Reduced;
use crate::dynamics::MeshOde;
use crate::error::{Result, SolverError};
use crate::ode::{Dopri5, Ode, Tolerances};
use nalgebra::DMatrix;

/// The mesh ODE with `cols` tangent vectors integrated alongside.
#[derive(Debug, Clone)]
pub(crate) struct VarOde {
    pub(crate) ode: MeshOde,
    n2: usize,
    cols: usize,
}

impl VarOde {
    pub(crate) fn new(ode: MeshOde, cols: usize) -> Self {
        let n2 = 2 * ode.dof();
        VarOde { ode, n2, cols }
    }
}

impl Ode for VarOde {
    fn dim(&self) -> usize {
        self.n2 * (1 + self.cols)
    }

    fn rhs(&mut self, t: f64, y: &[f64], dy: &mut [f64]) {
        let (ys, zs) = y.split_at(self.n2);
        let (dys, dzs) = dy.split_at_mut(self.n2);
        self.ode.rhs(t, ys, dys);
        if self.cols > 0 {
            self.ode.tangent(t, ys, zs, dzs);
        }
    }

    fn n_events(&self) -> usize {
        self.ode.n_events()
    }

    fn events(&mut self, t: f64, y: &[f64], dy: &[f64], g: &mut [f64], dg: &mut [f64]) {
        self.ode.events(t, &y[..self.n2], &dy[..self.n2], g, dg);
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

    /// The orbit alone: the tangents are read at the steps' ends only.
    fn dense_dim(&self) -> usize {
        self.n2
    }
}

/// One evaluation of `P^n` in progress: an integration from `t = 0` to
/// `n T`, resumable step by step.
#[derive(Debug, Clone)]
pub(crate) struct MapRun {
    var: VarOde,
    int: Dopri5,
    t_end: f64,
    with_monodromy: bool,
    bound_m: f64,
    max_steps: u64,
}

/// What an evaluation of `P^n` returns.
#[derive(Debug, Clone)]
pub(crate) struct MapValue {
    /// `P^n(z)` in reduced coordinates.
    pub(crate) z: Vec<f64>,
    /// The monodromy `dP^n/dz`, if asked for.
    pub(crate) monodromy: Option<DMatrix<f64>>,
}

impl MapRun {
    /// Starts `P^periods` at `z` (rigid-body position and rate `rigid`),
    /// with the monodromy if `with_monodromy`, its tangents at the orbit's
    /// absolute tolerance times `tangent_atol_scale`.
    #[allow(clippy::too_many_arguments)]
    pub(crate) fn new(
        red: &Reduced,
        ode: &MeshOde,
        tol: &Tolerances,
        z: &[f64],
        rigid: (f64, f64),
        periods: u32,
        with_monodromy: bool,
        tangent_atol_scale: f64,
        bound_m: f64,
        max_steps: u64,
    ) -> Self {
        let cols = if with_monodromy { red.dim() } else { 0 };
        let mut var = VarOde::new(ode.clone(), cols);
        let mut y0 = red.to_state(z, rigid);
        let mut atol = tol.atol.clone();
        for k in 0..cols {
            y0.extend(red.tangent_start(k));
            atol.extend(tol.atol.iter().map(|a| a * tangent_atol_scale));
        }
        let t_end = f64::from(periods) * red.period_s;
        let ext = Tolerances {
            rtol: tol.rtol,
            atol,
            h_min: tol.h_min,
            h_max: tol.h_max,
        };
        let int = Dopri5::new(&mut var, 0.0, &y0, red.period_s / 200.0, ext);
        MapRun {
            var,
            int,
            t_end,
            with_monodromy,
            bound_m,
            max_steps,
        }
    }

    /// Takes at most `max_steps` steps; the map's value once it is done.
    pub(crate) fn advance(
        &mut self,
        red: &Reduced,
        max_steps: u64,
        taken: &mut u64,
    ) -> Result<Option<MapValue>> {
        let n2 = red.n2();
        let mut k = 0;
        while self.int.t() < self.t_end {
            if k >= max_steps {
                return Ok(None);
            }
            self.int.step(&mut self.var, self.t_end)?;
            k += 1;
            *taken += 1;
            if self.int.stats.steps > self.max_steps {
                return Err(SolverError::TooManySteps {
                    max_steps: self.max_steps,
                    t_s: self.int.t(),
                });
            }
            let y = &self.int.y()[..n2];
            for j in 0..self.var.ode.n_meshes() {
                let d = self.var.ode.deflection(j, &y[..n2 / 2]);
                if d.abs() > self.bound_m || !d.is_finite() {
                    return Err(SolverError::Diverged {
                        mesh: red.mesh_name(j).to_string(),
                        delta_m: d,
                        bound_m: self.bound_m,
                        t_s: self.int.t(),
                    });
                }
            }
        }
        let y = self.int.y();
        let (z, _) = red.from_state(&y[..n2]);
        let monodromy = self.with_monodromy.then(|| {
            let m = red.dim();
            let mut mon = DMatrix::zeros(m, m);
            for c in 0..m {
                let col = &y[n2 * (1 + c)..n2 * (2 + c)];
                let (zc, _) = red.from_state(col);
                for (r, v) in zc.iter().enumerate() {
                    mon[(r, c)] = *v;
                }
            }
            mon
        });
        Ok(Some(MapValue { z, monodromy }))
    }
}
